// SPDX-License-Identifier: MIT
// Tone by hatching (scene "tone" with mode hatch or crosshatch, docs/tone.md): lines on the
// visible surface, closer together where it is darker, from the same light as the brush.
//
// The lines of a family are the surface's sections by parallel planes across an object-space
// direction, taken on the mesh as first seen (its rest shape), so they stay on the same points of
// the surface as it moves or deforms. The planes are nested: level 0 has planes half the mesh's
// extent apart, each later level adds the planes halfway between. Where the tone asks for lines
// of screen spacing s, the levels up to the one that spacing needs are drawn and the finest of
// them fades in (its width grows), so a darker tone or a closer camera adds lines between the
// others, never moving them. Crosshatch adds a second family once the tone passes cross_from.
// In screen space (ToneOptions::space) the planes are across an angle on the image instead: each
// line is straight on the page, through the points of the surface whose images lie on it.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/scene/camera.h"
#include "core/strokes/brush_style.h"
#include "core/strokes/outline.h"
#include "core/tone/tone_normals.h"
#include "core/tone/tone_options.h"
#include "core/visibility/visibility.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

struct Stroke;

// One visible run of a hatch line.
struct Hatch {
    uint32_t family = 0;  // 0: across ToneOptions::direction, 1: across cross_direction
    // Its plane, counted at the finest spacing from the family's first plane: the same curve on
    // the surface in every frame.
    uint64_t plane = 0;
    uint32_t level = 0;                    // the level that plane belongs to (0: the coarsest)
    // Where the line crosses mesh edges, and between them where it crosses a face that is long
    // on the image (every few px), px.
    std::vector<glm::dvec2> points_px;
    std::vector<glm::dvec3> points_world;
    std::vector<uint32_t> edges;           // the mesh edge of each point; inside a face, the face's first edge
    std::vector<uint32_t> faces;           // the face of the line up to each point (inside a face: that face)
    std::vector<double> width_px;          // its width at each point (faded in: less than line_width_px)
    std::vector<Ring> outline;             // the ink: one ring, filled (nonzero), ends cut square
    uint16_t ink = 0;                      // index in FrameTone::inks
};

struct HatchStats {
    size_t faces = 0;     // front-facing faces whose lines were traced
    size_t segments = 0;  // line segments traced (one per face a line crosses)
    size_t points = 0;    // of which points tested for occlusion
    size_t occluded = 0;
    size_t inked = 0;     // points under a visible stroke's ink

    HatchStats& operator+=(const HatchStats& other) {
        faces += other.faces, segments += other.segments, points += other.points;
        occluded += other.occluded, inked += other.inked;
        return *this;
    }
};

// Hatches frame after frame, keeping each family's planes on the rest shape.
class Hatcher {
  public:
    explicit Hatcher(ToneOptions options) : options_(options) {}

    // The hatches of one frame, as Stippler::stipple takes its arguments (face_tones too).
    std::vector<Hatch> hatch(const Mesh& mesh, const EdgeTable& table, const ToneNormals& normals,
                             const Projection& projection, const Light& light, const Occlusion& occlusion,
                             std::span<const Stroke> strokes, bool topology_changed, FaceTones face_tones = {});

    const HatchStats& stats() const { return stats_; }

  private:
    struct Family {
        // Per vertex: the rest position along the family's direction; in screen space, this
        // frame's image position across the lines (px).
        std::vector<float> h;
        double first = 0.0;  // the first plane
        double step0 = 1.0;  // spacing of level 0's planes
        glm::dvec2 across{0.0};  // screen space: the unit normal of the lines on the image
    };

    ToneOptions options_;
    std::vector<Family> families_;
    std::vector<glm::uvec3> face_edges_;  // per face, the edge of each side (face_edges), with families_
    size_t faces_ = 0;
    HatchStats stats_;
    // A frame's scratch, kept for the next: per normal its tone and its light's intensity, per
    // vertex its clip coordinates.
    std::vector<double> normal_tone_, normal_intensity_;
    std::vector<glm::dvec4> vertex_clip_;
};

}  // namespace inkline::core
