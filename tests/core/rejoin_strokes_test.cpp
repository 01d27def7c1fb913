// SPDX-License-Identifier: MIT
#include "core/strokes/rejoin_strokes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tests/core/repair_shapes.h"

namespace inkline {
namespace {

using glm::dvec2;
using repair_shapes::line;
using repair_shapes::through;
using repair_shapes::trace;
using repair_shapes::trace_along;

// A stroke that last frame was one, now cut at a tangle: a 1 px visible fragment between two
// occluded bits, and a third line leaving the tangle (the junction bridging cannot cross).
struct Tangle {
    std::vector<core::StrokeGeometry> strokes{line({0, 0}, {40, 0}, true, 0), line({41, 0}, {42, 0}, true, 60),
                                              line({43, 0}, {83, 0}, true, 100), line({43, 0}, {43, 30}, true, 200)};
    std::vector<core::StrokeGeometry> occluded{line({40, 0}, {41, 0}, false, 50), line({42, 0}, {43, 0}, false, 70)};
};

// The strokes after rejoin_split_strokes, those merged away (left without points) removed.
std::vector<core::StrokeGeometry> rejoin(std::vector<core::StrokeGeometry> strokes,
                                         const std::vector<core::StrokeGeometry>& occluded,
                                         const core::StrokeCoherence& memory, size_t* r_count = nullptr) {
    core::OccludedUse use;
    const size_t n = core::rejoin_split_strokes(strokes, occluded, use, memory, core::gap_bridge_options(4.8));
    if (r_count) *r_count = n;
    std::erase_if(strokes, [](const core::StrokeGeometry& g) { return g.points_px.empty(); });
    return strokes;
}

std::vector<core::StrokeGeometry> rejoin(const Tangle& t, const core::StrokeCoherence& memory,
                                         size_t* r_count = nullptr) {
    return rejoin(t.strokes, t.occluded, memory, r_count);
}

TEST(StrokeRejoin, StrokeSplitAtATangleIsJoinedAgainThroughIt) {
    // Last frame: one stroke along the line (id 7) and the line leaving upwards (id 8).
    const core::StrokeCoherence memory({trace({0, 0.5}, {90, 0.5}, 7), trace({43.5, 0}, {43.5, 30}, 8)}, 9);
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = rejoin(Tangle{}, memory, &joins);
    EXPECT_GE(joins, 1u);
    ASSERT_EQ(out.size(), 2u);
    const core::StrokeGeometry& g = out[0];
    EXPECT_EQ(g.points_px.front(), dvec2(0, 0));
    EXPECT_EQ(g.points_px.back(), dvec2(83, 0));
    ASSERT_EQ(g.bridged.size(), g.edges.size());
    for (size_t k = 0; k < g.edges.size(); ++k) {
        // The occluded bits are marked bridged; the fragment and both sides stay visible.
        const bool occluded = g.edges[k] == 50 || g.edges[k] == 70;
        EXPECT_EQ(g.bridged[k], occluded ? 1 : 0) << "edge " << g.edges[k];
    }
    EXPECT_EQ(std::count(g.edges.begin(), g.edges.end(), 60u), 1) << "the fragment is taken in once";
    EXPECT_EQ(out[1].points_px.front(), dvec2(43, 0)) << "the line leaving the tangle stays as it was";
    EXPECT_EQ(out[1].points_px.back(), dvec2(43, 30));
}

// Without memory, or where last frame drew two strokes, nothing is joined.
TEST(StrokeRejoin, OnlyWhatLastFrameDrewAsOneStroke) {
    EXPECT_EQ(rejoin(Tangle{}, {}).size(), 4u);
    const core::StrokeCoherence two(
        {trace({0, 0.5}, {40, 0.5}, 3), trace({44, 0.5}, {90, 0.5}, 4), trace({43.5, 0}, {43.5, 30}, 8)}, 9);
    const std::vector<core::StrokeGeometry> out = rejoin(Tangle{}, two);
    EXPECT_TRUE(std::none_of(out.begin(), out.end(), [](const core::StrokeGeometry& g) {
        return g.points_px.front() == dvec2(0, 0) && g.points_px.back() == dvec2(83, 0);
    }));
}

// Two parts of one stroke of last frame that lay far apart along it (a long detour between
// them) are not its neighbours: they stay apart even where they now nearly touch.
TEST(StrokeRejoin, PartsFarApartAlongLastFramesStrokeStayApart) {
    const core::StrokeTrace detour = trace_along({{0, 0.5}, {40, 0.5}, {40, 200}, {44, 200}, {44, 0.5}, {90, 0.5}}, 7);
    const core::StrokeCoherence memory({detour, trace({43.5, 0}, {43.5, 30}, 8)}, 9);
    const std::vector<core::StrokeGeometry> out = rejoin(Tangle{}, memory);
    EXPECT_TRUE(std::none_of(out.begin(), out.end(), [](const core::StrokeGeometry& g) {
        return g.points_px.front() == dvec2(0, 0) && g.points_px.back() == dvec2(83, 0);
    }));
}

// A zig-zag silhouette folds back along itself: the line runs right to x = 50, back to x = 38,
// and right again. The fold's edges are not silhouette edges this frame, so two strokes run over
// each other, their ends 12 px apart, farther than any gap is bridged.
TEST(StrokeRejoin, StrokesSplitAtAFoldAreJoinedAcrossIt) {
    const std::vector<core::StrokeGeometry> fold{line({0, 0}, {50, 0}, true, 0),
                                                 line({38, 0.5}, {100, 0.5}, true, 100)};
    const core::StrokeCoherence memory({trace({0, 0.25}, {100, 0.25}, 7)}, 8);
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = rejoin(fold, {}, memory, &joins);
    EXPECT_EQ(joins, 1u);
    ASSERT_EQ(out.size(), 1u);
    const core::StrokeGeometry& g = out[0];
    EXPECT_EQ(g.points_px.front(), dvec2(0, 0));
    EXPECT_EQ(g.points_px.back(), dvec2(100, 0.5));
    ASSERT_EQ(g.bridged.size(), g.edges.size());
    EXPECT_EQ(std::count(g.bridged.begin(), g.bridged.end(), uint8_t(1)), 1) << "the jump across the fold";
    const auto jump = size_t(std::find(g.bridged.begin(), g.bridged.end(), uint8_t(1)) - g.bridged.begin());
    EXPECT_EQ(g.points_px[jump], dvec2(50, 0));
    EXPECT_EQ(g.points_px[jump + 1], dvec2(38, 0.5));
    EXPECT_EQ(g.points_px.size(), fold[0].points_px.size() + fold[1].points_px.size()) << "every exact point kept";
}

// A line that leaves the fold's end running the same way as the stroke beside it is a branch,
// not the stroke's continuation; and without memory nothing is joined.
TEST(StrokeRejoin, ABranchBesideAStrokeIsNotAFold) {
    const std::vector<core::StrokeGeometry> branch{line({0, 0}, {50, 0}, true, 0),
                                                   line({38, 0.5}, {0, 0.5}, true, 100)};
    const core::StrokeCoherence memory({trace({0, 0.25}, {100, 0.25}, 7)}, 8);
    EXPECT_EQ(rejoin(branch, {}, memory).size(), 2u);
    const std::vector<core::StrokeGeometry> fold{line({0, 0}, {50, 0}, true, 0),
                                                 line({38, 0.5}, {100, 0.5}, true, 100)};
    EXPECT_EQ(rejoin(fold, {}, {}).size(), 2u);
}

TEST(StrokeRejoin, EveryFoldOfManyAcrossTheImageIsJoined) {
    // The fold of StrokesSplitAtAFoldAreJoinedAcrossIt 400 times, 150 px apart on a lattice that
    // also runs over negative coordinates, each remembered as a stroke of its own: ends are
    // compared with their neighbours only, and no fold may be missed or joined to another.
    std::vector<core::StrokeGeometry> strokes;
    std::vector<core::StrokeTrace> traces;
    constexpr int kSide = 20;
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) {
            const dvec2 o(150.0 * (x - kSide / 2), 150.0 * (y - kSide / 2));
            const auto id = uint32_t(y * kSide + x);
            strokes.push_back(line(o + dvec2(0, 0), o + dvec2(50, 0), true, 1000 * id));
            strokes.push_back(line(o + dvec2(38, 0.5), o + dvec2(100, 0.5), true, 1000 * id + 500));
            traces.push_back(trace(o + dvec2(0, 0.25), o + dvec2(100, 0.25), id));
        }
    }
    const core::StrokeCoherence memory(traces, kSide * kSide);
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = rejoin(strokes, {}, memory, &joins);
    EXPECT_EQ(joins, size_t(kSide * kSide));
    ASSERT_EQ(out.size(), size_t(kSide * kSide));
    for (const core::StrokeGeometry& g : out) {
        EXPECT_EQ(g.points_px.back() - g.points_px.front(), dvec2(100, 0.5));
        EXPECT_EQ(std::count(g.bridged.begin(), g.bridged.end(), uint8_t(1)), 1);
    }
}

}  // namespace
}  // namespace inkline
