// SPDX-License-Identifier: MIT
#include "core/strokes/brush.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <glm/geometric.hpp>
#include <vector>

#include "core/mesh/topology.h"
#include "core/strokes/strokes.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

namespace inkline {
namespace {

using core::StrokeEnd;

TEST(Brush, WidthFollowsTheResponseCurve) {
    core::BrushStyle style;
    style.width_min_px = 1.0;
    style.width_max_px = 5.0;
    style.gamma = 2.0;
    EXPECT_DOUBLE_EQ(core::light_width_px(1.0, style), 1.0) << "fully lit: thinnest";
    EXPECT_DOUBLE_EQ(core::light_width_px(0.0, style), 5.0) << "facing away: heaviest";
    EXPECT_DOUBLE_EQ(core::light_width_px(0.5, style), 1.0 + 4.0 * 0.25);
    EXPECT_DOUBLE_EQ(core::light_width_px(-3.0, style), 5.0) << "intensity is clamped";
    style.invert = true;
    EXPECT_DOUBLE_EQ(core::light_width_px(1.0, style), 5.0);
    EXPECT_DOUBLE_EQ(core::light_width_px(0.0, style), 1.0);
}

TEST(Brush, EndProfiles) {
    EXPECT_DOUBLE_EQ(core::end_profile(StrokeEnd::kFree, 0.0, 20.0), 0.0) << "S ends come to a point";
    EXPECT_DOUBLE_EQ(core::end_profile(StrokeEnd::kFree, 20.0, 20.0), 1.0);
    EXPECT_DOUBLE_EQ(core::end_profile(StrokeEnd::kFree, 10.0, 20.0), 0.75);
    EXPECT_DOUBLE_EQ(core::end_profile(StrokeEnd::kFree, 5.0, 0.0), 1.0) << "no taper";
    for (StrokeEnd e : {StrokeEnd::kCorner, StrokeEnd::kJunction, StrokeEnd::kLoop}) {
        EXPECT_DOUBLE_EQ(core::end_profile(e, 0.0, 20.0), 1.0) << core::stroke_end_name(e);
    }
}

TEST(Brush, TaperFreeMiddleIsMonotoneInShadow) {
    // A straight S-S stroke whose light falls off linearly along it.
    std::vector<glm::dvec2> line;
    std::vector<double> facing;
    for (int i = 0; i <= 200; ++i) line.push_back({double(i), 0.0}), facing.push_back(1.0 - i / 200.0);
    core::BrushStyle style;
    const core::StrokePath path = core::build_stroke_path(line, false, {});
    const core::BrushSamples b = core::brush_samples(path, facing, {StrokeEnd::kFree, StrokeEnd::kFree}, style);
    EXPECT_EQ(b.width.front(), 0.0);
    EXPECT_EQ(b.width.back(), 0.0);
    for (size_t i = 1; i < path.points_px.size(); ++i) {
        const double a = path.arc_px[i];
        if (a < style.taper_px || a > path.length_px - style.taper_px) continue;
        EXPECT_GE(b.width[i], b.width[i - 1]) << "darker along the stroke, heavier: " << a;
        EXPECT_DOUBLE_EQ(b.width[i], core::light_width_px(b.intensity[i], style));
    }
}

// The example: a 6 px stroke in full shadow with both ends free reached the full 4.8 px
// in its middle, a fat speck. Now a stroke is at most max_width_ratio times as wide as it is long
// (and may always be width_min_px wide); long strokes keep their width.
TEST(Brush, ShortStrokesAreShortMarksNotSpecks) {
    const core::BrushStyle style;
    for (const double length : {2.0, 6.0, 12.0, 24.0, 60.0}) {
        for (const StrokeEnd end : {StrokeEnd::kFree, StrokeEnd::kCorner}) {
            std::vector<glm::dvec2> line;
            for (int i = 0; i <= 12; ++i) line.push_back({length * i / 12.0, 0.0});
            const std::vector<double> facing(line.size(), 0.0);  // in shadow: the widest
            const core::StrokePath path = core::build_stroke_path(line, false, {});
            const core::BrushSamples b = core::brush_samples(path, facing, {end, end}, style);
            const double widest = *std::max_element(b.width.begin(), b.width.end());
            const double allowed = std::max(style.width_min_px, style.max_width_ratio * path.length_px);
            EXPECT_DOUBLE_EQ(core::short_stroke_width_px(path.length_px, style), allowed);
            if (end == StrokeEnd::kCorner) {
                // Blunt ends: the whole stroke at the widest allowed.
                EXPECT_NEAR(widest, std::min(allowed, style.width_max_px), 1e-9) << length;
            } else {
                EXPECT_LE(widest, allowed + 1e-9) << length;
            }
        }
    }
    // A 6 px stroke is 1.2 px wide at most, a quarter of the 4.8 px it was.
    EXPECT_DOUBLE_EQ(core::short_stroke_width_px(6.0, style), 1.2);
    // A small loop is a short mark too.
    std::vector<glm::dvec2> ring;
    for (int i = 0; i <= 16; ++i) ring.push_back({2.0 * std::cos(i * std::numbers::pi / 8.0), 2.0 * std::sin(i * std::numbers::pi / 8.0)});
    const core::StrokePath loop = core::build_stroke_path(ring, true, {});
    const core::BrushSamples b = core::brush_samples(loop, std::vector<double>(ring.size(), 0.0), {StrokeEnd::kLoop, StrokeEnd::kLoop}, style);
    EXPECT_LE(*std::max_element(b.width.begin(), b.width.end()), 0.2 * loop.length_px + 1e-9);
}

TEST(Brush, WidthIsMonotoneInShadowOnASideLitSphere) {
    // Sphere seen from +z, lit from +x: along the silhouette loop the intensity runs from 1 to 0
    // and back, and the width must be a monotone function of 1 - I everywhere (a loop has no taper).
    const core::Mesh sphere = test::uv_sphere(96, 48, 1.0);
    core::Scene scene = test::scene_for({}, sphere);
    scene.light.direction = {-1.0, 0.0, 0.0};
    const core::BrushStyle& style = scene.brush;
    const core::FrameStrokes strokes = test::draw(sphere, scene).strokes;
    ASSERT_EQ(strokes.strokes.size(), 1u);
    const core::Stroke& loop = strokes.strokes[0];
    EXPECT_TRUE(loop.geometry.closed);
    EXPECT_EQ(loop.geometry.ends[0], StrokeEnd::kLoop);

    std::vector<std::pair<double, double>> shadow_width;  // (1 - I, width)
    for (size_t i = 0; i < loop.width.size(); ++i) shadow_width.emplace_back(1.0 - loop.intensity[i], loop.width[i]);
    std::sort(shadow_width.begin(), shadow_width.end());
    for (size_t i = 1; i < shadow_width.size(); ++i) {
        EXPECT_GE(shadow_width[i].second, shadow_width[i - 1].second - 1e-12) << "at 1 - I = " << shadow_width[i].first;
    }
    // The silhouette normal is perpendicular to the view ray, so it faces +x to about cos(14 deg).
    EXPECT_LT(shadow_width.front().first, 0.05) << "the lit side is reached";
    EXPECT_GT(shadow_width.back().first, 0.98) << "the dark side is reached";
    EXPECT_NEAR(shadow_width.front().second, style.width_min_px, 0.05);
    EXPECT_NEAR(shadow_width.back().second, style.width_max_px, 0.05);
}

TEST(Brush, PointLightShinesFromItsPosition) {
    // One edge along x at y = 1 on a sphere's top: normals point up (+y).
    const core::Mesh sphere = test::uv_sphere(16, 8, 1.0);
    const core::EdgeTable table = core::build_edge_table(sphere);
    core::Light above;
    above.is_point = true;
    above.position = {0.0, 10.0, 0.0};
    const core::StrokeLighting lit(sphere, table, glm::dmat4(1.0), above);
    // The north pole (vertex 0) and its first edge.
    const uint32_t edge = table.edges_around(0)[0];
    const std::vector<double> facing =
        lit.facing(std::vector<glm::dvec3>{{0.0, 1.0, 0.0}}, std::vector<uint32_t>{edge});
    EXPECT_NEAR(facing[0], 1.0, 1e-9);
    above.position = {0.0, -10.0, 0.0};
    const core::StrokeLighting below(sphere, table, glm::dmat4(1.0), above);
    EXPECT_NEAR(below.facing(std::vector<glm::dvec3>{{0.0, 1.0, 0.0}}, std::vector<uint32_t>{edge})[0], -1.0, 1e-9);
}

TEST(Brush, VertexNormalsAreUnitAndOutward) {
    const core::Mesh sphere = test::uv_sphere(24, 12, 2.0);
    const std::vector<glm::dvec3> normals = core::vertex_normals(sphere);
    for (size_t v = 0; v < normals.size(); ++v) {
        EXPECT_NEAR(glm::length(normals[v]), 1.0, 1e-9);
        EXPECT_GT(glm::dot(normals[v], glm::normalize(glm::dvec3(sphere.positions[v]))), 0.98);
    }
}

TEST(Brush, NormalsAtSomeVerticesEqualTheFullPassBitForBit) {
    // A sphere plus faces the edge table drops: a repeated corner, and a sliver of three
    // distinct corners whose tiny normal (area ratio 2.5e-14) vertex_normals still adds.
    core::Mesh mesh = test::uv_sphere(24, 12, 2.0);
    const uint32_t n = uint32_t(mesh.positions.size());
    mesh.positions.push_back({0.0f, 0.0f, 1.0f});
    mesh.positions.push_back({0.0f, 0.0f, 2.0f});
    mesh.positions.push_back({1e-13f, 0.0f, 3.0f});
    mesh.triangles.push_back({3, 3, 7});
    mesh.triangles.push_back({n, n + 1, n + 2});
    mesh.triangles.push_back({n, 0, 1});
    const core::EdgeTable table = core::build_edge_table(mesh);
    ASSERT_EQ(std::count(table.face_valid.begin(), table.face_valid.end(), 0), 2);
    ASSERT_NE(core::vertex_normals(mesh)[n + 2], glm::dvec3(0.0));
    std::vector<uint32_t> every(mesh.positions.size());
    for (uint32_t v = 0; v < every.size(); ++v) every[v] = v;
    const std::vector<glm::dvec3> full = core::vertex_normals(mesh);
    const std::vector<glm::dvec3> some = core::vertex_normals_at(mesh, table, every);
    ASSERT_EQ(full.size(), some.size());
    for (size_t v = 0; v < full.size(); ++v) EXPECT_EQ(full[v], some[v]) << "vertex " << v;
}

TEST(Brush, NormalCacheGivesTheNormalsOfAFreshPass) {
    core::Mesh mesh = test::uv_sphere(24, 12, 2.0);
    const core::EdgeTable table = core::build_edge_table(mesh);
    core::VertexNormalCache cache;
    const std::vector<uint32_t> first = {0, 3, 5, 9, 40}, second = {3, 4, 9, 41, 100};
    EXPECT_EQ(cache.at(mesh, table, first), core::vertex_normals_at(mesh, table, first));
    EXPECT_EQ(cache.at(mesh, table, second), core::vertex_normals_at(mesh, table, second)) << "some kept, some new";
    // Moved: without clear() the kept normals would be stale; after it they are fresh.
    for (glm::vec3& p : mesh.positions) p.z *= 3.0f;
    cache.clear();
    const std::vector<glm::dvec3> moved = cache.at(mesh, table, second);
    EXPECT_EQ(moved, core::vertex_normals_at(mesh, table, second));
    EXPECT_NE(moved, core::vertex_normals_at(test::uv_sphere(24, 12, 2.0), table, second));
}

TEST(Brush, ColorHex) {
    EXPECT_EQ(core::color_hex({0.0, 0.5, 1.0}), "#0080ff");
    EXPECT_EQ(core::color_hex(core::BrushStyle{}.color), "#171412");
}

}  // namespace
}  // namespace inkline
