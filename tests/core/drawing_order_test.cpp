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

// The hierarchy's rules on a frame's strokes; with `fresh`, level 0 is the longest of its group.
void expect_hierarchy(const std::vector<core::Stroke>& strokes, bool fresh) {
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
        EXPECT_TRUE(touch(s, parent)) << "stroke " << s.id << " does not touch its parent " << parent.id;
        EXPECT_LT(parent.order, s.order) << "a parent is drawn first";
    }
    EXPECT_EQ(orders.size(), strokes.size()) << "orders are a permutation";
    if (!orders.empty()) {
        EXPECT_EQ(*orders.rbegin(), strokes.size() - 1);
    }
    for (const core::Stroke& s : strokes) {
        for (const core::Stroke& t : strokes) {
            if (touch(s, t)) {
                EXPECT_EQ(s.group, t.group) << "touching strokes " << s.id << " and " << t.id;
            }
            if (fresh && t.group == s.group && t.level == 0) {
                EXPECT_GE(t.geometry.length_px(), s.geometry.length_px()) << "level 0 is the longest of group " << t.id;
            }
        }
    }
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

TEST(DrawingOrder, TheMainStrokeStaysWhileItIsNearlyTheLongest) {
    // Two strokes meeting end to end; the second grows past the first by 5%, then by 20%.
    auto frame = [](double second) {
        return std::vector<core::Stroke>{stroke(1, {{0, 0}, {100, 0}}), stroke(2, {{100, 0}, {100, second}})};
    };
    core::DrawingOrder order;
    std::vector<core::Stroke> strokes = frame(90.0);
    order.assign(strokes);
    EXPECT_EQ(strokes[0].level, 0u);
    strokes = frame(105.0);
    order.assign(strokes);
    EXPECT_EQ(strokes[0].level, 0u) << "kept: at least 90% of the longest";
    EXPECT_EQ(strokes[1].order, 1u);
    strokes = frame(120.0);
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
    strokes = frame(105.0);
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

TEST(DrawingOrder, AMergeAndASplitLeaveTheMainStrokesTreeAsItWas) {
    // A tree of three (A, B from A's end, C from B's end) and a short stroke D apart; D's end
    // reaches C's end, then draws back.
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
    core::DrawingOrder order;
    std::vector<core::Stroke> strokes = frame({50, 60});
    order.assign(strokes);
    ASSERT_EQ(strokes[3].level, 0u);
    const std::vector<core::Stroke> before = strokes;
    strokes = frame({60, 50});
    order.assign(strokes);
    expect_hierarchy(strokes, false);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(strokes[i].level, before[i].level) << "stroke " << strokes[i].id;
        EXPECT_EQ(strokes[i].parent, before[i].parent) << "stroke " << strokes[i].id;
    }
    EXPECT_EQ(strokes[3].group, 1u);
    EXPECT_EQ(strokes[3].level, 3u);
    EXPECT_EQ(strokes[3].parent, 3);
    strokes = frame({50, 60});
    order.assign(strokes);
    expect_hierarchy(strokes, false);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(strokes[i].level, before[i].level) << "stroke " << strokes[i].id;
        EXPECT_EQ(strokes[i].order, before[i].order) << "stroke " << strokes[i].id;
    }
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
    for (int f = 1; f <= frames; ++f) {
        const core::FrameResult r = pipeline.run(f);
        expect_hierarchy(r.strokes.strokes, f == 1);
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
    const Steadiness s = turntable_steadiness(test::torus(1.0, 0.4, 96, 48), 40, 3.0);
    std::printf("torus: %zu kept strokes, same level %.4f, same place %.4f\n", s.kept, s.level, s.order);
    EXPECT_GT(s.kept, 100u);
    EXPECT_GE(s.level, 0.95);
    EXPECT_GE(s.order, 0.95);
}

TEST(DrawingOrder, TheHierarchyHoldsOnEveryFrameOfABumpySphereTurntable) {
    // The rules on every frame; steadiness below the torus's where strokes grow and shrink
    // past junctions (docs/strokes.md measures scanned meshes). Measured: 95.5% and 98.2%.
    const core::Mesh mesh = test::bumpy_sphere(test::icosphere(4), {.count = 30, .height_max = 0.1});
    const Steadiness s = turntable_steadiness(mesh, 30, 3.0);
    std::printf("bumpy sphere: %zu kept strokes, same level %.4f, same place %.4f\n", s.kept, s.level, s.order);
    EXPECT_GT(s.kept, 100u);
    EXPECT_GE(s.level, 0.9);
    EXPECT_GE(s.order, 0.95);
}

}  // namespace
}  // namespace inkline
