// SPDX-License-Identifier: MIT
#include "core/strokes/pure_strokes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

namespace inkline {
namespace {

using core::StrokeEnd;
using glm::dvec2;

constexpr StrokeEnd S = StrokeEnd::kFree, A = StrokeEnd::kCorner, C = StrokeEnd::kJunction, L = StrokeEnd::kLoop;

// A polyline through image points; world points mirror them, edges are numbered from first_edge.
core::Polyline line(const std::vector<dvec2>& points, uint32_t first_edge, bool closed = false,
                    core::LineKind kind = core::LineKind::kSilhouette) {
    core::Polyline l;
    l.kind = kind;
    l.closed = closed;
    l.points_px = points;
    for (const dvec2& p : points) l.points_world.emplace_back(p.x, p.y, 0.0);
    for (size_t i = 0; i + 1 < points.size(); ++i) l.edges.push_back(first_edge + uint32_t(i));
    return l;
}

// Points from a to b about step px apart, both ends included.
std::vector<dvec2> segment(const dvec2& a, const dvec2& b, double step = 5.0) {
    const int n = std::max(1, int(std::ceil(glm::length(b - a) / step)));
    std::vector<dvec2> out;
    for (int i = 0; i <= n; ++i) out.push_back(a + (b - a) * (double(i) / n));
    return out;
}

std::vector<dvec2> join(std::vector<dvec2> a, const std::vector<dvec2>& b) {
    a.insert(a.end(), b.begin() + 1, b.end());
    return a;
}

std::vector<dvec2> circle(dvec2 center, double radius, int n) {
    std::vector<dvec2> out;
    for (int i = 0; i <= n; ++i) {
        const double a = 2.0 * std::numbers::pi * (i % n) / n;
        out.push_back(center + radius * dvec2(std::cos(a), std::sin(a)));
    }
    return out;
}

using Ends = std::array<StrokeEnd, 2>;

TEST(PureStrokes, SharpTurnSplitsIntoCornerEnds) {
    const auto l_shape = join(segment({0, 0}, {50, 0}), segment({50, 0}, {50, 50}));
    const core::PureStrokes r = core::build_pure_strokes({line(l_shape, 0)}, {});
    ASSERT_EQ(r.strokes.size(), 2u);
    EXPECT_EQ(r.corners, 1u);
    EXPECT_EQ(r.strokes[0].ends, (Ends{S, A}));
    EXPECT_EQ(r.strokes[1].ends, (Ends{A, S}));
    EXPECT_EQ(r.strokes[0].points_px.back(), dvec2(50, 0)) << "split at the corner point";
    EXPECT_EQ(r.strokes[1].points_px.front(), dvec2(50, 0));
    EXPECT_EQ(r.strokes[0].edges.size() + r.strokes[1].edges.size(), l_shape.size() - 1) << "every segment kept once";
}

TEST(PureStrokes, GentleCurveStaysWhole) {
    std::vector<dvec2> arc;
    for (int i = 0; i <= 30; ++i) arc.push_back(100.0 * dvec2(std::cos(0.05 * i), std::sin(0.05 * i)));
    const core::PureStrokes r = core::build_pure_strokes({line(arc, 0)}, {});
    ASSERT_EQ(r.strokes.size(), 1u);
    EXPECT_EQ(r.corners, 0u);
    EXPECT_EQ(r.strokes[0].ends, (Ends{S, S}));
}

TEST(PureStrokes, ZigZagSplitsAtEveryTurn) {
    std::vector<dvec2> zig;
    for (int i = 0; i <= 6; ++i) zig.push_back({10.0 * i, 20.0 * (i % 2)});
    const core::PureStrokes r = core::build_pure_strokes({line(zig, 0)}, {});
    ASSERT_EQ(r.strokes.size(), 6u);
    EXPECT_EQ(r.strokes.front().ends, (Ends{S, A}));
    for (size_t i = 1; i + 1 < r.strokes.size(); ++i) EXPECT_EQ(r.strokes[i].ends, (Ends{A, A})) << i;
    EXPECT_EQ(r.strokes.back().ends, (Ends{A, S}));
}

TEST(PureStrokes, TurnAngleIsAnOption) {
    std::vector<dvec2> zig;
    for (int i = 0; i <= 6; ++i) zig.push_back({10.0 * i, 20.0 * (i % 2)});
    EXPECT_EQ(core::build_pure_strokes({line(zig, 0)}, {.turn_angle_deg = 170.0}).strokes.size(), 1u);
}

TEST(PureStrokes, HairpinSplitsAtItsApex) {
    const auto hairpin = join(segment({0, 0}, {60, 0}), segment({60, 0}, {0, 4}));
    const core::PureStrokes r = core::build_pure_strokes({line(hairpin, 0)}, {});
    ASSERT_EQ(r.strokes.size(), 2u);
    EXPECT_EQ(r.strokes[0].ends, (Ends{S, A}));
    EXPECT_EQ(r.strokes[1].ends, (Ends{A, S}));
}

TEST(PureStrokes, SmoothLoopIsOneLStroke) {
    const core::PureStrokes r = core::build_pure_strokes({line(circle({0, 0}, 40, 48), 0, true)}, {});
    ASSERT_EQ(r.strokes.size(), 1u);
    EXPECT_TRUE(r.strokes[0].closed);
    EXPECT_EQ(r.strokes[0].ends, (Ends{L, L}));
}

TEST(PureStrokes, SquareLoopIsCutAtItsCorners) {
    auto square = join(join(join(segment({0, 0}, {40, 0}), segment({40, 0}, {40, 40})), segment({40, 40}, {0, 40})),
                       segment({0, 40}, {0, 0}));
    const core::PureStrokes r = core::build_pure_strokes({line(square, 0, true)}, {});
    ASSERT_EQ(r.strokes.size(), 4u);
    for (const core::StrokeGeometry& g : r.strokes) {
        EXPECT_FALSE(g.closed);
        EXPECT_EQ(g.ends, (Ends{A, A}));
        EXPECT_NEAR(g.length_px(), 40.0, 1e-9);
    }
}

TEST(PureStrokes, JunctionLinksTheLongestStrokeToItsSmoothestContinuation) {
    // Three polylines meet at the origin: a long one from the left, a nearly straight
    // continuation to the right and a branch going down. The long one continues to the right.
    const std::vector<core::Polyline> lines = {
        line(segment({0, 0}, {0, 50}), 100),    // branch, 50 px
        line(segment({-100, 0}, {0, 0}), 200),  // main, 100 px
        line(segment({0, 0}, {80, 6}), 300),    // continuation, 80 px, turns 4 degrees
    };
    const core::PureStrokes r = core::build_pure_strokes(lines, {});
    EXPECT_EQ(r.links, 1u);
    ASSERT_EQ(r.strokes.size(), 2u);
    const core::StrokeGeometry& branch = r.strokes[0];
    const core::StrokeGeometry& main = r.strokes[1];
    EXPECT_EQ(branch.ends, (Ends{C, S}));
    EXPECT_EQ(main.pure_stroke_count, 2u);
    EXPECT_EQ(main.ends, (Ends{S, S}));
    EXPECT_NEAR(main.length_px(), 100.0 + glm::length(dvec2(80, 6)), 1e-9);
    EXPECT_EQ(main.edges.size(), lines[1].edges.size() + lines[2].edges.size());
    for (size_t i = 1; i < main.points_px.size(); ++i) EXPECT_GT(main.points_px[i].x, main.points_px[i - 1].x);
}

TEST(PureStrokes, JunctionOfManyEndsLinksEachToTheOneOppositeIt) {
    // 64 rays from one point (more ends than are searched pair by pair): each ray continues into
    // the one pointing the opposite way, 32 straight strokes through the centre.
    constexpr int kRays = 64;
    const dvec2 centre(200.0, 200.0);
    std::vector<core::Polyline> rays;
    for (int k = 0; k < kRays; ++k) {
        const double a = 2.0 * std::numbers::pi * k / kRays, length = 100.0 + k;
        rays.push_back(line(segment(centre, centre + length * dvec2(std::cos(a), std::sin(a))), uint32_t(k) * 100));
    }
    const core::PureStrokes r = core::build_pure_strokes(rays, {});
    EXPECT_EQ(r.pure_strokes, size_t(kRays));
    EXPECT_EQ(r.links, size_t(kRays / 2));
    ASSERT_EQ(r.strokes.size(), size_t(kRays / 2));
    for (const core::StrokeGeometry& s : r.strokes) {
        EXPECT_EQ(s.pure_stroke_count, 2u);
        EXPECT_EQ(s.ends, (Ends{S, S}));
        EXPECT_NEAR(glm::length(s.points_px.back() - s.points_px.front()), s.length_px(), 1e-6);
    }
}

TEST(PureStrokes, TwoEndsMeetingSharplyAreCorners) {
    const std::vector<core::Polyline> lines = {line(segment({-50, 0}, {0, 0}), 0), line(segment({0, 0}, {0, 50}), 100)};
    const core::PureStrokes r = core::build_pure_strokes(lines, {});
    EXPECT_EQ(r.links, 0u);
    ASSERT_EQ(r.strokes.size(), 2u);
    EXPECT_EQ(r.strokes[0].ends, (Ends{S, A}));
    EXPECT_EQ(r.strokes[1].ends, (Ends{A, S}));
}

TEST(PureStrokes, SmoothMeetingOfDifferentKindsIsAJunction) {
    const std::vector<core::Polyline> lines = {line(segment({-50, 0}, {0, 0}), 0),
                                               line(segment({0, 0}, {50, 0}), 100, false, core::LineKind::kBoundary)};
    const core::PureStrokes r = core::build_pure_strokes(lines, {});
    EXPECT_EQ(r.links, 0u);
    ASSERT_EQ(r.strokes.size(), 2u);
    EXPECT_EQ(r.strokes[0].ends, (Ends{S, C}));
    EXPECT_EQ(r.strokes[1].ends, (Ends{C, S}));
}

TEST(PureStrokes, EndOnAnotherStrokeIsATJunction) {
    // A line that stops 0.3 px short of another, as where it passes behind it.
    const std::vector<core::Polyline> lines = {line(segment({0, 0}, {100, 0}), 0),
                                               line(segment({50, 0.3}, {50, 60}), 100)};
    const core::PureStrokes r = core::build_pure_strokes(lines, {});
    ASSERT_EQ(r.strokes.size(), 2u);
    EXPECT_EQ(r.strokes[0].ends, (Ends{S, S}));
    EXPECT_EQ(r.strokes[1].ends, (Ends{C, S}));
}

TEST(PureStrokes, ChainsLinkedIntoACycleAreALoop) {
    // Two halves of a circle meeting smoothly at both ends.
    const std::vector<dvec2> c = circle({0, 0}, 40, 48);
    const std::vector<dvec2> top(c.begin(), c.begin() + 25), bottom(c.begin() + 24, c.end());
    const core::PureStrokes r = core::build_pure_strokes({line(top, 0), line(bottom, 100)}, {});
    EXPECT_EQ(r.links, 2u);
    ASSERT_EQ(r.strokes.size(), 1u);
    EXPECT_TRUE(r.strokes[0].closed);
    EXPECT_EQ(r.strokes[0].ends, (Ends{L, L}));
    EXPECT_EQ(r.strokes[0].points_px.size(), c.size());
}

TEST(PureStrokes, EndTypeNames) {
    EXPECT_STREQ(core::stroke_end_name(S), "S");
    EXPECT_STREQ(core::stroke_end_name(A), "A");
    EXPECT_STREQ(core::stroke_end_name(C), "C");
    EXPECT_STREQ(core::stroke_end_name(L), "L");
}

}  // namespace
}  // namespace inkline
