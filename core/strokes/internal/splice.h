// SPDX-License-Identifier: MIT
// Strokes spliced end to end and cut into parts: how pure strokes are linked into strokes, and
// how the repairs (bridge_gaps, rejoin_strokes, t_junctions, reversals) join and cut them.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <utility>

#include "core/strokes/stroke_geometry.h"

namespace inkline::core::internal {

// Continues r_into with `next`, which starts at r_into's last point (or ends there, run
// `reversed`): r_into takes next's other points, its edges and bridged marks, its pure strokes
// and the type of its far end. Bridged marks are kept per segment once either has any.
void splice(StrokeGeometry& r_into, const StrokeGeometry& next, bool reversed = false);
// The same for an occluded part drawn across (a gap): every segment of it is marked bridged.
void splice_bridged(StrokeGeometry& r_into, const StrokeGeometry& gap);
// Continues r_into by one bridged segment to (px, world), on mesh edge `edge`.
void splice_bridged_segment(StrokeGeometry& r_into, const glm::dvec2& px, const glm::dvec3& world, uint32_t edge);

// Turns a round to end at pa and b to start at pb, ready to be spliced a -> b. False, with
// neither turned, where a has no end at pa or b none at pb (an earlier join took it).
bool orient_for_splice(StrokeGeometry& a, const glm::dvec2& pa, StrokeGeometry& b, const glm::dvec2& pb);

// Points [begin, end] of a stroke as a stroke of its own: the ends cut inside it are junctions.
StrokeGeometry part_of(const StrokeGeometry& g, size_t begin, size_t end);

// Strokes that meet share their end points bit for bit: an exact point as a map key (-0 as +0,
// as == compares them).
using PointKey = std::pair<double, double>;
inline PointKey point_key(const glm::dvec2& p) { return {p.x + 0.0, p.y + 0.0}; }
struct PointKeyHash {
    size_t operator()(const PointKey& k) const {
        const uint64_t h = std::bit_cast<uint64_t>(k.first) * 0x9e3779b97f4a7c15ull ^ std::bit_cast<uint64_t>(k.second);
        return size_t((h ^ (h >> 29)) * 0xbf58476d1ce4e5b9ull);
    }
};

// An open visible stroke with two ends, the only kind the repairs join, cut or end on.
inline bool is_open_visible(const StrokeGeometry& g) { return g.visible && !g.closed && g.points_px.size() >= 2; }

}  // namespace inkline::core::internal
