// SPDX-License-Identifier: MIT
#include "core/strokes/stroke_coherence.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <vector>

namespace inkline {
namespace {

using glm::dvec2;

// A straight stroke from a to b, sampled every kTraceSpacingPx, on edge_count edges of equal
// length from first_edge on.
core::StrokeCandidate candidate(dvec2 a, dvec2 b, uint32_t first_edge, uint32_t edge_count = 10) {
    core::StrokeCandidate c;
    c.length_px = glm::length(b - a);
    for (uint32_t e = 0; e <= edge_count; ++e) {
        const dvec2 p = a + (b - a) * (double(e) / edge_count);
        c.geometry.points_px.push_back(p);
        c.geometry.points_world.push_back(glm::dvec3(p, 0.0));
        if (e < edge_count) c.geometry.edges.push_back(first_edge + e);
    }
    for (double s = 0.0; s <= c.length_px + 1e-9; s += core::kTraceSpacingPx) {
        c.samples_px.push_back(a + (b - a) * (s / c.length_px));
        c.samples_arc.push_back(s);
    }
    return c;
}

// What the state remembers of a candidate given an id and u offset.
core::StrokeTrace trace(const core::StrokeCandidate& c, uint32_t id, double u_offset) {
    core::StrokeTrace t;
    t.id = id;
    t.length_px = c.length_px;
    t.edges = c.geometry.edges;
    t.samples_px = c.samples_px;
    for (double s : c.samples_arc) t.samples_u.push_back(u_offset + s);
    return t;
}

TEST(StrokeCoherence, FirstFrameGetsFreshIdsInOrder) {
    const core::StrokeCoherence state({}, 7);
    const auto m = state.match({candidate({0, 0}, {100, 0}, 0), candidate({0, 50}, {100, 50}, 100)});
    ASSERT_EQ(m.size(), 2u);
    EXPECT_EQ(m[0].id, 7u);
    EXPECT_EQ(m[1].id, 8u);
    EXPECT_FALSE(m[0].inherited || m[1].inherited);
}

TEST(StrokeCoherence, SameStrokeKeepsIdAndParameter) {
    const core::StrokeCandidate c = candidate({0, 0}, {100, 0}, 0);
    const core::StrokeCoherence state({trace(c, 42, 17.0)}, 43);
    const auto m = state.match({c});
    ASSERT_EQ(m.size(), 1u);
    EXPECT_EQ(m[0].id, 42u);
    EXPECT_TRUE(m[0].inherited);
    EXPECT_FALSE(m[0].reverse);
    EXPECT_NEAR(m[0].u_offset, 17.0, 1e-9);
}

TEST(StrokeCoherence, ReversedStrokeIsTurnedBack) {
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0), 3, 0.0)}, 4);
    const auto m = state.match({candidate({100, 0}, {0, 0}, 0)});
    EXPECT_EQ(m[0].id, 3u);
    EXPECT_TRUE(m[0].reverse);
    EXPECT_NEAR(m[0].u_offset, 0.0, 1e-9);
}

TEST(StrokeCoherence, ParameterStaysOnTheImageWhenAStrokeGrowsAndMoves) {
    // Last frame: x in [0, 100], u = x. Now the stroke moved 3 px down and grew 10 px at its start:
    // u must stay attached, so the new start gets u = -10.
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0), 1, 0.0)}, 2);
    const auto m = state.match({candidate({-10, 3}, {100, 3}, 500)});
    EXPECT_EQ(m[0].id, 1u) << "no shared edge, but it lies close";
    EXPECT_FALSE(m[0].reverse);
    EXPECT_NEAR(m[0].u_offset, -10.0, 1.01);
}

TEST(StrokeCoherence, SplitStrokeKeepsItsIdOnTheLargerPart) {
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0, 10), 5, 0.0)}, 6);
    const auto m = state.match({candidate({0, 0}, {30, 0}, 0, 3), candidate({40, 0}, {100, 0}, 4, 6)});
    EXPECT_EQ(m[1].id, 5u);
    EXPECT_TRUE(m[1].inherited);
    EXPECT_EQ(m[0].id, 6u);
    EXPECT_FALSE(m[0].inherited);
    EXPECT_NEAR(m[1].u_offset, 40.0, 1e-9);
}

TEST(StrokeCoherence, DistantStrokeIsNew) {
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0), 5, 0.0)}, 6);
    const auto m = state.match({candidate({0, 300}, {100, 300}, 1000)});
    EXPECT_EQ(m[0].id, 6u);
    EXPECT_FALSE(m[0].inherited);
}

TEST(StrokeCoherence, KindsDoNotMix) {
    core::StrokeCandidate c = candidate({0, 0}, {100, 0}, 0);
    const core::StrokeCoherence state({trace(c, 5, 0.0)}, 6);
    c.geometry.kind = core::LineKind::kCrease;
    EXPECT_FALSE(state.match({c})[0].inherited);
    c.geometry.visible = false;
    EXPECT_FALSE(state.match({c})[0].inherited);
}

TEST(StrokeCoherence, HiddenLineComingIntoViewKeepsItsId) {
    // Last frame the line was hidden (written with lines.hidden); now it shows, moved 4 px and
    // on the neighbouring mesh edges, as a silhouette sliding over the mesh does.
    core::StrokeTrace hidden = trace(candidate({0, 0}, {100, 0}, 0), 5, 10.0);
    hidden.visible = false;
    const core::StrokeCoherence state({hidden}, 6);
    const auto m = state.match({candidate({0, 4}, {100, 4}, 500)});
    EXPECT_EQ(m[0].id, 5u);
    EXPECT_TRUE(m[0].inherited);
    EXPECT_NEAR(m[0].u_offset, 10.0, 1e-9);
}

TEST(StrokeCoherence, SameVisibilityComesFirst) {
    // A visible line with a hidden one right behind it, both seen again, moved and on other
    // edges: each keeps its own id, although the hidden stroke of last frame overlaps the
    // visible one now (100 px) more than the visible one (60 px) or the hidden one (80 px) does.
    core::StrokeTrace visible = trace(candidate({0, 0}, {60, 0}, 0), 1, 0.0);
    core::StrokeTrace hidden = trace(candidate({0, 1}, {100, 1}, 100), 2, 0.0);
    hidden.visible = false;
    const core::StrokeCoherence state({visible, hidden}, 3);
    core::StrokeCandidate now_visible = candidate({0, 0}, {100, 0}, 200);
    core::StrokeCandidate now_hidden = candidate({0, 6}, {80, 6}, 300);
    now_hidden.geometry.visible = false;
    const auto m = state.match({now_visible, now_hidden});
    EXPECT_EQ(m[0].id, 1u);
    EXPECT_EQ(m[1].id, 2u);
}

TEST(StrokeCoherence, SameVisibilityComesFirstOverEveryRadius) {
    // A visible line sweeping fast (16 px since last frame: only the wider radius finds it) and
    // a small hidden piece right on last frame's line: the visible line keeps the id.
    const core::StrokeCoherence state({trace(candidate({0, 0}, {200, 0}, 0), 4, 0.0)}, 5);
    core::StrokeCandidate piece = candidate({100, 1}, {110, 1}, 600, 1);
    piece.geometry.visible = false;
    const auto m = state.match({candidate({0, 16}, {200, 16}, 500), piece});
    EXPECT_EQ(m[0].id, 4u);
    EXPECT_EQ(m[1].id, 5u);
}

TEST(StrokeCoherence, SideSamplesPassOverATangleAtTheEnd) {
    // The stroke runs back and forth near its end (a zig-zag tangle), then away along x: its
    // side is sampled where it first gets 2, 4, ... 12 px from the end.
    const std::vector<dvec2> zigzag{{0, 0}, {3, 0}, {1, 0}, {3.5, 0}, {0.5, 0}, {20, 0}};
    const std::vector<dvec2> side = core::side_samples(zigzag, 0);
    ASSERT_EQ(side.size(), 6u);
    for (size_t i = 0; i < side.size(); ++i) EXPECT_NEAR(side[i].x, 2.0 * double(i + 1), 1e-9) << i;
    std::vector<dvec2> reversed(zigzag.rbegin(), zigzag.rend());
    EXPECT_EQ(core::side_samples(reversed, 1), side);
}

TEST(StrokeCoherence, LoopStartStaysPut) {
    // A square loop seen twice: the start stays where it was.
    core::StrokeCandidate loop;
    loop.geometry.closed = true;
    const std::vector<dvec2> corners = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    for (int side = 0; side < 4; ++side) {
        for (int i = 0; i < 50; ++i) {
            loop.samples_px.push_back(corners[size_t(side)] +
                                      (corners[size_t((side + 1) % 4)] - corners[size_t(side)]) * (i / 50.0));
            loop.samples_arc.push_back(100.0 * side + 2.0 * i);
        }
    }
    loop.length_px = 400.0;
    core::StrokeTrace t = trace(loop, 9, 0.0);
    t.closed = true;
    t.start_px = {100, 40};
    const core::StrokeCoherence state({t}, 10);
    const auto m = state.match({loop});
    ASSERT_TRUE(m[0].start_px.has_value());
    EXPECT_LT(glm::length(*m[0].start_px - dvec2(100, 40)), 1e-9);
}

}  // namespace
}  // namespace inkline

namespace inkline {
namespace {

TEST(StrokeCoherence, NearestSampleIsTheNearestOfAllInCrowdedAndSparsePlaces) {
    // Random short strokes, dense in one corner and sparse elsewhere, some hidden and some of
    // another kind, against a search over every sample: the nearest visible one of the kind
    // within kMatchRadiusPx, ties to the lower stroke and sample.
    uint32_t seed = 7;
    auto random = [&] {
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 24);
    };
    std::vector<core::StrokeTrace> traces;
    for (uint32_t s = 0; s < 3000; ++s) {
        const double spread = s % 3 ? 120.0 : 2000.0;
        const dvec2 a(spread * random() - 300.0, spread * random() - 300.0);
        const dvec2 b = a + dvec2(40.0 * random() - 20.0, 40.0 * random() - 20.0);
        core::StrokeTrace t = trace(candidate(a, b, 10 * s), s, 0.0);
        t.visible = s % 5 != 0;
        t.kind = s % 7 == 0 ? core::LineKind::kCrease : core::LineKind::kSilhouette;
        traces.push_back(std::move(t));
    }
    std::vector<dvec2> points;
    for (int i = 0; i < 4000; ++i) {
        const double spread = i % 2 ? 150.0 : 2100.0;
        points.push_back({spread * random() - 320.0, spread * random() - 320.0});
    }
    points.push_back(traces[1].samples_px[0]);  // exactly on a sample
    const core::StrokeCoherence state(traces, 3000);
    const std::vector<core::StrokeCoherence::Nearest> got = state.nearest_visible(points, core::LineKind::kSilhouette);
    ASSERT_EQ(got.size(), points.size());
    size_t found = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        double best = HUGE_VAL;
        int64_t id = -1;
        double u = 0.0;
        for (const core::StrokeTrace& t : traces) {
            if (!t.visible || t.kind != core::LineKind::kSilhouette) continue;
            for (size_t k = 0; k < t.samples_px.size(); ++k) {
                const double d = glm::length(t.samples_px[k] - points[i]);
                if (d <= core::kMatchRadiusPx && d < best) best = d, id = t.id, u = t.samples_u[k];
            }
        }
        found += id >= 0;
        ASSERT_EQ(got[i].id, id) << "point " << i;
        ASSERT_EQ(got[i].u, u) << "point " << i;
    }
    EXPECT_GT(found, points.size() / 3);
    EXPECT_LT(found, points.size());
}

}  // namespace
}  // namespace inkline
