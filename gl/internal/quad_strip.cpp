// SPDX-License-Identifier: MIT
#include "gl/internal/quad_strip.h"

#include "core/error.h"
#include "core/strokes/outline.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace inkline::gl::internal {
namespace {

// Consecutive centerline points closer than this (px) are one point (core/strokes/outline.cpp's value).
constexpr double kSamePointPx = 1e-9;
// Ends narrower than this (px) are a point: no cap (core/strokes/outline.cpp's kCapMinWidthPx).
constexpr double kCapMinWidthPx = 1e-3;

glm::dvec2 perp(const glm::dvec2& v) { return {-v.y, v.x}; }

struct Sample {
    glm::dvec2 p;
    double u = 0.0;
    double width = 0.0;
};

// A half-disc fan of radius `half` around `centre`, bulging along `out` (a unit vector, the
// tangent at the end or its opposite), its rim points on the circle as the outline's cap.
void add_cap(QuadStrip& r_strip, const glm::dvec2& centre, const glm::dvec2& tangent, const glm::dvec2& out,
             double half, double s_end, double u_end, double width, int segments) {
    const glm::dvec2 normal = perp(tangent);
    const double step = std::numbers::pi / segments;
    const auto first = uint32_t(r_strip.vertices.size());
    r_strip.vertices.push_back({glm::vec2(centre), glm::vec2(0.0f), float(s_end), float(u_end), float(width)});
    for (int k = 0; k <= segments; ++k) {
        const double phi = -0.5 * std::numbers::pi + step * k;
        const glm::dvec2 offset = (std::cos(phi) * out + std::sin(phi) * normal) * half;
        const double a = glm::dot(offset, normal) / half;
        const double b = glm::dot(offset, tangent) / half;  // negative before the start
        r_strip.vertices.push_back({glm::vec2(centre + offset), glm::vec2(float(a), float(b)), float(s_end + b * half),
                                    float(u_end + b * half), float(width)});
    }
    for (int k = 0; k < segments; ++k) {
        r_strip.indices.insert(r_strip.indices.end(), {first, first + 1 + uint32_t(k), first + 2 + uint32_t(k)});
    }
}

// A square of half-width `half` past an end, along `out`: room for a square cap.
void add_square_cap(QuadStrip& r_strip, const glm::dvec2& centre, const glm::dvec2& tangent, const glm::dvec2& out,
                    double half, double s_end, double u_end, double width) {
    const glm::dvec2 normal = perp(tangent);
    const double along = glm::dot(out, tangent);  // -1 before the start, 1 past the end
    const auto first = uint32_t(r_strip.vertices.size());
    for (const double b : {0.0, along}) {
        for (const double a : {-1.0, 1.0}) {
            r_strip.vertices.push_back({glm::vec2(centre + (a * normal + b * tangent) * half), glm::vec2(float(a), float(b)),
                                        float(s_end + b * half), float(u_end + b * half), float(width)});
        }
    }
    r_strip.indices.insert(r_strip.indices.end(), {first, first + 1, first + 2, first + 1, first + 3, first + 2});
}

// The strip of centerline samples (distinct, a loop's first not repeated last), with caps of
// shape `cap` (none for butt) on each open end whose width exceeds kCapMinWidthPx.
QuadStrip strip_of(const std::vector<Sample>& c, bool closed, core::LineCap cap, const QuadStripOptions& options) {
    QuadStrip strip;
    strip.closed = closed;
    if (c.size() < 2) return strip;
    std::vector<glm::dvec2> points(c.size());
    std::transform(c.begin(), c.end(), points.begin(), [](const Sample& sample) { return sample.p; });
    const std::vector<glm::dvec2> t = core::centerline_tangents(points, strip.closed);

    // Two vertices per sample, a quad between neighbours; a loop repeats its first pair at the
    // end with s and u one loop further on, so texture coordinates run on across the seam.
    const size_t n = c.size();
    const size_t pairs = strip.closed ? n + 1 : n;
    double s = 0.0;
    for (size_t k = 0; k < pairs; ++k) {
        const size_t i = k % n;
        if (k > 0) s += glm::length(c[i].p - c[k - 1].p);
        const double u = k < n ? c[i].u : c.back().u + glm::length(c[0].p - c.back().p);
        const double half = 0.5 * c[i].width * options.widen;
        const glm::dvec2 offset = perp(t[i]) * half;
        for (const float a : {-1.0f, 1.0f}) {
            strip.vertices.push_back(
                {glm::vec2(c[i].p + offset * double(a)), glm::vec2(a, 0.0f), float(s), float(u), float(c[i].width)});
        }
        if (k > 0) {
            const auto v = uint32_t(2 * k);
            strip.indices.insert(strip.indices.end(), {v - 2, v - 1, v, v - 1, v + 1, v});
        }
    }
    strip.length_px = s;

    // Caps where an open stroke's end keeps its width.
    if (!strip.closed && cap != core::LineCap::kButt) {
        const auto end_cap = [&](const Sample& end, const glm::dvec2& tangent, const glm::dvec2& out, double s_end) {
            if (!(end.width > kCapMinWidthPx)) return;
            const double half = 0.5 * end.width * options.widen;
            if (cap == core::LineCap::kSquare) {
                add_square_cap(strip, end.p, tangent, out, half, s_end, end.u, end.width);
            } else {
                add_cap(strip, end.p, tangent, out, half, s_end, end.u, end.width, options.cap_segments);
            }
        };
        end_cap(c.front(), t.front(), -t.front(), 0.0);
        end_cap(c.back(), t.back(), t.back(), s);
    }
    return strip;
}

}  // namespace

QuadStrip quad_strip(const core::Stroke& stroke, const QuadStripOptions& options) {
    INKLINE_CHECK_EQ(stroke.centerline_u.size(), stroke.centerline_px.size());
    INKLINE_CHECK_EQ(stroke.centerline_width.size(), stroke.centerline_px.size());
    INKLINE_CHECK(options.widen > 0.0 && options.cap_segments >= 2);
    const bool closed = stroke.geometry.closed;
    // Distinct samples; a loop that repeats its first point last drops the repeat.
    std::vector<Sample> c;
    for (size_t i = 0; i < stroke.centerline_px.size(); ++i) {
        const Sample s{stroke.centerline_px[i], stroke.centerline_u[i], stroke.centerline_width[i]};
        if (c.empty() || glm::length(s.p - c.back().p) > kSamePointPx) c.push_back(s);
    }
    if (closed && c.size() > 2 && glm::length(c.front().p - c.back().p) <= kSamePointPx) c.pop_back();
    return strip_of(c, closed, core::LineCap::kRound, options);
}

QuadStrip centerline_strip(std::span<const glm::dvec2> points, bool closed, double width_px, double u_start,
                           core::LineCap cap, const QuadStripOptions& options) {
    INKLINE_CHECK(options.widen > 0.0 && options.cap_segments >= 2 && width_px > 0.0);
    std::vector<Sample> c;
    double u = u_start;
    for (const glm::dvec2& p : points) {
        if (!c.empty()) {
            const double step = glm::length(p - c.back().p);
            if (!(step > kSamePointPx)) continue;
            u += step;
        }
        c.push_back({p, u, width_px});
    }
    if (closed && c.size() > 2 && glm::length(c.front().p - c.back().p) <= kSamePointPx) c.pop_back();
    return strip_of(c, closed, cap, options);
}

}  // namespace inkline::gl::internal
