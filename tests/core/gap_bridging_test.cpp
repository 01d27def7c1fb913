// SPDX-License-Identifier: MIT
#include "core/strokes/gap_bridging.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <cmath>
#include <optional>
#include <vector>

namespace inkline {
namespace {

using glm::dvec2;

// A straight stroke from a to b with a point every px, on edges first_edge...
core::StrokeGeometry line(dvec2 a, dvec2 b, bool visible, uint32_t first_edge) {
    core::StrokeGeometry g;
    g.visible = visible;
    const int n = std::max(1, int(std::ceil(glm::length(b - a))));
    for (int i = 0; i <= n; ++i) {
        const dvec2 p = i == n ? b : a + (b - a) * (double(i) / n);
        g.points_px.push_back(p);
        g.points_world.push_back(glm::dvec3(p, 0.0));
        if (i < n) g.edges.push_back(first_edge + uint32_t(i));
    }
    return g;
}

// Last frame remembered visible strokes from a to b with these ids.
core::StrokeTrace trace(dvec2 a, dvec2 b, uint32_t id) {
    core::StrokeTrace t;
    t.id = id;
    t.length_px = glm::length(b - a);
    for (double s = 0.0; s <= t.length_px + 1e-9; s += core::kTraceSpacingPx) {
        t.samples_px.push_back(a + (b - a) * (s / t.length_px));
        t.samples_u.push_back(s);
    }
    return t;
}

// Last frame remembered a stroke along this path, with these ids, u running from its start.
core::StrokeTrace trace_along(const std::vector<dvec2>& path, uint32_t id) {
    core::StrokeTrace t;
    t.id = id;
    double u = 0.0;
    for (size_t i = 0; i + 1 < path.size(); ++i) {
        const double len = glm::length(path[i + 1] - path[i]);
        for (double s = 0.0; s < len; s += core::kTraceSpacingPx) {
            t.samples_px.push_back(path[i] + (path[i + 1] - path[i]) * (s / len));
            t.samples_u.push_back(u + s);
        }
        u += len;
    }
    t.length_px = u;
    return t;
}

// A visible stroke through these points, a point every px, on edges first_edge...
core::StrokeGeometry through(const std::vector<dvec2>& path, uint32_t first_edge) {
    core::StrokeGeometry g = line(path[0], path[1], true, first_edge);
    for (size_t i = 1; i + 1 < path.size(); ++i) {
        const core::StrokeGeometry next = line(path[i], path[i + 1], true, first_edge + uint32_t(g.edges.size()));
        g.points_px.insert(g.points_px.end(), next.points_px.begin() + 1, next.points_px.end());
        g.points_world.insert(g.points_world.end(), next.points_world.begin() + 1, next.points_world.end());
        g.edges.insert(g.edges.end(), next.edges.begin(), next.edges.end());
    }
    return g;
}

struct Bridged {
    std::vector<core::StrokeGeometry> strokes;  // empty ones (merged away) removed
    std::vector<uint8_t> used;
    size_t count = 0;
};

// Visible 0..40 and gap_px + 40.. along x, the gap between them occluded.
Bridged bridge_gap(double gap_px, const core::StrokeCoherence& coherence) {
    std::vector<core::StrokeGeometry> strokes{line({0, 0}, {40, 0}, true, 0),
                                              line({40 + gap_px, 0}, {80 + gap_px, 0}, true, 100)};
    const std::vector<core::StrokeGeometry> occluded{line({40, 0}, {40 + gap_px, 0}, false, 50)};
    Bridged r;
    r.count = core::bridge_hidden_gaps(strokes, occluded, coherence, core::gap_bridge_options(4.8), r.used);
    for (core::StrokeGeometry& g : strokes) {
        if (!g.points_px.empty()) r.strokes.push_back(std::move(g));
    }
    return r;
}

TEST(GapBridging, BoundsFollowTheBrush) {
    const core::GapBridgeOptions o = core::gap_bridge_options(4.8);
    EXPECT_DOUBLE_EQ(o.max_gap_px, 9.6);
    EXPECT_LT(o.split_gap_px, o.new_gap_px);
    EXPECT_LT(o.new_gap_px, o.max_gap_px);
}

// A short gap with no memory is drawn across; its points stay exact and are marked hidden.
TEST(GapBridging, ShortGapBecomesOneStrokeWithHiddenSegmentsMarked) {
    const Bridged r = bridge_gap(3.0, {});
    EXPECT_EQ(r.count, 1u);
    ASSERT_EQ(r.strokes.size(), 1u);
    EXPECT_EQ(r.used, std::vector<uint8_t>{1});
    const core::StrokeGeometry& g = r.strokes[0];
    EXPECT_TRUE(g.visible);
    EXPECT_FALSE(g.closed);
    ASSERT_EQ(g.hidden.size(), g.edges.size());
    ASSERT_EQ(g.points_px.size(), g.edges.size() + 1);
    EXPECT_EQ(g.points_px.front(), dvec2(0, 0));
    EXPECT_EQ(g.points_px.back(), dvec2(83, 0));
    for (size_t k = 0; k < g.edges.size(); ++k) {
        const bool in_gap = g.edges[k] >= 50 && g.edges[k] < 100;
        EXPECT_EQ(g.hidden[k], in_gap ? 1 : 0) << k;
        // Hidden segments lie exactly on the gap.
        if (in_gap) {
            EXPECT_GE(g.points_px[k].x, 40.0);
            EXPECT_LE(g.points_px[k + 1].x, 43.0);
        }
    }
}

// Without memory, a gap wider than new_gap_px stays; where last frame drew one stroke across
// the place, gaps up to max_gap_px are bridged; wider ones never are.
TEST(GapBridging, WiderGapsBridgedOnlyWhereLastFrameDrewOneStroke) {
    EXPECT_EQ(bridge_gap(7.0, {}).strokes.size(), 2u);
    const core::StrokeCoherence one({trace({0, 0.5}, {90, 0.5}, 7)}, 8);
    EXPECT_EQ(bridge_gap(7.0, one).strokes.size(), 1u);
    EXPECT_EQ(bridge_gap(9.0, one).strokes.size(), 1u);
    EXPECT_EQ(bridge_gap(11.0, one).strokes.size(), 2u);
}

// Where last frame split (two strokes met at the gap), the gap is kept unless it closes well
// below the bound: the split does not flicker either.
TEST(GapBridging, GapThatExistedLastFrameKeptUnlessItAlmostCloses) {
    const core::StrokeCoherence two({trace({0, 0}, {40, 0}, 3), trace({44, 0}, {84, 0}, 4)}, 5);
    EXPECT_EQ(bridge_gap(3.0, two).strokes.size(), 2u);
    EXPECT_EQ(bridge_gap(2.0, two).strokes.size(), 1u);
}

// A stroke whose two ends meet across a gap stays open: a loop made only by a flickering dip
// would come and go, and its start with it.
TEST(GapBridging, GapBetweenOneStrokesEndsStaysOpen) {
    core::StrokeGeometry open = line({0, 0}, {40, 0}, true, 0);
    for (const dvec2 p : {dvec2(40, 20), dvec2(0, 20), dvec2(0, 2)}) {
        open.points_px.push_back(p);
        open.points_world.push_back(glm::dvec3(p, 0.0));
        open.edges.push_back(uint32_t(open.edges.size()));
    }
    std::vector<core::StrokeGeometry> strokes{open};
    const std::vector<core::StrokeGeometry> occluded{line({0, 2}, {0, 0}, false, 500)};
    std::vector<uint8_t> used;
    EXPECT_EQ(core::bridge_hidden_gaps(strokes, occluded, {}, core::gap_bridge_options(4.8), used), 0u);
    ASSERT_EQ(strokes.size(), 1u);
    EXPECT_FALSE(strokes[0].closed);
    EXPECT_TRUE(strokes[0].hidden.empty());
}

// At a junction (two visible ends at the gap's end) there is no single stroke to continue.
TEST(GapBridging, NoBridgeIntoAJunction) {
    std::vector<core::StrokeGeometry> strokes{line({0, 0}, {40, 0}, true, 0), line({43, 0}, {80, 0}, true, 100),
                                              line({43, 0}, {43, 30}, true, 200)};
    const std::vector<core::StrokeGeometry> occluded{line({40, 0}, {43, 0}, false, 50)};
    std::vector<uint8_t> used;
    EXPECT_EQ(core::bridge_hidden_gaps(strokes, occluded, {}, core::gap_bridge_options(4.8), used), 0u);
    EXPECT_EQ(used, std::vector<uint8_t>{0});
}

// Two occluded parts leaving one visible end: the first bridges, the second finds the end taken
// and leaves the strokes alone (it must not join them anywhere else).
TEST(GapBridging, AnEndBridgesOnce) {
    std::vector<core::StrokeGeometry> strokes{line({0, 0}, {40, 0}, true, 0), line({43, 0}, {80, 0}, true, 100),
                                              line({40, 3}, {40, 40}, true, 200)};
    const std::vector<core::StrokeGeometry> occluded{line({40, 0}, {43, 0}, false, 50),
                                                     line({40, 0}, {40, 3}, false, 60)};
    std::vector<uint8_t> used;
    EXPECT_EQ(core::bridge_hidden_gaps(strokes, occluded, {}, core::gap_bridge_options(4.8), used), 1u);
    EXPECT_EQ(used, (std::vector<uint8_t>{1, 0}));
    EXPECT_EQ(strokes[0].points_px.back(), dvec2(80, 0));
    EXPECT_EQ(strokes[2].points_px.front(), dvec2(40, 3));
}

// Deterministic: the same strokes and memory give the same bridges.
TEST(GapBridging, SameInputSameResult) {
    const core::StrokeCoherence one({trace({0, 0.5}, {90, 0.5}, 7)}, 8);
    const Bridged a = bridge_gap(6.0, one), b = bridge_gap(6.0, one);
    ASSERT_EQ(a.strokes.size(), b.strokes.size());
    for (size_t i = 0; i < a.strokes.size(); ++i) {
        EXPECT_EQ(a.strokes[i].points_px, b.strokes[i].points_px);
        EXPECT_EQ(a.strokes[i].hidden, b.strokes[i].hidden);
    }
}

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

std::vector<core::StrokeGeometry> rejoin(const Tangle& t, const core::StrokeCoherence& memory, size_t* r_count = nullptr) {
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
    ASSERT_EQ(g.hidden.size(), g.edges.size());
    for (size_t k = 0; k < g.edges.size(); ++k) {
        // The occluded bits are marked hidden; the fragment and both sides stay visible.
        const bool occluded = g.edges[k] == 50 || g.edges[k] == 70;
        EXPECT_EQ(g.hidden[k], occluded ? 1 : 0) << "edge " << g.edges[k];
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
    const std::vector<core::StrokeGeometry> fold{line({0, 0}, {50, 0}, true, 0), line({38, 0.5}, {100, 0.5}, true, 100)};
    const core::StrokeCoherence memory({trace({0, 0.25}, {100, 0.25}, 7)}, 8);
    size_t joins = 0;
    const std::vector<core::StrokeGeometry> out = rejoin(fold, {}, memory, &joins);
    EXPECT_EQ(joins, 1u);
    ASSERT_EQ(out.size(), 1u);
    const core::StrokeGeometry& g = out[0];
    EXPECT_EQ(g.points_px.front(), dvec2(0, 0));
    EXPECT_EQ(g.points_px.back(), dvec2(100, 0.5));
    ASSERT_EQ(g.hidden.size(), g.edges.size());
    EXPECT_EQ(std::count(g.hidden.begin(), g.hidden.end(), uint8_t(1)), 1) << "the jump across the fold";
    const auto jump = size_t(std::find(g.hidden.begin(), g.hidden.end(), uint8_t(1)) - g.hidden.begin());
    EXPECT_EQ(g.points_px[jump], dvec2(50, 0));
    EXPECT_EQ(g.points_px[jump + 1], dvec2(38, 0.5));
    EXPECT_EQ(g.points_px.size(), fold[0].points_px.size() + fold[1].points_px.size()) << "every exact point kept";
}

// A line that leaves the fold's end running the same way as the stroke beside it is a branch,
// not the stroke's continuation; and without memory nothing is joined.
TEST(StrokeRejoin, ABranchBesideAStrokeIsNotAFold) {
    const std::vector<core::StrokeGeometry> branch{line({0, 0}, {50, 0}, true, 0), line({38, 0.5}, {0, 0.5}, true, 100)};
    const core::StrokeCoherence memory({trace({0, 0.25}, {100, 0.25}, 7)}, 8);
    EXPECT_EQ(rejoin(branch, {}, memory).size(), 2u);
    const std::vector<core::StrokeGeometry> fold{line({0, 0}, {50, 0}, true, 0), line({38, 0.5}, {100, 0.5}, true, 100)};
    EXPECT_EQ(rejoin(fold, {}, {}).size(), 2u);
}

// A T-junction: a stroke ends 1 px beside another one's interior. Last frame, one stroke (id 7)
// ran along the left part of the crossing line and turned up into the ending stroke; the right
// part of the crossing line was a stroke of its own (id 9).
struct Tee {
    std::vector<core::StrokeGeometry> strokes{line({0, 0}, {50, 0}, true, 0), line({30, 1}, {30, 40}, true, 100)};
    Tee() {
        strokes[1].ends = {core::StrokeEnd::kJunction, core::StrokeEnd::kFree};
    }
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
    ASSERT_EQ(g.hidden.size(), g.edges.size());
    EXPECT_EQ(std::count(g.hidden.begin(), g.hidden.end(), uint8_t(1)), 1) << "the 1 px jump";
    const auto jump = size_t(std::find(g.hidden.begin(), g.hidden.end(), uint8_t(1)) - g.hidden.begin());
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
    const core::StrokeCoherence memory({trace_along({{0, 0}, {32.5, 0}, {32.5, 40}}, 7), trace({34, 0}, {50, 0}, 9)}, 10);
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
        through({{0, 0}, {60, 0}, {45, 2}, {120, 2}}, 0),     // a fold 15 px back, shorter than the scale
        through({{0, 50}, {60, 50}, {60, 110}}, 1000),       // a right-angle corner
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
        EXPECT_EQ(std::count(g.hidden.begin(), g.hidden.end(), uint8_t(1)), 1);
    }
}

TEST(OccludedLeft, WhatTheJoinsTookIsLeftOut) {
    auto polyline = [](std::vector<dvec2> pts, bool closed) {
        core::Polyline p;
        p.visible = false;
        p.closed = closed;
        for (const dvec2& q : pts) p.points_px.push_back(q), p.points_world.push_back(glm::dvec3(q, 0.0));
        for (size_t k = 0; k + 1 < pts.size(); ++k) p.edges.push_back(uint32_t(10 * pts.size() + k));
        return p;
    };
    const std::vector<core::Polyline> occluded{
        polyline({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}}, false),  // segment 2 taken
        polyline({{0, 5}, {1, 5}, {2, 5}}, false),                          // bridged whole
        polyline({{0, 9}, {1, 9}, {1, 10}, {0, 10}, {0, 9}}, true),         // a loop, segment 0 taken
        polyline({{7, 7}, {8, 8}}, false),                                   // untouched
    };
    core::OccludedUse use;
    use.runs = {0, 1, 0, 0};
    use.segments = {{0, 2}, {2, 0}};
    const std::vector<core::Polyline> left = core::occluded_left(occluded, use);
    ASSERT_EQ(left.size(), 4u);
    EXPECT_EQ(left[0].points_px, (std::vector<dvec2>{{0, 0}, {1, 0}, {2, 0}}));
    EXPECT_EQ(left[1].points_px, (std::vector<dvec2>{{3, 0}, {4, 0}, {5, 0}}));
    EXPECT_EQ(left[1].edges, (std::vector<uint32_t>{63, 64}));
    EXPECT_EQ(left[2].points_px, (std::vector<dvec2>{{1, 9}, {1, 10}, {0, 10}, {0, 9}})) << "opened after the cut";
    EXPECT_FALSE(left[2].closed);
    EXPECT_EQ(left[3].points_px, occluded[3].points_px);
    for (const core::Polyline& p : left) {
        EXPECT_FALSE(p.visible);
        EXPECT_EQ(p.points_world.size(), p.points_px.size());
        EXPECT_EQ(p.edges.size() + 1, p.points_px.size());
    }
}

}  // namespace
}  // namespace inkline
