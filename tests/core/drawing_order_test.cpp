// SPDX-License-Identifier: MIT
// Groups, levels and drawing order: level 0 is the longest stroke of its group, every level-k
// stroke touches a level-(k-1) stroke (its parent), orders are a permutation, and over a
// turntable levels and order stay as they were for the strokes that keep their ids.
#include "core/strokes/drawing_order.h"

#include "core/pipeline/frame_pipeline.h"
#include "core/visibility/occlusion_source.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

namespace inkline {
namespace {

core::Stroke stroke(uint32_t id, std::vector<glm::dvec2> points) {
    core::Stroke s;
    s.id = id;
    s.geometry.points_px = std::move(points);
    return s;
}

// Touching as the test sees it, by brute force: an end of one within 1e-3 px of a point of the other.
bool touch(const core::Stroke& a, const core::Stroke& b) {
    auto near = [](const glm::dvec2& p, const std::vector<glm::dvec2>& line) {
        return std::any_of(line.begin(), line.end(), [&](const glm::dvec2& q) { return glm::distance(p, q) <= 1e-3; });
    };
    const auto& p = a.geometry.points_px;
    const auto& q = b.geometry.points_px;
    return near(p.front(), q) || near(p.back(), q) || near(q.front(), p) || near(q.back(), p);
}

// Whether an end of a lies within max_px of b's polyline, or an end of b of a's.
bool ends_within(const core::Stroke& a, const core::Stroke& b, double max_px) {
    auto near = [&](const glm::dvec2& p, const std::vector<glm::dvec2>& line) {
        for (size_t k = 0; k + 1 < line.size(); ++k) {
            const glm::dvec2 d = line[k + 1] - line[k];
            const double t = std::clamp(glm::dot(p - line[k], d) / std::max(glm::dot(d, d), 1e-300), 0.0, 1.0);
            if (glm::distance(p, line[k] + t * d) <= max_px) return true;
        }
        return false;
    };
    const auto& p = a.geometry.points_px;
    const auto& q = b.geometry.points_px;
    return near(p.front(), q) || near(p.back(), q) || near(q.front(), p) || near(q.back(), p);
}

// What the hierarchy's rules need to know of the frames before: each stroke's parent and group
// last frame, and for strokes of two different groups last frame, how many frames in a row
// they have touched.
struct History {
    std::map<uint32_t, int64_t> parents;
    std::map<uint32_t, uint32_t> groups;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> touched;
};

// The hierarchy's rules on a frame's strokes; with `fresh`, level 0 is the longest of its group.
// A stroke touches its parent, or one of the two was the other's parent last frame and their
// ends lie within 1 px (DrawingOrderOptions::keep_parent_px). Touching strokes share a group,
// unless they were in two groups last frame and have touched fewer than join_after_frames frames
// in a row. `r_history` is read, then updated to this frame.
void expect_hierarchy(const std::vector<core::Stroke>& strokes, bool fresh, History& r_history) {
    std::map<uint32_t, const core::Stroke*> by_id;
    for (const core::Stroke& s : strokes) by_id[s.id] = &s;
    std::set<uint32_t> orders;
    for (const core::Stroke& s : strokes) {
        orders.insert(s.order);
        const core::Stroke& main = *by_id.at(s.group);
        EXPECT_EQ(main.level, 0u) << "stroke " << s.id << ": its group is named by its main stroke";
        if (s.level == 0) {
            EXPECT_EQ(s.group, s.id);
            EXPECT_EQ(s.parent, -1);
            continue;
        }
        ASSERT_GE(s.parent, 0) << "stroke " << s.id;
        const core::Stroke& parent = *by_id.at(uint32_t(s.parent));
        EXPECT_EQ(parent.level + 1, s.level) << "stroke " << s.id;
        EXPECT_EQ(parent.group, s.group) << "stroke " << s.id;
        auto was_parent = [&](const core::Stroke& child, const core::Stroke& of) {
            const auto last = r_history.parents.find(child.id);
            return last != r_history.parents.end() && last->second == int64_t(of.id);
        };
        const bool kept = (was_parent(s, parent) || was_parent(parent, s)) && ends_within(s, parent, 1.0);
        EXPECT_TRUE(touch(s, parent) || kept) << "stroke " << s.id << " does not touch its parent " << parent.id;
        EXPECT_LT(parent.order, s.order) << "a parent is drawn first";
    }
    EXPECT_EQ(orders.size(), strokes.size()) << "orders are a permutation";
    if (!orders.empty()) {
        EXPECT_EQ(*orders.rbegin(), strokes.size() - 1);
    }
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> touched;
    for (const core::Stroke& s : strokes) {
        for (const core::Stroke& t : strokes) {
            if (s.id < t.id && touch(s, t)) {
                const auto gs = r_history.groups.find(s.id), gt = r_history.groups.find(t.id);
                const bool apart = gs != r_history.groups.end() && gt != r_history.groups.end() && gs->second != gt->second;
                const uint32_t frames = apart ? touched[{s.id, t.id}] = r_history.touched[{s.id, t.id}] + 1 : 0;
                if (!apart || frames >= core::DrawingOrderOptions{}.join_after_frames) {
                    EXPECT_EQ(s.group, t.group) << "touching strokes " << s.id << " and " << t.id;
                }
            }
            if (fresh && t.group == s.group && t.level == 0) {
                EXPECT_GE(t.geometry.length_px(), s.geometry.length_px()) << "level 0 is the longest of group " << t.id;
            }
        }
    }
    r_history = {};
    r_history.touched = std::move(touched);
    for (const core::Stroke& s : strokes) {
        if (s.parent >= 0) r_history.parents[s.id] = s.parent;
        r_history.groups[s.id] = s.group;
    }
}

// The rules on a single frame, with nothing remembered.
void expect_hierarchy(const std::vector<core::Stroke>& strokes, bool fresh) {
    History none;
    expect_hierarchy(strokes, fresh, none);
}

TEST(DrawingOrder, ATreeOfStrokesHasItsLongestStrokeFirstAndLevelsByTouch) {
    // A: a long line; B hangs from its middle; C from B's end; D and E stand alone, E longer.
    std::vector<core::Stroke> strokes = {
        stroke(7, {{0, 0}, {50, 0}, {100, 0}}),  // A
        stroke(3, {{50, 0}, {50, 40}}),          // B
        stroke(9, {{70, 60}, {50, 40}}),         // C
        stroke(4, {{200, 200}, {210, 200}}),     // D
        stroke(5, {{300, 200}, {330, 200}}),     // E
    };
    core::DrawingOrder order;
    order.assign(strokes);
    expect_hierarchy(strokes, true);
    EXPECT_EQ(strokes[0].level, 0u);
    EXPECT_EQ(strokes[1].level, 1u);
    EXPECT_EQ(strokes[1].parent, 7);
    EXPECT_EQ(strokes[2].level, 2u);
    EXPECT_EQ(strokes[2].parent, 3);
    EXPECT_EQ(strokes[2].group, 7u);
    // Groups longest main first: A's group (0, 1, 2), then E, then D.
    EXPECT_EQ(strokes[0].order, 0u);
    EXPECT_EQ(strokes[1].order, 1u);
    EXPECT_EQ(strokes[2].order, 2u);
    EXPECT_EQ(strokes[4].order, 3u);
    EXPECT_EQ(strokes[3].order, 4u);
}

TEST(DrawingOrder, TheMainStrokeStaysWhileItIsAtLeastHalfTheLongest) {
    // Two strokes meeting end to end; the second grows past the first, to 1.9 times its length,
    // then to 2.1 times.
    auto frame = [](double second) {
        return std::vector<core::Stroke>{stroke(1, {{0, 0}, {100, 0}}), stroke(2, {{100, 0}, {100, second}})};
    };
    core::DrawingOrder order;
    std::vector<core::Stroke> strokes = frame(90.0);
    order.assign(strokes);
    EXPECT_EQ(strokes[0].level, 0u);
    strokes = frame(190.0);
    order.assign(strokes);
    EXPECT_EQ(strokes[0].level, 0u) << "kept: at least half the longest";
    EXPECT_EQ(strokes[1].order, 1u);
    strokes = frame(210.0);
    order.assign(strokes);
    EXPECT_EQ(strokes[1].level, 0u) << "the longest takes over";
    EXPECT_EQ(strokes[0].parent, 2);
    // Two groups that were apart merge: the longer of their main strokes stays main.
    core::DrawingOrder merging;
    strokes = {stroke(1, {{0, 0}, {100, 0}}), stroke(2, {{105, 0}, {200, 0}})};
    merging.assign(strokes);
    ASSERT_EQ(strokes[1].level, 0u);
    strokes = {stroke(2, {{105, 0}, {200, 0}}), stroke(1, {{0, 0}, {100, 0}}), stroke(3, {{100, 0}, {105, 0}})};
    merging.assign(strokes);
    EXPECT_EQ(strokes[1].level, 0u) << "stroke 1, the longer of the two main strokes";
    EXPECT_EQ(strokes[2].level, 1u);
    EXPECT_EQ(strokes[0].level, 2u);
    // A new frame order: a fresh DrawingOrder takes the longest at once.
    core::DrawingOrder fresh;
    strokes = frame(190.0);
    fresh.assign(strokes);
    EXPECT_EQ(strokes[1].level, 0u);
}

TEST(DrawingOrder, StrokesTouchAtAPointTheyShareNotWhereOneEndsOnAnothersSide) {
    // B ends on A's side between its points, as a line that passes behind A does; C ends on A's
    // corner, as a line that meets A at a junction does; D meets C end to end.
    std::vector<core::Stroke> strokes = {
        stroke(1, {{0, 0}, {100, 0}, {200, 0}}),  // A
        stroke(2, {{50, 0}, {50, 40}}),           // B
        stroke(3, {{100, 0}, {100, 40}}),         // C
        stroke(4, {{100, 40}, {130, 70}}),        // D
    };
    const std::vector<std::vector<uint32_t>> touches = core::touching_strokes(strokes, 1e-3);
    EXPECT_EQ(touches[0], (std::vector<uint32_t>{2}));
    EXPECT_TRUE(touches[1].empty());
    EXPECT_EQ(touches[2], (std::vector<uint32_t>{0, 3}));
    core::DrawingOrder order;
    order.assign(strokes);
    expect_hierarchy(strokes, true);
    EXPECT_EQ(strokes[1].group, 2u) << "B stands alone";
    EXPECT_EQ(strokes[1].level, 0u);
    EXPECT_EQ(strokes[2].group, 1u);
    EXPECT_EQ(strokes[2].level, 1u);
    EXPECT_EQ(strokes[3].level, 2u);
}

TEST(DrawingOrder, TwoGroupsJoinOnceTheirTouchHasHeldAndAMergeAndASplitLeaveTheMainTree) {
    // A tree of three (A, B from A's end, C from B's end) and a short stroke D apart; D's end
    // reaches C's end for a frame less than it takes to join, draws back, reaches it again and
    // stays, then draws back.
    const std::vector<core::Stroke> tree = {
        stroke(1, {{0, 0}, {100, 0}}),   // A
        stroke(2, {{100, 0}, {100, 50}}),  // B
        stroke(3, {{100, 50}, {60, 50}}),  // C
    };
    auto frame = [&](glm::dvec2 d_end) {
        std::vector<core::Stroke> strokes = tree;
        strokes.push_back(stroke(4, {{30, 80}, d_end}));  // D
        return strokes;
    };
    const glm::dvec2 apart{50, 60}, touching{60, 50};
    const uint32_t join_after = core::DrawingOrderOptions{}.join_after_frames;
    ASSERT_GT(join_after, 1u);
    core::DrawingOrder order;
    History history;
    std::vector<core::Stroke> strokes = frame(apart);
    order.assign(strokes);
    expect_hierarchy(strokes, true, history);
    ASSERT_EQ(strokes[3].level, 0u);
    const std::vector<core::Stroke> before = strokes;
    auto expect_as_before = [&](size_t count, const char* when) {
        for (size_t i = 0; i < count; ++i) {
            EXPECT_EQ(strokes[i].group, before[i].group) << when << ", stroke " << strokes[i].id;
            EXPECT_EQ(strokes[i].level, before[i].level) << when << ", stroke " << strokes[i].id;
            EXPECT_EQ(strokes[i].parent, before[i].parent) << when << ", stroke " << strokes[i].id;
            EXPECT_EQ(strokes[i].order, before[i].order) << when << ", stroke " << strokes[i].id;
        }
    };
    for (int round = 0; round < 2; ++round) {
        for (uint32_t f = 1; f < join_after; ++f) {
            strokes = frame(touching);
            order.assign(strokes);
            expect_hierarchy(strokes, false, history);
            expect_as_before(4, "touching, not yet joined");
        }
        // The first time the touch breaks a frame short; the second it holds.
        strokes = frame(round == 0 ? apart : touching);
        order.assign(strokes);
        expect_hierarchy(strokes, false, history);
        expect_as_before(round == 0 ? 4 : 3, round == 0 ? "apart again" : "joined");
    }
    EXPECT_EQ(strokes[3].group, 1u);
    EXPECT_EQ(strokes[3].level, 3u);
    EXPECT_EQ(strokes[3].parent, 3);
    strokes = frame(apart);
    order.assign(strokes);
    expect_hierarchy(strokes, false, history);
    expect_as_before(4, "split");
    // A new stroke joins what it touches at once, as does everything with join_after_frames 1.
    strokes = frame(touching);
    strokes[3].id = 5;
    order.assign(strokes);
    expect_hierarchy(strokes, false, history);
    EXPECT_EQ(strokes[3].group, 1u);
    core::DrawingOrder at_once({.join_after_frames = 1});
    strokes = frame(apart);
    at_once.assign(strokes);
    strokes = frame(touching);
    at_once.assign(strokes);
    EXPECT_EQ(strokes[3].group, 1u);
    EXPECT_EQ(strokes[3].level, 3u);
}

TEST(DrawingOrder, AGroupThatSplitsOffKeepsTheLevelsItCan) {
    // A main stroke M with A hanging from its end, and B, C and D from A's other end. M moves
    // 10 px away: A, B, C and D are a group of their own. Its main is B, under which A keeps
    // level 1 and C and D level 2; under A, the longest, none would keep theirs.
    std::vector<core::Stroke> strokes = {
        stroke(1, {{0, 0}, {200, 0}}),     // M
        stroke(2, {{200, 0}, {200, 50}}),  // A
        stroke(3, {{200, 50}, {240, 50}}),  // B
        stroke(4, {{200, 50}, {200, 80}}),  // C
        stroke(5, {{200, 50}, {179, 71}}),  // D
    };
    core::DrawingOrder order;
    order.assign(strokes);
    History history;
    expect_hierarchy(strokes, true, history);
    ASSERT_EQ(strokes[1].level, 1u);
    ASSERT_EQ(strokes[2].level, 2u);
    strokes[0].geometry.points_px = {{0, -10}, {200, -10}};
    order.assign(strokes);
    expect_hierarchy(strokes, false, history);
    EXPECT_EQ(strokes[0].group, 1u);
    EXPECT_EQ(strokes[2].level, 0u) << "B is main";
    EXPECT_EQ(strokes[1].group, 3u);
    EXPECT_EQ(strokes[1].level, 1u);
    EXPECT_EQ(strokes[3].level, 2u);
    EXPECT_EQ(strokes[4].level, 2u);
    EXPECT_EQ(strokes[3].parent, 2);
}

TEST(DrawingOrder, ANewStrokeIsDrawnJustBeforeTheStrokesOfLastFrameThatHangFromIt) {
    // P with C1 and C2 hanging from its ends, drawn first; A with three strokes hanging from it.
    // Then P's line comes back as a new stroke N: C1 and C2 hang from it and are still drawn
    // first, N just before them.
    auto frame = [](uint32_t first_id) {
        return std::vector<core::Stroke>{
            stroke(first_id, {{0, 0}, {200, 0}}),             // P, then N
            stroke(2, {{200, 0}, {200, 40}}),                 // C1
            stroke(3, {{0, 0}, {0, 40}}),                     // C2
            stroke(4, {{0, 100}, {75, 100}, {150, 100}}),     // A
            stroke(5, {{150, 100}, {150, 130}}),              // A1
            stroke(6, {{0, 100}, {0, 130}}),                  // A2
            stroke(7, {{75, 100}, {75, 130}}),                // A3
        };
    };
    core::DrawingOrder order;
    std::vector<core::Stroke> strokes = frame(1);
    order.assign(strokes);
    expect_hierarchy(strokes, true);
    for (uint32_t i = 0; i < strokes.size(); ++i) ASSERT_EQ(strokes[i].order, i) << "stroke " << strokes[i].id;
    strokes = frame(9);
    order.assign(strokes);
    expect_hierarchy(strokes, false);
    for (uint32_t i = 0; i < strokes.size(); ++i) EXPECT_EQ(strokes[i].order, i) << "stroke " << strokes[i].id;
}

TEST(DrawingOrder, AStrokeStaysWithItsParentWhileTheirEndsAreWithinAPixel) {
    // B hangs from A's end; then B's end draws back 0.6 px from A's, then 2 px.
    auto frame = [](double gap) {
        return std::vector<core::Stroke>{stroke(1, {{0, 0}, {100, 0}}), stroke(2, {{100, gap}, {100, 40}})};
    };
    core::DrawingOrder order;
    std::vector<core::Stroke> strokes = frame(0.0);
    order.assign(strokes);
    ASSERT_EQ(strokes[1].parent, 1);
    History history;
    expect_hierarchy(strokes, true, history);
    strokes = frame(0.6);
    order.assign(strokes);
    expect_hierarchy(strokes, false, history);
    EXPECT_EQ(strokes[1].parent, 1) << "still touching: 0.6 px apart";
    EXPECT_EQ(strokes[1].group, 1u);
    strokes = frame(2.0);
    order.assign(strokes);
    expect_hierarchy(strokes, false, history);
    EXPECT_EQ(strokes[1].group, 2u) << "apart at 2 px";
    EXPECT_EQ(strokes[1].level, 0u);
    // Strokes 0.6 px apart in a first frame do not touch: only a pair that touched holds on.
    core::DrawingOrder fresh;
    strokes = frame(0.6);
    fresh.assign(strokes);
    EXPECT_EQ(strokes[1].group, 2u);
}

// Over a turntable, the share of strokes that keep their ids whose level, and whose place among
// those strokes, are the same as last frame.
struct Steadiness {
    double level = 1.0, order = 1.0;
    size_t kept = 0;
};

Steadiness turntable_steadiness(const core::Mesh& mesh, int frames, double degrees_per_frame) {
    const test::View view{.eye = {0.4, 1.6, 4.2}, .fov_y_deg = 40.0, .size = 1024};
    core::Scene scene = test::scene_for(view, mesh);
    scene.last_frame = frames;
    scene.camera.orbit = core::Rotation{.axis = {0.0, 1.0, 0.0}, .degrees = degrees_per_frame * frames};
    scene.camera.near.reset();
    scene.camera.far.reset();
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> last;  // id -> (level, order)
    size_t kept = 0, same_level = 0, same_order = 0;
    History history;
    for (int f = 1; f <= frames; ++f) {
        const core::FrameResult r = pipeline.run(f);
        expect_hierarchy(r.strokes.strokes, f == 1, history);
        std::map<uint32_t, std::pair<uint32_t, uint32_t>> now;
        for (const core::Stroke& s : r.strokes.strokes) now[s.id] = {s.level, s.order};
        // The strokes in both frames, ranked by order in each.
        std::vector<std::pair<uint32_t, uint32_t>> before, after;  // (order, id)
        for (const auto& [id, lo] : now) {
            if (const auto it = last.find(id); it != last.end()) {
                before.emplace_back(it->second.second, id);
                after.emplace_back(lo.second, id);
                ++kept;
                if (it->second.first == lo.first) ++same_level;
            }
        }
        std::sort(before.begin(), before.end());
        std::sort(after.begin(), after.end());
        for (size_t i = 0; i < before.size(); ++i) same_order += before[i].second == after[i].second ? 1 : 0;
        last = std::move(now);
    }
    return {double(same_level) / double(std::max<size_t>(kept, 1)), double(same_order) / double(std::max<size_t>(kept, 1)), kept};
}

TEST(DrawingOrder, LevelsAndOrderHoldOverATorusTurntableAtThreeDegreesAFrame) {
    // Half a turn: the torus settles into two strokes a frame, and more than 100 of them are
    // carried from one frame to the next.
    const Steadiness s = turntable_steadiness(test::torus(1.0, 0.4, 96, 48), 60, 3.0);
    std::printf("torus: %zu kept strokes, same level %.4f, same place %.4f\n", s.kept, s.level, s.order);
    EXPECT_GT(s.kept, 100u);
    EXPECT_GE(s.level, 0.95);
    EXPECT_GE(s.order, 0.95);
}

TEST(DrawingOrder, TheHierarchyHoldsOnEveryFrameOfABumpySphereTurntable) {
    // The rules on every frame, and the 95% where strokes grow and shrink past
    // junctions (docs/strokes.md measures scanned meshes). Measured: 99.1% and 100%.
    const core::Mesh mesh = test::bumpy_sphere(test::icosphere(4), {.count = 30, .height_max = 0.1});
    const Steadiness s = turntable_steadiness(mesh, 30, 3.0);
    std::printf("bumpy sphere: %zu kept strokes, same level %.4f, same place %.4f\n", s.kept, s.level, s.order);
    EXPECT_GT(s.kept, 100u);
    EXPECT_GE(s.level, 0.95);
    EXPECT_GE(s.order, 0.95);
}

}  // namespace
}  // namespace inkline
