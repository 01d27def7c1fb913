// SPDX-License-Identifier: MIT
// Stroke outlines: the closed boundary of a variable-width centerline, offset left and right
// along its normal, with round joins, local folds cut away and round caps where an end has width.
// A quad strip (perpendiculars of half the line weight either side of each vertex) made
// watertight as a filled outline.
#pragma once

#include <glm/vec2.hpp>
#include <span>
#include <vector>

#include "core/strokes/brush_style.h"

namespace inkline::core {

using Ring = std::vector<glm::dvec2>;  // closed polygon, px; the last point does not repeat the first

struct OutlineOptions {
    double simplify_px = 0.05;    // dropped points lie this close to the simplified ring (finer on thin strokes)
    double join_step_deg = 15.0;  // the normal turns at most this much between outline points
    LineCap cap = LineCap::kRound;  // how an open stroke's ends with width are closed
};

// Outline of a centerline with a width (px) at each point. An open stroke gives one ring, a
// loop two (outer and inner, of opposite orientation): fill them together with the nonzero rule.
std::vector<Ring> build_outline(std::span<const glm::dvec2> centerline, std::span<const double> width, bool closed,
                                const OutlineOptions& options);

// The ink of a dot (a dash of no length) of that width at c, drawn along `tangent` (unit): a
// circle with round caps, a square with square caps, nothing with butt caps.
std::vector<Ring> dot_outline(const glm::dvec2& c, const glm::dvec2& tangent, double width, const OutlineOptions& options);

// Unit tangents of a centerline by central differences over the nearest distinct neighbours
// (wrapping round a loop); the outline's normals are their perpendiculars, and a preview drawn
// along the same centerline uses the same ones.
std::vector<glm::dvec2> centerline_tangents(std::span<const glm::dvec2> centerline, bool closed);

// Signed area (shoelace), px^2; positive for counter-clockwise in a y-up frame.
double signed_area(const Ring& ring);

// Area covered by rings that nest as build_outline makes them: |sum of signed areas|.
double outline_area(const std::vector<Ring>& rings);

// True when the ring does not touch or cross itself: CGAL::is_simple_2's answer, swept in
// doubles with exact orientations where that is cheaper.
bool is_simple(const Ring& ring);

// Douglas-Peucker simplification of a closed ring within tolerance_px.
Ring simplify_ring(const Ring& ring, double tolerance_px);

}  // namespace inkline::core
