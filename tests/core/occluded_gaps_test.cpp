// SPDX-License-Identifier: MIT
#include "core/strokes/occluded_gaps.h"

#include <gtest/gtest.h>

#include <glm/vec2.hpp>
#include <vector>

namespace inkline {
namespace {

using glm::dvec2;

TEST(OccludedGaps, BoundsFollowTheBrush) {
    const core::GapBridgeOptions o = core::gap_bridge_options(4.8);
    EXPECT_DOUBLE_EQ(o.max_gap_px, 9.6);
    EXPECT_LT(o.split_gap_px, o.new_gap_px);
    EXPECT_LT(o.new_gap_px, o.max_gap_px);
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
        polyline({{7, 7}, {8, 8}}, false),                                  // untouched
    };
    core::OccludedUse use;
    use.bridged_whole = {0, 1, 0, 0};
    use.segments_taken = {{0, 2}, {2, 0}};
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
