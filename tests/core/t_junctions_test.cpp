// SPDX-License-Identifier: MIT
#include "core/strokes/t_junctions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "tests/core/repair_shapes.h"

namespace inkline {
namespace {

using glm::dvec2;
using repair_shapes::line;
using repair_shapes::through;
using repair_shapes::trace;
using repair_shapes::trace_along;

// A T-junction: a stroke ends 1 px beside another one's interior. Last frame, one stroke (id 7)
// ran along the left part of the crossing line and turned up into the ending stroke; the right
// part of the crossing line was a stroke of its own (id 9).
struct Tee {
    std::vector<core::StrokeGeometry> strokes{line({0, 0}, {50, 0}, true, 0), line({30, 1}, {30, 40}, true, 100)};
    Tee() { strokes[1].ends = {core::StrokeEnd::kJunction, core::StrokeEnd::kFree}; }
};

std::vector<core::StrokeGeometry> join_tees(std::vector<core::StrokeGeometry> strokes,
                                            const core::StrokeCoherence& memory, size_t* r_count = nullptr) {
    const size_t n = core::join_at_t_junctions(strokes, memory, core::gap_bridge_options(4.8));
    if (r_count) *r_count = n;
    std::erase_if(strokes, [](const core::StrokeGeometry& g) { return g.points_px.empty(); });
    return strokes;
}

TEST(StrokeTee, StrokeEndingOnAnotherIsJoinedToThePartLastFrameContinued) {
    const core::StrokeCoherence memory({trace_along({{0, 0}, {30, 0}, {30, 40}}, 7), trace({31, 0}, {50, 0}, 9)}, 10);
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = join_tees(Tee{}.strokes, memory, &joins);
    EXPECT_EQ(joins, 1u);
    ASSERT_EQ(out.size(), 2u);
    const auto turn = std::find_if(out.begin(), out.end(), [](const core::StrokeGeometry& g) {
        return g.points_px.front() == dvec2(0, 0) || g.points_px.back() == dvec2(0, 0);
    });
    ASSERT_NE(turn, out.end());
    core::StrokeGeometry g = *turn;
    if (g.points_px.front() != dvec2(0, 0)) g.reverse();
    EXPECT_EQ(g.points_px.back(), dvec2(30, 40));
    ASSERT_EQ(g.bridged.size(), g.edges.size());
    EXPECT_EQ(std::count(g.bridged.begin(), g.bridged.end(), uint8_t(1)), 1) << "the 1 px jump";
    const auto jump = size_t(std::find(g.bridged.begin(), g.bridged.end(), uint8_t(1)) - g.bridged.begin());
    EXPECT_EQ(g.points_px[jump], dvec2(30, 0));
    EXPECT_EQ(g.points_px[jump + 1], dvec2(30, 1));
    EXPECT_EQ(g.ends[1], core::StrokeEnd::kFree);

    const core::StrokeGeometry& rest = turn == out.begin() ? out[1] : out[0];
    EXPECT_EQ(rest.points_px.front(), dvec2(30, 0)) << "the rest of the crossing line, cut where the stroke ends";
    EXPECT_EQ(rest.points_px.back(), dvec2(50, 0));
    EXPECT_EQ(rest.ends[0], core::StrokeEnd::kJunction);
}

// Where last frame's stroke ran straight along the crossing line, or without memory, the
// crossing line stays whole.
TEST(StrokeTee, CrossingLineLastFrameDrewWholeStaysWhole) {
    const core::StrokeCoherence straight({trace({0, 0}, {50, 0}, 7), trace({30, 2}, {30, 40}, 8)}, 9);
    const std::vector<core::StrokeGeometry> out = join_tees(Tee{}.strokes, straight);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].points_px.size(), Tee{}.strokes[0].points_px.size());
    EXPECT_EQ(join_tees(Tee{}.strokes, {}).size(), 2u);
}

// The stroke of `out` with an end at (0, 0), turned to start there (none: no points).
core::StrokeGeometry from_origin(const std::vector<core::StrokeGeometry>& out) {
    for (core::StrokeGeometry g : out) {
        if (g.points_px.back() == dvec2(0, 0)) g.reverse();
        if (g.points_px.front() == dvec2(0, 0)) return g;
    }
    return {};
}

TEST(StrokeTee, AnEndBetweenTheCrossingStrokesPointsIsOnIt) {
    // The crossing stroke has a point every 5 px; the branch ends 1 px beside it, midway between
    // two of them (2.7 px from either).
    core::StrokeGeometry crossing;
    crossing.visible = true;
    for (int i = 0; i <= 10; ++i) {
        crossing.points_px.push_back(dvec2(5.0 * i, 0.0));
        crossing.points_world.push_back(glm::dvec3(5.0 * i, 0.0, 0.0));
        if (i < 10) crossing.edges.push_back(uint32_t(i));
    }
    std::vector<core::StrokeGeometry> strokes{crossing, line({32.5, 1}, {32.5, 40}, true, 100)};
    strokes[1].ends = {core::StrokeEnd::kJunction, core::StrokeEnd::kFree};
    const core::StrokeCoherence memory({trace_along({{0, 0}, {32.5, 0}, {32.5, 40}}, 7), trace({34, 0}, {50, 0}, 9)},
                                       10);
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = join_tees(strokes, memory, &joins);
    EXPECT_EQ(joins, 1u);
    ASSERT_EQ(out.size(), 2u);
    const core::StrokeGeometry g = from_origin(out);
    ASSERT_FALSE(g.points_px.empty());
    EXPECT_EQ(g.points_px.back(), dvec2(32.5, 40)) << "joined into the branch";
}

TEST(StrokeTee, AFragmentNearerTheEndDoesNotHideTheCrossingStroke) {
    // A 2 px fragment of a tangle lies between the branch's end and the crossing stroke.
    std::vector<core::StrokeGeometry> strokes = Tee{}.strokes;
    strokes.push_back(line({29, 1.5}, {31, 1.5}, true, 200));
    strokes.back().ends = {core::StrokeEnd::kJunction, core::StrokeEnd::kJunction};
    const core::StrokeCoherence memory({trace_along({{0, 0}, {30, 0}, {30, 40}}, 7), trace({31, 0}, {50, 0}, 9)}, 10);
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = join_tees(strokes, memory, &joins);
    EXPECT_EQ(joins, 1u);
    const core::StrokeGeometry g = from_origin(out);
    ASSERT_FALSE(g.points_px.empty());
    EXPECT_EQ(g.points_px.back(), dvec2(30, 40)) << "joined into the branch";
}

// Last frame's stroke ran on past the junction and turned off along the branch. The crossing
// stroke's stub goes on straight beside the branch's start, nearer last frame's line there, and
// stops: the branch is joined, the stub left off. A branch that stops sooner than the stub is not.
TEST(StrokeTee, AStubBesideTheBranchLastFrameTookIsLeftOff) {
    const core::StrokeCoherence memory({trace_along({{0, 0}, {45, 0}, {80, 40}}, 7)}, 8);
    auto tee = [](const std::vector<dvec2>& branch) {
        std::vector<core::StrokeGeometry> strokes{line({0, 0}, {45, 0}, true, 0), through(branch, 100)};
        strokes[1].ends = {core::StrokeEnd::kJunction, core::StrokeEnd::kFree};
        return strokes;
    };
    size_t joins = 0;
    std::vector<core::StrokeGeometry> out = join_tees(tee({{30, 1}, {42, 3}, {80, 40}}), memory, &joins);
    EXPECT_EQ(joins, 1u);
    ASSERT_EQ(out.size(), 2u);
    for (core::StrokeGeometry& g : out) {
        if (g.points_px.front().x > g.points_px.back().x) g.reverse();
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.length_px() > b.length_px(); });
    EXPECT_EQ(out[0].points_px.front(), dvec2(0, 0));
    EXPECT_EQ(out[0].points_px.back(), dvec2(80, 40)) << "the branch joined";
    EXPECT_EQ(out[1].points_px.front(), dvec2(30, 0));
    EXPECT_EQ(out[1].points_px.back(), dvec2(45, 0)) << "the stub on its own";

    out = join_tees(tee({{30, 1}, {38, 2}}), memory, &joins);
    EXPECT_EQ(joins, 0u);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].points_px.size(), 46u) << "the crossing stroke stays whole";
}

TEST(StrokeTee, AnEndWhereHundredsOfStrokesCrossJoinsThePartLastFrameContinued) {
    // The T-junction above, with 200 more strokes crossing the line where the stroke ends on it
    // (as where thousands of faces share an edge): each is a candidate, and last frame drew each
    // as a stroke of its own; they run within 25 degrees of the line, across the ending stroke.
    std::vector<core::StrokeGeometry> strokes = Tee{}.strokes;
    std::vector<core::StrokeTrace> memory{trace_along({{0, 0}, {30, 0}, {30, 40}}, 7), trace({31, 0}, {50, 0}, 9)};
    for (uint32_t i = 0; i < 200; ++i) {
        const double a = (5.0 + 20.0 * double(i % 100) / 100.0 + (i < 100 ? 0.0 : 150.0)) * std::numbers::pi / 180.0;
        const dvec2 d = 20.0 * dvec2(std::cos(a), std::sin(a));
        strokes.push_back(line(dvec2(30, 0) - d, dvec2(30, 0) + d, true, 1000 + 100 * i));
        memory.push_back(trace(dvec2(30, 0) - d, dvec2(30, 0) + d, 100 + i));
    }
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = join_tees(strokes, core::StrokeCoherence(memory, 300), &joins);
    EXPECT_EQ(joins, 1u);
    ASSERT_EQ(out.size(), 202u);
    const core::StrokeGeometry g = from_origin(out);
    ASSERT_FALSE(g.points_px.empty());
    EXPECT_EQ(g.points_px.back(), dvec2(30, 40)) << "joined to the part last frame's stroke 7 continued";
    // In place: the joined stroke where the crossing line was, the ending one gone, the rest last.
    for (size_t i = 0; i < 200; ++i) ASSERT_EQ(out[1 + i].points_px, strokes[2 + i].points_px) << "crossing stroke " << i;
    EXPECT_EQ(out.back().points_px.front(), dvec2(30, 0));
    EXPECT_EQ(out.back().points_px.back(), dvec2(50, 0));
}

}  // namespace
}  // namespace inkline
