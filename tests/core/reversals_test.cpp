// SPDX-License-Identifier: MIT
#include "core/strokes/reversals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <optional>
#include <vector>

#include "tests/core/repair_shapes.h"

namespace inkline {
namespace {

using glm::dvec2;
using repair_shapes::line;
using repair_shapes::through;
using repair_shapes::trace;
using repair_shapes::trace_along;

TEST(StrokeReversal, AHairpinIsCutAtItsTip) {
    // Out 80 px along x and back 6 px below: two strokes meeting at the tip, corners there.
    std::vector<core::StrokeGeometry> strokes{through({{0, 0}, {80, 0}, {0, 6}}, 0)};
    strokes[0].ends = {core::StrokeEnd::kFree, core::StrokeEnd::kFree};
    EXPECT_EQ(core::split_at_reversals(strokes, 28.8, 120.0), 1u);
    ASSERT_EQ(strokes.size(), 2u);
    const core::StrokeGeometry &out = strokes[0], &back = strokes[1];
    EXPECT_EQ(out.points_px.front(), dvec2(0, 0));
    EXPECT_EQ(back.points_px.back(), dvec2(0, 6));
    EXPECT_EQ(out.points_px.back(), back.points_px.front());
    EXPECT_LE(glm::length(out.points_px.back() - dvec2(80, 0)), 2.0) << "cut at the tip";
    EXPECT_EQ(out.ends[0], core::StrokeEnd::kFree);
    EXPECT_EQ(out.ends[1], core::StrokeEnd::kCorner);
    EXPECT_EQ(back.ends[0], core::StrokeEnd::kCorner);
    EXPECT_EQ(back.ends[1], core::StrokeEnd::kFree);
    EXPECT_EQ(out.edges.size() + back.edges.size(), 80u + 81u);
}

TEST(StrokeReversal, FoldsCornersAndLoopsStayWhole) {
    std::vector<core::StrokeGeometry> strokes{
        through({{0, 0}, {60, 0}, {45, 2}, {120, 2}}, 0),          // a fold 15 px back, shorter than the scale
        through({{0, 50}, {60, 50}, {60, 110}}, 1000),             // a right-angle corner
        through({{0, 200}, {80, 200}, {0, 206}, {0, 200}}, 2000),  // a thin loop
    };
    strokes[2].closed = true;
    const std::vector<core::StrokeGeometry> before = strokes;
    EXPECT_EQ(core::split_at_reversals(strokes, 28.8, 120.0), 0u);
    ASSERT_EQ(strokes.size(), before.size());
    for (size_t i = 0; i < strokes.size(); ++i) EXPECT_EQ(strokes[i].points_px, before[i].points_px) << i;
}

// Where split_at_reversals cuts, found the plain way: from every point, step out one point at a
// time until the points scale_px away before and after it, and the sharpest point of each run
// turning more than angle_deg.
std::vector<size_t> reversal_cuts_reference(const std::vector<dvec2>& pts, double scale_px, double angle_deg) {
    auto turn_at = [&](size_t k) -> std::optional<double> {
        size_t b = k, f = k;
        while (b > 0 && glm::length(pts[b] - pts[k]) < scale_px) --b;
        while (f + 1 < pts.size() && glm::length(pts[f] - pts[k]) < scale_px) ++f;
        const dvec2 in = pts[k] - pts[b], out = pts[f] - pts[k];
        if (glm::length(in) < scale_px || glm::length(out) < scale_px) return std::nullopt;
        const double c = glm::dot(in, out) / (glm::length(in) * glm::length(out));
        return glm::degrees(std::acos(std::clamp(c, -1.0, 1.0)));
    };
    std::vector<size_t> at;
    double best = 0.0;
    size_t best_k = 0;
    for (size_t i = 0; i <= pts.size(); ++i) {
        const std::optional<double> turn = i < pts.size() ? turn_at(i) : std::nullopt;
        if (turn && *turn > angle_deg) {
            if (*turn > best) best = *turn, best_k = i;
        } else if (best > 0.0) {
            at.push_back(best_k);
            best = 0.0;
        }
    }
    return at;
}

TEST(StrokeReversal, DenselySampledZigZagIsCutWhereThePlainSearchCuts) {
    // Hairpins and wobbles of random lengths with points 0.05 to 1 px apart: the points skipped
    // by arc length must not change a cut.
    uint32_t seed = 12345;
    auto random = [&] {
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 24);
    };
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<dvec2> path{{0, 0}};
        for (int leg = 0; leg < 12; ++leg) {
            const double angle = 6.283185307179586 * random(), length = 5.0 + 60.0 * random();
            path.push_back(path.back() + length * dvec2(std::cos(angle), std::sin(angle)));
        }
        core::StrokeGeometry g;
        g.visible = true;
        const double spacing = trial % 2 ? 0.05 : 0.2 + 0.8 * random();
        for (size_t i = 0; i + 1 < path.size(); ++i) {
            const int n = std::max(1, int(glm::length(path[i + 1] - path[i]) / spacing));
            for (int k = 0; k < n; ++k) g.points_px.push_back(path[i] + (path[i + 1] - path[i]) * (double(k) / n));
        }
        g.points_px.push_back(path.back());
        g.points_world.assign(g.points_px.size(), glm::dvec3(0.0));
        g.edges.assign(g.points_px.size() - 1, 0);
        const std::vector<size_t> expected = reversal_cuts_reference(g.points_px, 28.8, 120.0);
        std::vector<core::StrokeGeometry> strokes{g};
        ASSERT_EQ(core::split_at_reversals(strokes, 28.8, 120.0), expected.size()) << "trial " << trial;
        // The pieces end at the expected points, in order: the first, then those appended.
        ASSERT_EQ(strokes.size(), expected.size() + 1);
        size_t begin = 0;
        for (size_t i = 0; i < strokes.size(); ++i) {
            const size_t end = i < expected.size() ? expected[i] : g.points_px.size() - 1;
            EXPECT_EQ(strokes[i].points_px.size(), end - begin + 1) << "trial " << trial << " piece " << i;
            EXPECT_EQ(strokes[i].points_px.back(), g.points_px[end]) << "trial " << trial << " piece " << i;
            begin = end;
        }
    }
}

}  // namespace
}  // namespace inkline
