// SPDX-License-Identifier: MIT
#include "core/strokes/brush_texture.h"

#include "core/random.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

namespace inkline::core {
namespace {

// Lanes across the stroke that dry out one by one, and bristle streaks.
constexpr int kLanes = 7;
constexpr int kStreaks = 5;
// Holes stay this far (a fraction of the width) inside the outline's edges.
constexpr double kEdgeInset = 0.06;
// A streak's hole, as a fraction of the width.
constexpr double kStreakWidth = 0.08;
// Streaks open only on strokes at least this wide (px): on thinner ones they would be dust.
constexpr double kMinStreakStrokePx = 2.0;
// Holes are simplified within this distance (px), as outlines are.
constexpr double kSimplifyPx = 0.05;
// Along the stroke the dry noise has a knot every this many px of u.
constexpr double kNoiseKnotPx = 6.0;
// Where the centerline bends tighter than this fraction of its width, the outline's inner side
// folds: no hole is cut there.
constexpr double kMinBendRadiusWidths = 0.75;

// Smooth value noise in [0, 1] along u, anchored to u: the same u gives the same value.
double value_noise(uint64_t seed, double u) {
    const double x = u / kNoiseKnotPx;
    const double k = std::floor(x);
    const double f = x - k;
    const double a = SplitMix64::unit(SplitMix64::hash(seed ^ uint64_t(int64_t(k))));
    const double b = SplitMix64::unit(SplitMix64::hash(seed ^ uint64_t(int64_t(k) + 1)));
    const double s = f * f * (3.0 - 2.0 * f);
    return a + (b - a) * s;
}

// A hole between offsets v0 < v1 (fractions of the width from the centerline, left positive) over
// samples [a, b].
Ring band(std::span<const glm::dvec2> c, std::span<const glm::dvec2> normal, std::span<const double> w, size_t a,
          size_t b, const std::vector<double>& v0, const std::vector<double>& v1) {
    Ring ring;
    for (size_t i = a; i <= b; ++i) ring.push_back(c[i] + normal[i] * (v1[i] * w[i]));
    for (size_t i = b + 1; i-- > a;) ring.push_back(c[i] + normal[i] * (v0[i] * w[i]));
    return ring;
}

}  // namespace

std::vector<TextureHole> texture_gaps(std::span<const glm::dvec2> c, std::span<const double> u, std::span<const double> w,
                               bool closed, StrokeEnd end, uint32_t stroke_id, const BrushTexture& texture,
                               const std::vector<Ring>& outline) {
    std::vector<TextureHole> holes;
    const size_t n = c.size();
    if (n < 3 || u.size() != n || w.size() != n || outline.empty()) return holes;
    const std::vector<glm::dvec2> t = centerline_tangents(c, closed);
    std::vector<glm::dvec2> normal(n);
    for (size_t i = 0; i < n; ++i) normal[i] = {-t[i].y, t[i].x};
    // Where a hole may be: the outline there is the plain offset of the centerline.
    std::vector<uint8_t> open(n, 1);
    for (size_t i = 1; i + 1 < n; ++i) {
        const glm::dvec2 d0 = c[i] - c[i - 1], d1 = c[i + 1] - c[i];
        const double l0 = glm::length(d0), l1 = glm::length(d1);
        if (!(l0 > 0.0 && l1 > 0.0)) continue;
        const double turn = std::atan2(std::abs(d0.x * d1.y - d0.y * d1.x), glm::dot(d0, d1));
        const double radius = turn > 0.0 ? 0.5 * (l0 + l1) / turn : HUGE_VAL;
        if (radius < kMinBendRadiusWidths * w[i]) open[i - 1] = open[i] = open[i + 1] = 0;
    }
    if (!closed) open.front() = open.back() = 0;

    const uint64_t seed = SplitMix64::hash(0x5eedb7a5ull ^ (uint64_t(stroke_id) << 8));
    SplitMix64 random(seed);
    std::vector<uint8_t> gap(n);
    std::vector<double> v0(n), v1(n);
    // Each run of samples marked in `gap` becomes one hole.
    const auto cut_runs = [&](int band_index) {
        for (size_t a = 0; a < n;) {
            if (!gap[a] || !open[a]) {
                ++a;
                continue;
            }
            size_t b = a;
            while (b + 1 < n && gap[b + 1] && open[b + 1]) ++b;
            if (b > a + 1) {
                Ring hole = simplify_ring(band(c, normal, w, a, b, v0, v1), kSimplifyPx);
                if (hole.size() >= 3) holes.push_back({band_index, u[a], u[b], std::move(hole)});
            }
            a = b + 1;
        }
    };

    // Dry brush: toward a free end, lanes break where the dryness, wobbled by each lane's noise
    // along u, passes their threshold; lanes near the edges break first.
    std::array<double, kLanes + 1> edges{};
    for (int l = 0; l < kLanes; ++l) edges[size_t(l) + 1] = edges[size_t(l)] + random.uniform(0.5, 1.5);
    for (double& e : edges) e = (0.5 - kEdgeInset) * (2.0 * e / edges.back() - 1.0);
    if (!closed && end == StrokeEnd::kFree && texture.dry > 0.0 && texture.dry_px > 0.0) {
        const double u_end = u.back();
        for (int l = 0; l < kLanes; ++l) {
            const double centre = 0.5 * (edges[size_t(l)] + edges[size_t(l) + 1]);
            const double to_border = 1.0 - std::abs(centre) / (0.5 - kEdgeInset);
            const double dry_at = random.uniform(0.25, 1.05) * (0.55 + 0.45 * to_border);
            const uint64_t lane_seed = SplitMix64::hash(seed + uint64_t(l) + 1);
            for (size_t i = 0; i < n; ++i) {
                const double tail = std::clamp(1.0 - (u_end - u[i]) / texture.dry_px, 0.0, 1.0);
                const double dryness = 1.1 * texture.dry * std::pow(tail, 1.6);
                const double wobble = 0.6 * (value_noise(lane_seed, u[i]) - 0.5);
                gap[i] = tail > 0.0 && dryness + wobble > dry_at;
                v0[i] = edges[size_t(l)];
                v1[i] = edges[size_t(l) + 1];
            }
            cut_runs(l);
        }
    }
    // Bristle streaks: thin holes along the stroke that open and close with u.
    if (texture.streaks > 0.0) {
        for (int k = 0; k < kStreaks; ++k) {
            const double centre = random.uniform(-0.35, 0.35);
            const double period = random.uniform(40.0, 120.0);
            const double phase = random.uniform(0.0, 1.0);
            for (size_t i = 0; i < n; ++i) {
                const double strength = 0.5 + 0.5 * std::sin(2.0 * std::numbers::pi * (u[i] / period + phase));
                gap[i] = w[i] >= kMinStreakStrokePx && strength > 1.0 - 0.35 * texture.streaks;
                v0[i] = centre - 0.5 * kStreakWidth;
                v1[i] = centre + 0.5 * kStreakWidth;
            }
            cut_runs(kLanes + k);
        }
    }

    // Holes run against the ink: the outline's widest ring gives its orientation.
    const Ring& outer = *std::max_element(outline.begin(), outline.end(), [](const Ring& a, const Ring& b) {
        return std::abs(signed_area(a)) < std::abs(signed_area(b));
    });
    const bool ink_ccw = signed_area(outer) > 0.0;
    for (TextureHole& hole : holes) {
        if ((signed_area(hole.ring) > 0.0) == ink_ccw) std::reverse(hole.ring.begin(), hole.ring.end());
    }
    return holes;
}

double pressure_darkening(std::span<const double> width, const BrushStyle& style) {
    if (!style.texture || width.empty() || !(style.width_max_px > style.width_min_px)) return 0.0;
    double sum = 0.0;
    for (const double w : width) sum += std::clamp((w - style.width_min_px) / (style.width_max_px - style.width_min_px), 0.0, 1.0);
    return std::clamp(style.texture->pressure * sum / double(width.size()), 0.0, 1.0);
}

}  // namespace inkline::core
