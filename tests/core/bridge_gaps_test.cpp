// SPDX-License-Identifier: MIT
#include "core/strokes/bridge_gaps.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/repair_shapes.h"

namespace inkline {
namespace {

using glm::dvec2;
using repair_shapes::line;
using repair_shapes::through;
using repair_shapes::trace;
using repair_shapes::trace_along;

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

// A short gap with no memory is drawn across; its points stay exact and are marked bridged.
TEST(GapBridging, ShortGapBecomesOneStrokeWithBridgedSegmentsMarked) {
    const Bridged r = bridge_gap(3.0, {});
    EXPECT_EQ(r.count, 1u);
    ASSERT_EQ(r.strokes.size(), 1u);
    EXPECT_EQ(r.used, std::vector<uint8_t>{1});
    const core::StrokeGeometry& g = r.strokes[0];
    EXPECT_TRUE(g.visible);
    EXPECT_FALSE(g.closed);
    ASSERT_EQ(g.bridged.size(), g.edges.size());
    ASSERT_EQ(g.points_px.size(), g.edges.size() + 1);
    EXPECT_EQ(g.points_px.front(), dvec2(0, 0));
    EXPECT_EQ(g.points_px.back(), dvec2(83, 0));
    for (size_t k = 0; k < g.edges.size(); ++k) {
        const bool in_gap = g.edges[k] >= 50 && g.edges[k] < 100;
        EXPECT_EQ(g.bridged[k], in_gap ? 1 : 0) << k;
        // Bridged segments lie exactly on the gap.
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
    EXPECT_TRUE(strokes[0].bridged.empty());
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
        EXPECT_EQ(a.strokes[i].bridged, b.strokes[i].bridged);
    }
}

}  // namespace
}  // namespace inkline
