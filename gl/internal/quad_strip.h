// SPDX-License-Identifier: MIT
// A stroke's drawn centerline as triangles for the preview: a quad strip (two points offset by
// the half-width along the normal at every centerline sample) and half-disc fans on ends that
// keep their width, the same shape as core::build_outline's filled outline.
// Strokes as textured strips: J. D. Northrup, L. Markosian. Artistic Silhouettes: A Hybrid
// Approach. NPAR 2000.
#pragma once

#include "core/strokes/strokes.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace inkline::gl::internal {

// One vertex as the preview's vertex shader reads it (7 floats, tightly packed).
struct StripVertex {
    glm::vec2 p_px;    // image px, origin top-left, y down
    glm::vec2 across;  // (a, b) in strip half-widths: a from -1 (left edge) to 1 (right), b past an end (caps)
    float s_px;        // arc length from the stroke's start along the centerline; past an end on caps
    float u_px;        // the stroke's propagated u (continues past the ends on caps)
    float width_px;    // brush width at the nearest centerline sample (pressure)
};

static_assert(sizeof(StripVertex) == 7 * sizeof(float), "the vertex layout gl/preview.cpp declares");

struct QuadStrip {
    std::vector<StripVertex> vertices;
    std::vector<uint32_t> indices;  // triangles, three indices each
    double length_px = 0.0;         // centerline arc length (a loop's includes its closing segment)
    bool closed = false;
};

struct QuadStripOptions {
    // Strip half-width over half the brush width: above 1 to make room for a tip's soft margin
    // (1 / (1 - 2 * edge_margin)).
    double widen = 1.0;
    int cap_segments = 12;  // triangles per half-disc cap: 15 degrees each, as the outline's joins
};

// Triangles of one stroke's drawn centerline (centerline_px, centerline_u, centerline_width).
// An open stroke gets a cap at each end whose width exceeds a thousandth of a pixel (blunt A and
// C ends; free S ends taper to a point and get none); a loop closes on itself. Empty when the
// centerline has fewer than two distinct points.
QuadStrip quad_strip(const core::Stroke& stroke, const QuadStripOptions& options);

// Triangles of a constant-width line along `points` (px), as the vector outputs stroke a
// centerline (hidden lines): u runs from u_start by arc length, and each open end gets room for
// its cap (a half-disc for round, a square for square, none for butt), which the preview's
// dashes trim. Empty when the points have fewer than two distinct ones.
QuadStrip centerline_strip(std::span<const glm::dvec2> points, bool closed, double width_px, double u_start,
                           core::LineCap cap, const QuadStripOptions& options);

}  // namespace inkline::gl::internal
