// SPDX-License-Identifier: MIT
#include "core/strokes/internal/splice.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/repair_shapes.h"

namespace inkline {
namespace {

using glm::dvec2;
using repair_shapes::line;

TEST(Splice, NextContinuesWhereTheStrokeEndsAndGivesItsFarEnd) {
    core::StrokeGeometry a = line({0, 0}, {3, 0}, true, 0);
    core::StrokeGeometry b = line({3, 0}, {5, 0}, true, 10);
    b.ends = {core::StrokeEnd::kJunction, core::StrokeEnd::kCorner};
    core::internal::splice(a, b);
    EXPECT_EQ(a.points_px, (std::vector<dvec2>{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}}));
    EXPECT_EQ(a.points_world.size(), a.points_px.size());
    EXPECT_EQ(a.edges, (std::vector<uint32_t>{0, 1, 2, 10, 11}));
    EXPECT_EQ(a.ends[1], core::StrokeEnd::kCorner);
    EXPECT_EQ(a.pure_stroke_count, 2u);
    EXPECT_TRUE(a.bridged.empty()) << "nothing bridged on either side";
}

TEST(Splice, ReversedNextIsRunBackwards) {
    core::StrokeGeometry a = line({0, 0}, {2, 0}, true, 0);
    core::StrokeGeometry b = line({4, 0}, {2, 0}, true, 10);  // ends where a ends
    b.bridged = {1, 0};
    b.ends = {core::StrokeEnd::kFree, core::StrokeEnd::kJunction};
    core::internal::splice(a, b, true);
    EXPECT_EQ(a.points_px, (std::vector<dvec2>{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}}));
    EXPECT_EQ(a.edges, (std::vector<uint32_t>{0, 1, 11, 10}));
    EXPECT_EQ(a.bridged, (std::vector<uint8_t>{0, 0, 0, 1})) << "marks run backwards with their segments";
    EXPECT_EQ(a.ends[1], core::StrokeEnd::kFree);
}

TEST(Splice, AGapIsBridgedThroughout) {
    core::StrokeGeometry a = line({0, 0}, {2, 0}, true, 0);
    core::internal::splice_bridged(a, line({2, 0}, {4, 0}, false, 50));
    core::internal::splice(a, line({4, 0}, {5, 0}, true, 100));
    EXPECT_EQ(a.edges, (std::vector<uint32_t>{0, 1, 50, 51, 100}));
    EXPECT_EQ(a.bridged, (std::vector<uint8_t>{0, 0, 1, 1, 0}));
    EXPECT_TRUE(a.visible);
    EXPECT_DOUBLE_EQ(a.unbridged_length_px(), 3.0);
    EXPECT_DOUBLE_EQ(a.length_px(), 5.0);
}

TEST(Splice, OneBridgedSegment) {
    core::StrokeGeometry a = line({0, 0}, {2, 0}, true, 0);
    core::internal::splice_bridged_segment(a, {2, 1}, {2, 1, 0}, 7);
    EXPECT_EQ(a.points_px.back(), dvec2(2, 1));
    EXPECT_EQ(a.points_world.back(), glm::dvec3(2, 1, 0));
    EXPECT_EQ(a.edges, (std::vector<uint32_t>{0, 1, 7}));
    EXPECT_EQ(a.bridged, (std::vector<uint8_t>{0, 0, 1}));
}

TEST(Splice, OrientTurnsBothStrokesToMeetOrNeither) {
    core::StrokeGeometry a = line({2, 0}, {0, 0}, true, 0);   // starts at the join
    core::StrokeGeometry b = line({5, 0}, {3, 0}, true, 10);  // ends at the join
    ASSERT_TRUE(core::internal::orient_for_splice(a, {2, 0}, b, {3, 0}));
    EXPECT_EQ(a.points_px.back(), dvec2(2, 0));
    EXPECT_EQ(b.points_px.front(), dvec2(3, 0));
    // An end that is gone: nothing is turned.
    core::StrokeGeometry c = line({2, 0}, {0, 0}, true, 0);
    core::StrokeGeometry d = line({5, 0}, {3, 0}, true, 10);
    EXPECT_FALSE(core::internal::orient_for_splice(c, {2, 0}, d, {9, 9}));
    EXPECT_EQ(c.points_px.front(), dvec2(2, 0));
    EXPECT_EQ(d.points_px.front(), dvec2(5, 0));
}

TEST(Splice, PartsKeepTheirMarksAndAreJunctionsWhereCut) {
    core::StrokeGeometry g = line({0, 0}, {4, 0}, true, 0);
    g.bridged = {0, 1, 0, 0};
    g.ends = {core::StrokeEnd::kFree, core::StrokeEnd::kCorner};
    const core::StrokeGeometry head = core::internal::part_of(g, 0, 2);
    const core::StrokeGeometry tail = core::internal::part_of(g, 2, 4);
    EXPECT_EQ(head.points_px, (std::vector<dvec2>{{0, 0}, {1, 0}, {2, 0}}));
    EXPECT_EQ(head.bridged, (std::vector<uint8_t>{0, 1}));
    EXPECT_EQ(head.ends[0], core::StrokeEnd::kFree);
    EXPECT_EQ(head.ends[1], core::StrokeEnd::kJunction);
    EXPECT_EQ(tail.edges, (std::vector<uint32_t>{2, 3}));
    EXPECT_EQ(tail.bridged, (std::vector<uint8_t>{0, 0}));
    EXPECT_EQ(tail.ends[0], core::StrokeEnd::kJunction);
    EXPECT_EQ(tail.ends[1], core::StrokeEnd::kCorner);
}

}  // namespace
}  // namespace inkline
