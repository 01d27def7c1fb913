// SPDX-License-Identifier: MIT
// Quad strips of stroke centerlines: the outline's shape, texture coordinates along and across.
#include "gl/internal/quad_strip.h"

#include "core/error.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace inkline {
namespace {

using gl::internal::QuadStrip;
using gl::internal::StripVertex;

// A circle of radius r around (50, 50), or the arc of it up to `degrees`, every 0.5 px.
core::Stroke arc_stroke(double r, double degrees, double width, bool closed) {
    core::Stroke s;
    s.geometry.closed = closed;
    s.geometry.ends = closed ? std::array{core::StrokeEnd::kLoop, core::StrokeEnd::kLoop}
                             : std::array{core::StrokeEnd::kCorner, core::StrokeEnd::kFree};
    const double length = r * degrees * std::numbers::pi / 180.0;
    const int n = int(length / 0.5);
    for (int i = 0; i < (closed ? n : n + 1); ++i) {
        const double a = length * i / n / r;
        s.centerline_px.push_back({50.0 + r * std::cos(a), 50.0 + r * std::sin(a)});
        s.centerline_u.push_back(100.0 + length * i / n);
        s.centerline_width.push_back(closed ? width : width * (1.0 - double(i) / n));
    }
    return s;
}

double area(const QuadStrip& strip) {
    double sum = 0.0;
    for (size_t k = 0; k < strip.indices.size(); k += 3) {
        const glm::vec2 a = strip.vertices[strip.indices[k]].p_px, b = strip.vertices[strip.indices[k + 1]].p_px,
                        c = strip.vertices[strip.indices[k + 2]].p_px;
        sum += 0.5 * std::abs(double((b - a).x * (c - a).y - (b - a).y * (c - a).x));
    }
    return sum;
}

TEST(QuadStrip, LoopIsAClosedRingOfTheWidth) {
    const QuadStrip strip = gl::internal::quad_strip(arc_stroke(20.0, 360.0, 4.0, true), {});
    ASSERT_TRUE(strip.closed);
    EXPECT_NEAR(strip.length_px, 2.0 * std::numbers::pi * 20.0, 0.01);
    // Annulus between radii 18 and 22; a = 1 on the right of the direction of travel, inside.
    EXPECT_NEAR(area(strip), std::numbers::pi * (22.0 * 22.0 - 18.0 * 18.0), 0.5);
    for (const StripVertex& v : strip.vertices) {
        EXPECT_NEAR(glm::length(glm::dvec2(v.p_px) - glm::dvec2(50.0)), 20.0 - 2.0 * v.across.x, 1e-3);
        EXPECT_EQ(std::abs(v.across.x), 1.0f);
        EXPECT_EQ(v.across.y, 0.0f);
    }
    // The seam: the last pair repeats the first one loop further on.
    const StripVertex& first = strip.vertices.front();
    const StripVertex& last = strip.vertices[strip.vertices.size() - 2];
    EXPECT_NEAR(glm::length(last.p_px - first.p_px), 0.0, 1e-4);
    EXPECT_NEAR(last.s_px, strip.length_px, 1e-3);
    // u here measures the circle, length_px its chords: 0.003 px apart over the loop.
    EXPECT_NEAR(last.u_px - first.u_px, strip.length_px, 1e-2);
}

TEST(QuadStrip, BluntEndsGetHalfDiscCapsAndPointsNone) {
    // An open arc: full width at its corner (A) start, tapering to a point at its free end.
    const core::Stroke stroke = arc_stroke(20.0, 90.0, 6.0, false);
    const QuadStrip strip = gl::internal::quad_strip(stroke, {.widen = 1.0, .cap_segments = 12});
    const size_t pairs = stroke.centerline_px.size();
    ASSERT_EQ(strip.vertices.size(), 2 * pairs + 14) << "one cap: its centre and 13 rim points";
    ASSERT_EQ(strip.indices.size(), 6 * (pairs - 1) + 3 * 12);
    // The cap lies behind the start (s < 0), on the circle of half the width around it.
    const glm::dvec2 start = stroke.centerline_px.front();
    for (size_t k = 2 * pairs; k < strip.vertices.size(); ++k) {
        const StripVertex& v = strip.vertices[k];
        EXPECT_LE(v.s_px, 1e-5);
        EXPECT_NEAR(v.u_px - stroke.centerline_u.front(), v.s_px, 1e-4) << "u runs on past the end";
        if (k > 2 * pairs) {
            EXPECT_NEAR(glm::length(glm::dvec2(v.p_px) - start), 3.0, 1e-4);
            EXPECT_NEAR(glm::length(v.across), 1.0f, 1e-5);
        }
    }
}

TEST(QuadStrip, WidenMakesRoomForASoftMargin) {
    const core::Stroke stroke = arc_stroke(20.0, 360.0, 4.0, true);
    const QuadStrip strip = gl::internal::quad_strip(stroke, {.widen = 1.5});
    for (const StripVertex& v : strip.vertices) {
        EXPECT_NEAR(glm::length(glm::dvec2(v.p_px) - glm::dvec2(50.0)), 20.0 - 3.0 * v.across.x, 1e-3);
    }
}

TEST(QuadStrip, RepeatedPointsAndTooShortCenterlines) {
    core::Stroke s = arc_stroke(20.0, 90.0, 2.0, false);
    s.centerline_px.insert(s.centerline_px.begin() + 5, s.centerline_px[5]);
    s.centerline_u.insert(s.centerline_u.begin() + 5, s.centerline_u[5]);
    s.centerline_width.insert(s.centerline_width.begin() + 5, s.centerline_width[5]);
    const QuadStrip strip = gl::internal::quad_strip(s, {});
    for (const StripVertex& v : strip.vertices) ASSERT_TRUE(std::isfinite(v.p_px.x) && std::isfinite(v.p_px.y));
    EXPECT_NEAR(strip.length_px, 20.0 * std::numbers::pi / 2.0, 0.01);

    core::Stroke dot;
    dot.centerline_px = {{3.0, 3.0}, {3.0, 3.0}};
    dot.centerline_u = {0.0, 0.0};
    dot.centerline_width = {2.0, 2.0};
    EXPECT_TRUE(gl::internal::quad_strip(dot, {}).indices.empty());
}

}  // namespace
}  // namespace inkline
