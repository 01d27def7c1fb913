// SPDX-License-Identifier: MIT
// The exact geometry of a stroke: its points in the image and in the world, the mesh edge of each
// segment, its end types and the segments drawn across short occluded gaps. Every stroke type of
// the stage holds one (pure strokes while they are linked and repaired, a candidate while it is
// matched to last frame's strokes, the finished Stroke).
#pragma once

#include "core/lines/features.h"
#include "core/visibility/visibility.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace inkline::core {

enum class StrokeEnd : uint8_t {
    kFree = 0,      // S: touches no other stroke
    kCorner = 1,    // A: meets one other stroke at a sharp angle
    kJunction = 2,  // C: meets other strokes (or ends on one, where a line passes behind another)
    kLoop = 3,      // L: the stroke is closed
};

// "S", "A", "C" or "L".
const char* stroke_end_name(StrokeEnd end);

// Pure strokes of one kind and visibility joined end to end, in drawing direction.
struct StrokeGeometry {
    LineKind kind = LineKind::kSilhouette;
    bool visible = true;  // false: an occluded line (output only with lines.hidden)
    bool closed = false;  // a loop: points repeat the first point last
    std::array<StrokeEnd, 2> ends{StrokeEnd::kFree, StrokeEnd::kFree};  // at the first and last point
    std::vector<glm::dvec2> points_px;                                  // exact projected points, px
    std::vector<glm::dvec3> points_world;                               // the same points in world space
    std::vector<uint32_t> edges;                                        // mesh edge of each segment (points - 1)
    // Per segment: 1 where a visible stroke is drawn across a short occluded gap (bridge_gaps.h,
    // rejoin_strokes.h, t_junctions.h): the segment is occluded, drawn all the same. Empty when
    // no segment is; else one mark per segment.
    std::vector<uint8_t> bridged;
    size_t pure_stroke_count = 1;  // how many pure strokes were linked into this one
    int32_t object = -1;           // the object of its first edge (FrameLines::objects; build_strokes); -1 without objects

    const glm::dvec2& end_px(int end) const { return end == 0 ? points_px.front() : points_px.back(); }
    double length_px() const;
    // The length less the bridged segments.
    double unbridged_length_px() const;
    // Indices of the exact points the stroke is drawn through: a bridged gap is drawn straight
    // across, its occluded inner points left out. A zig-zag silhouette's hidden folds would
    // otherwise be drawn as spikes, and leave holes where the outline folds over itself.
    std::vector<size_t> drawn_indices() const;
    // Runs the stroke the other way: points, edges, bridged marks and end types.
    void reverse();
};

// A polyline's geometry as it is: free ends, nothing bridged.
StrokeGeometry geometry_of(const Polyline& line);

}  // namespace inkline::core
