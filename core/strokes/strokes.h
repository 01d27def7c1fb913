// SPDX-License-Identifier: MIT
// Brush strokes of one frame: the visible polylines made into pure strokes (pure_strokes.h),
// repaired where visibility flickers (occluded_gaps.h), given stable ids and a propagated
// arc-length parameter u (stroke_coherence.h), a light-weighted width with tapered ends
// (brush.h) and a filled outline (outline.h). build_strokes() is the single entry point;
// StrokeCoherence carries frame to frame.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_lines.h"
#include "core/scene/camera.h"
#include "core/strokes/brush.h"
#include "core/strokes/brush_style.h"
#include "core/strokes/line_styles.h"
#include "core/strokes/outline.h"
#include "core/strokes/stroke_coherence.h"
#include "core/strokes/stroke_geometry.h"

namespace inkline::core {

struct Stroke {
    uint32_t id = 0;  // stable across frames; unique within a frame
    // The exact geometry, in drawing direction; a loop starts where u = 0. Bridged segments are
    // marked only where there are any (geometry.bridged is empty otherwise).
    StrokeGeometry geometry;
    bool drawn = true;  // false when shorter than min_length_px: kept in the data, no outline
    uint32_t style = 0;  // index into FrameStrokes::styles

    // Per exact point of geometry.
    std::vector<double> u;          // arc-length parameter, px, carried between frames
    std::vector<double> intensity;  // light intensity in [0, 1], smoothed along u
    std::vector<double> width;      // brush width, px

    // The drawn centerline (cleaned, smoothed within max_deviation_px, resampled).
    std::vector<glm::dvec2> centerline_px;
    std::vector<double> centerline_u;
    std::vector<double> centerline_width;  // px
    // One ring, or outer and inner for a loop (nonzero fill); a dashed stroke has one ring per
    // dash or dot. With brush.texture, holes follow: rings the other way round.
    std::vector<Ring> outline;

    // With brush.texture: how much darker the ink is drawn for the brush's pressure, in [0, 1]
    // (core/strokes/brush_texture.h); 0 otherwise.
    double darkening = 0.0;

    // Drawing order (core/strokes/drawing_order.h; set by DrawingOrder::assign, which the frame
    // pipeline runs): the group (the id of its main stroke), the level in the group's hierarchy
    // (0: the main stroke), the stroke it hangs from (-1 at level 0), the place in the frame's
    // drawing order.
    uint32_t group = 0;
    uint32_t level = 0;
    int64_t parent = -1;
    uint32_t order = 0;

    double deviation_px = 0.0;  // largest distance of the drawn centerline from the exact points
    double removed_px = 0.0;    // largest distance of an exact point from the drawn centerline

    // Smooth contours: the face each segment of geometry crosses (geometry.edges then name the
    // edge each segment starts on); empty for the other lines.
    std::vector<uint32_t> faces;
};

struct StrokeStats {
    size_t polylines = 0;              // input polylines
    size_t pure_strokes = 0;           // after splitting at corners, before linking
    size_t corners = 0;                // splits at sharp turns
    size_t links = 0;                  // joins through junctions
    size_t bridges = 0;                // short occluded gaps drawn across, split strokes joined again
    size_t drawn = 0;                  // strokes with an outline
    size_t inherited = 0;              // strokes whose id was present last frame
    double visible_length_px = 0.0;    // exact length of the visible strokes (bridged gaps left out)
    double inherited_length_px = 0.0;  // ... of those whose id was present last frame
    double max_deviation_px = 0.0;     // over drawn strokes
    double max_removed_px = 0.0;       // over drawn strokes: back-tracking removed
};

// How far the write-on of a frame has come (core/strokes/write_on.h).
struct WriteOnFrame {
    double time_s = 0.0;  // time since the drawing began
    double seconds = 0.0;
    double speed_px_s = 0.0;
    struct StrokeProgress {
        double start_s = -1.0;  // when its tip set off; -1: not timed (appears when the drawing is done)
        double end_s = -1.0;    // when it is finished
        double drawn_px = 0.0;  // length drawn along its drawn centerline
        double length_px = 0.0;  // that centerline's length
    };
    std::vector<StrokeProgress> strokes;  // one per stroke, as FrameStrokes::strokes
};

struct FrameStrokes {
    int frame = 0;
    std::vector<Stroke> strokes;
    // The styles the strokes use; styles[0] is the scene's brush, the style of a stroke no rule
    // matched.
    std::vector<StrokeStyle> styles;
    StrokeStats stats;
    // Set on the drawing of a write-on at a time (strokes_at); unset otherwise.
    std::optional<WriteOnFrame> write_on;
};

// The ink of a drawn centerline (samples c with their width and u; a loop's last sample does not
// repeat its first, length_px includes its closing segment): its outline, in dashes when
// style.dash_px has a pattern, with the texture's holes cut and its darkening when style.texture
// is set (seeded by the stroke's id; last_end is the end the centerline runs to).
struct StrokeInk {
    std::vector<Ring> outline;
    double darkening = 0.0;
};
StrokeInk stroke_ink(std::span<const glm::dvec2> centerline, std::span<const double> width, std::span<const double> u,
                     bool closed, double length_px, StrokeEnd last_end, uint32_t id, const BrushStyle& style);

// Builds one frame's brush strokes from its polylines (frame.polylines) and light (frame.light).
// mesh and table are the frame's mesh and edge table, projection its camera and object motion.
// Reads the previous frame's strokes from r_coherence and leaves this frame's there; short
// occluded gaps (frame.occluded) are bridged as gap_bridge_options says. With nothing in
// r_coherence (a first frame), the strokes are made twice, the second time with the first's as
// memory (the first pass draws no outlines), so that the frame after joins no more than this one:
// stats.inherited stays 0.
// The object (an index into FrameLines::objects) of the first of these mesh edges.
using ObjectOfEdges = std::function<int32_t(std::span<const uint32_t> edges)>;

// Each stroke is drawn with `style` and the style rules that match it applied in order. With
// object_of, each stroke's geometry.object is the object of its first edge in drawing direction
// (for a loop, before its start is chosen), and rules select by it. With `normals`, the vertex
// normals the light needs are kept there for the next frame (clear it when the mesh changes).
// Deterministic: the same frames in the same order give the same strokes, bit for bit.
FrameStrokes build_strokes(const FrameLines& frame, const Mesh& mesh, const EdgeTable& table,
                           const Projection& projection, const BrushStyle& style, StrokeCoherence& r_coherence,
                           std::span<const StyleRule> rules = {}, const ObjectOfEdges& object_of = {},
                           VertexNormalCache* normals = nullptr);

}  // namespace inkline::core
