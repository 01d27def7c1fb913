// SPDX-License-Identifier: MIT
// Tone by stippling (scene "tone", docs/tone.md): dots on the visible surface, denser where it is
// darker, from the same light as the brush.
//
// The dots are points of a nested blue-noise set on the surface (SurfaceSamples,
// core/tone/surface_samples.h): a sample, a face and barycentric coordinates, is drawn where the
// density the tone asks for there is above its rank. A darker tone, or a camera coming closer,
// draws more of the same points, so dots are added and removed without moving the others; a dot
// near its threshold fades in (its area grows) instead of popping. Density is counted per square pixel of
// projected surface, so the tone holds on screen as the camera dollies.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/scene/camera.h"
#include "core/strokes/brush_style.h"
#include "core/tone/surface_samples.h"
#include "core/tone/tone_normals.h"
#include "core/tone/tone_options.h"
#include "core/visibility/visibility.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace inkline::core {

struct Stroke;

// Dots per square pixel that give ink coverage `tone` with dots of radius_px: the inverse of
// the coverage of the nested set's dots, overlaps included (docs/tone.md).
double dot_density(double tone, double radius_px);

struct Dot {
    uint64_t sample = 0;  // the surface sample's id: the same point of the surface in every frame
    uint32_t face = 0;
    glm::dvec3 barycentric{1.0, 0.0, 0.0};
    glm::dvec2 point_px{0.0};
    glm::dvec3 point_world{0.0};
    double radius_px = 0.0;
    double tone = 0.0;  // the tone asked for there
    uint16_t ink = 0;   // index in FrameTone::inks
};

struct StippleStats {
    size_t samples = 0;     // surface samples built so far
    size_t asked = 0;       // about the samples asked for; more than `samples` when max_samples held them back
    size_t considered = 0;  // samples of rank below their face's most density
    size_t wanted = 0;      // front-facing, in the image, asked for by the tone
    size_t inked = 0;       // of those, under a visible stroke's ink (left out)
    size_t occluded = 0;    // of the rest, hidden by the surface
};

// Stipples frame after frame, keeping the surface samples of the mesh.
class Stippler {
  public:
    explicit Stippler(ToneOptions options) : options_(options) {}

    // The dots of one frame: mesh (object space) seen through `projection`, lit by `light`,
    // hidden as `occlusion` says (prepared for this mesh and projection); the ink of `strokes`
    // (visible, drawn) covers dots under it. `normals` are those the light is read from: the
    // mesh's vertex normals (vertex_normals), or its smooth pieces' (tone_normals.h). A new
    // topology (topology_changed) rebuilds the samples. With face_tones, each face is shaded on
    // its own curve, and faces left unshaded get no dots (they still hide them); empty: every face
    // on the options' curve.
    std::vector<Dot> stipple(const Mesh& mesh, const EdgeTable& table, const ToneNormals& normals,
                             const Projection& projection, const Light& light, const Occlusion& occlusion,
                             std::span<const Stroke> strokes, bool topology_changed, FaceTones face_tones = {});

    const ToneOptions& options() const { return options_; }
    // Counts of the last stipple().
    const StippleStats& stats() const { return stats_; }

  private:
    // Builds the samples the faces' limits ask for, level by level while max_samples allows; need
    // gives the most density a face's part in a tile can ask for. Returns the density up to which
    // every face's samples are built (infinity when nothing was held back).
    double build_samples(const Mesh& mesh, const std::function<double(uint32_t, const SurfaceSamples::Part&)>& need);

    ToneOptions options_;
    std::optional<SurfaceSamples> samples_;
    StippleStats stats_;
    // A frame's scratch, kept for the next: per vertex what its faces' limits read of it, per face
    // the most density it can ask for.
    struct VertexView {
        glm::dvec2 px{0.0};
        glm::dvec3 jacobian{0.0};  // the pixel Jacobian's rows, crossed: square pixels per unit area along a normal
        glm::dvec3 to_eye{0.0};    // unit
        bool in_front = false;
    };
    std::vector<VertexView> vertex_view_;
    // Per normal: its light and tone.
    struct NormalTone {
        double tone = 0.0;       // on the options' curve (the darkest without a normal)
        double intensity = NAN;  // of the light, for other curves; NaN without a normal
    };
    std::vector<NormalTone> normal_tone_;
    std::vector<double> face_limit_;  // per face, the most density (samples per unit area) it asks for
    std::vector<double> face_ink_;    // per face, its darkest tone's density per square pixel (with margins)
    // Per face, the last level of the samples built over its whole box (-1: none yet); a face
    // wider than 16 tiles of a level is built tile by tile where the view needs it instead.
    std::vector<int8_t> face_built_;
    bool eager_built_ = false;  // the coarser levels built on the whole surface
    // Per face, the edge its dots' occlusion queries seed their search at, once asked for
    // (kNoIndex before); kept while the topology holds.
    std::vector<uint32_t> face_edge_;
};

}  // namespace inkline::core
