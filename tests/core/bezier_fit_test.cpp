// SPDX-License-Identifier: MIT
#include "core/strokes/bezier_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

namespace inkline {
namespace {

using glm::dvec2;

void expect_closed_chain(const std::vector<core::CubicBezier>& curves) {
    ASSERT_FALSE(curves.empty());
    for (size_t i = 0; i < curves.size(); ++i) {
        EXPECT_EQ(curves[i].p3, curves[(i + 1) % curves.size()].p0) << "segment " << i;
    }
}

TEST(BezierFit, CircleTakesFewSegmentsWithinTolerance) {
    core::Ring ring;
    for (int i = 0; i < 400; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 400;
        ring.push_back(30.0 * dvec2(std::cos(a), std::sin(a)));
    }
    const std::vector<core::CubicBezier> curves = core::fit_cubics(ring, 0.1);
    expect_closed_chain(curves);
    EXPECT_LE(curves.size(), 12u);
    EXPECT_LE(core::fit_error_px(ring, curves), 0.1);
}

TEST(BezierFit, StrokeOutlinesKeepTheirTipsAndTolerance) {
    // A wavy stroke tapering to points at both ends, and a loop of varying width.
    std::vector<dvec2> c;
    std::vector<double> w;
    for (int i = 0; i <= 400; ++i) {
        const double t = i / 400.0;
        c.push_back({200.0 * t, 15.0 * std::sin(8.0 * t)});
        w.push_back(5.0 * std::sin(std::numbers::pi * t));
    }
    std::vector<dvec2> loop;
    std::vector<double> loop_w;
    for (int i = 0; i < 300; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 300;
        loop.push_back({60.0 * std::cos(a), 35.0 * std::sin(a)});
        loop_w.push_back(3.0 + 1.5 * std::cos(3.0 * a));
    }
    std::vector<core::Ring> rings = core::build_outline(c, w, false, {});
    const std::vector<core::Ring> loop_rings = core::build_outline(loop, loop_w, true, {});
    rings.insert(rings.end(), loop_rings.begin(), loop_rings.end());
    ASSERT_EQ(rings.size(), 3u);
    for (const core::Ring& ring : rings) {
        const std::vector<core::CubicBezier> curves = core::fit_cubics(ring, 0.1);
        expect_closed_chain(curves);
        EXPECT_LE(core::fit_error_px(ring, curves), 0.1);
        EXPECT_LT(curves.size(), ring.size() / 3) << "much shorter than the polygon";
    }
    // The pointed tips stay on the curve as segment ends.
    const std::vector<core::CubicBezier> stroke = core::fit_cubics(rings[0], 0.1);
    for (const dvec2 tip : {c.front(), c.back()}) {
        bool found = false;
        for (const core::CubicBezier& b : stroke) found = found || glm::length(b.p0 - tip) < 1e-9;
        EXPECT_TRUE(found) << tip.x << ", " << tip.y;
    }
}

TEST(BezierFit, DegenerateRings) {
    EXPECT_TRUE(core::fit_cubics({}, 0.1).empty());
    EXPECT_TRUE(core::fit_cubics({{0, 0}, {1, 0}}, 0.1).empty());
    const std::vector<core::CubicBezier> triangle = core::fit_cubics({{0, 0}, {10, 0}, {0, 10}}, 0.1);
    expect_closed_chain(triangle);
    EXPECT_LE(core::fit_error_px({{0, 0}, {10, 0}, {0, 10}}, triangle), 0.1);
}

}  // namespace
}  // namespace inkline
