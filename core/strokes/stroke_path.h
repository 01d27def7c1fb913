// SPDX-License-Identifier: MIT
// Drawn centerline of a stroke: the exact polyline with image-space back-tracking removed,
// smoothed within a bounded deviation and resampled evenly. Only drawing uses it; the exact
// points stay as they are.
// Silhouettes extracted from a mesh fold back on themselves at the pixel scale (near cusps and at
// visibility cuts); they are cleaned like this before a brush is laid along them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <span>
#include <vector>

namespace inkline::core {

// A zig-zag arm this short (px) that turns back by more than kBacktrackTurnDeg is back-tracking:
// mesh silhouettes fold over at this scale near cusps and at visibility cuts.
inline constexpr double kBacktrackPx = 2.0;
inline constexpr double kBacktrackTurnDeg = 120.0;

struct StrokePathOptions {
    double spacing_px = 1.0;        // resampling step
    double smooth_px = 2.0;         // Gaussian sigma along the path; 0 keeps the cleaned polyline
    double max_deviation_px = 0.5;  // no sample moves farther than this from the exact polyline
};

struct StrokePath {
    bool closed = false;                // samples form a loop; the last does not repeat the first
    std::vector<glm::dvec2> points_px;  // samples
    std::vector<double> arc_px;         // arc length of each sample along the drawn path
    std::vector<double> g;              // exact parameter of each sample: segment + fraction
    double g_end = 0.0;                 // exact parameter of the last exact point (a loop's seam)
    double length_px = 0.0;             // drawn length (a loop includes its closing segment)
    double step_px = 0.0;               // sample spacing along the cleaned path, before smoothing
    double deviation_px = 0.0;          // largest distance of a sample from the exact polyline

    // Fractional sample index where the exact parameter g lies (monotone in g).
    double sample_at(double g_exact) const;
    // Arc length at a fractional sample index; on a loop, past the last sample runs on to length_px.
    double arc_at(double sample) const;
    // Linear interpolation of per-sample values at a fractional sample index.
    double interpolate(std::span<const double> values, double sample) const;
};

// Indices of the exact points kept once back-tracking spikes are removed, in order. A closed
// polyline (first point repeated last) keeps its first point and ends with it again.
std::vector<size_t> remove_backtracking(std::span<const glm::dvec2> points_px, bool closed);

// Builds the drawn centerline of an exact polyline (a closed one repeats its first point last).
StrokePath build_stroke_path(std::span<const glm::dvec2> points_px, bool closed, const StrokePathOptions& options);

// Largest distance from an exact point to the drawn path: what back-tracking removal and
// smoothing took away (px).
double removed_extent_px(std::span<const glm::dvec2> points_px, const StrokePath& path);

// Gaussian smoothing (sigma in px) of values at samples step_px apart; a loop wraps around,
// an open path's kernel is cut (and renormalised) at its ends.
std::vector<double> smooth_samples(std::span<const double> values, double step_px, double sigma_px, bool closed);

// Squared distance from p to the segment ab.
inline double distance2_to_segment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    const glm::dvec2 off = p - (a + ab * t);
    return glm::dot(off, off);
}

// Distance from p to the segment ab.
inline double distance_to_segment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
    return std::sqrt(distance2_to_segment(p, a, b));
}

}  // namespace inkline::core
