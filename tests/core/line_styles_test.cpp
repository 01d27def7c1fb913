// SPDX-License-Identifier: MIT
// Line styles: selectors, rule order, every brush key a rule sets, roles, dashes.
#include "core/strokes/line_styles.h"

#include "core/error.h"
#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/strokes/brush.h"
#include "core/strokes/outline.h"
#include "core/visibility/occlusion_source.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

namespace inkline {
namespace {

using core::LineKind;
using core::LineRole;

core::StrokeTraits traits(LineKind kind, bool visible = true, std::string_view object = "", LineRole role = LineRole::kInner) {
    return {kind, visible, object, role};
}

core::StyleSelector kinds(std::initializer_list<LineKind> list, bool hidden = false) {
    core::StyleSelector s;
    for (const LineKind k : list) s.kinds |= uint8_t(1u << unsigned(k));
    if (hidden) s.kinds |= core::kSelectHidden;
    return s;
}

TEST(LineStyles, KindSelectsVisibleLinesOfThatKindAndHiddenSelectsHiddenLines) {
    const core::StyleSelector every;
    EXPECT_TRUE(core::matches(every, traits(LineKind::kCrease)));
    EXPECT_TRUE(core::matches(every, traits(LineKind::kCrease, false)));

    const core::StyleSelector silhouettes = kinds({LineKind::kSilhouette});
    EXPECT_TRUE(core::matches(silhouettes, traits(LineKind::kSilhouette)));
    EXPECT_FALSE(core::matches(silhouettes, traits(LineKind::kBoundary)));
    EXPECT_FALSE(core::matches(silhouettes, traits(LineKind::kSilhouette, false)));

    const core::StyleSelector hidden = kinds({}, true);
    EXPECT_TRUE(core::matches(hidden, traits(LineKind::kSilhouette, false)));
    EXPECT_TRUE(core::matches(hidden, traits(LineKind::kIntersection, false)));
    EXPECT_FALSE(core::matches(hidden, traits(LineKind::kSilhouette)));

    // "hidden" with a kind: that kind, visible or hidden.
    const core::StyleSelector creases = kinds({LineKind::kCrease}, true);
    EXPECT_TRUE(core::matches(creases, traits(LineKind::kCrease)));
    EXPECT_TRUE(core::matches(creases, traits(LineKind::kCrease, false)));
    EXPECT_FALSE(core::matches(creases, traits(LineKind::kBoundary, false)));
    EXPECT_FALSE(core::matches(creases, traits(LineKind::kBoundary)));
}

TEST(LineStyles, ObjectGlobAndRoleSelect) {
    core::StyleSelector trees;
    trees.object = "Tree.*";
    EXPECT_TRUE(core::matches(trees, traits(LineKind::kSilhouette, true, "Tree.004")));
    EXPECT_FALSE(core::matches(trees, traits(LineKind::kSilhouette, true, "Trees")));
    EXPECT_FALSE(core::matches(trees, traits(LineKind::kSilhouette, true, "")));

    core::StyleSelector outer;
    outer.role = LineRole::kOuter;
    EXPECT_TRUE(core::matches(outer, traits(LineKind::kBoundary, true, "", LineRole::kOuter)));
    EXPECT_FALSE(core::matches(outer, traits(LineKind::kBoundary, true, "", LineRole::kInner)));
    // Hidden lines have no role.
    EXPECT_FALSE(core::matches(outer, traits(LineKind::kBoundary, false, "", LineRole::kOuter)));
    core::StyleSelector inner;
    inner.role = LineRole::kInner;
    EXPECT_FALSE(core::matches(inner, traits(LineKind::kBoundary, false, "", LineRole::kInner)));
}

TEST(LineStyles, RulesApplyInOrderKeyByKeyAndTheLastNamesTheStyle) {
    std::vector<core::StyleRule> rules(3);
    rules[0].name = "ink";
    rules[0].set.color = glm::dvec3(1.0, 0.0, 0.0);
    rules[0].set.width_max_px = 2.0;
    rules[1].name = "thin-creases";
    rules[1].select = kinds({LineKind::kCrease});
    rules[1].set.width_max_px = 1.0;
    rules[1].set.opacity = 0.5;
    rules[2].name = "trees";
    rules[2].select.object = "Tree*";
    rules[2].set.dash_px = std::vector<double>{4.0, 2.0};

    const core::BrushStyle base;
    core::StyleSheet sheet(base, rules);
    const uint32_t crease = sheet.resolve(traits(LineKind::kCrease, true, "Rock"));
    const uint32_t silhouette = sheet.resolve(traits(LineKind::kSilhouette, true, "Rock"));
    const uint32_t tree_crease = sheet.resolve(traits(LineKind::kCrease, true, "Tree1"));
    EXPECT_EQ(sheet.resolve(traits(LineKind::kCrease, true, "Stone")), crease);  // same rules, same style
    const auto& styles = sheet.styles();
    ASSERT_EQ(styles.size(), 4u);  // the base, and three combinations
    EXPECT_EQ(styles[0].name, "");
    EXPECT_EQ(styles[0].rule, -1);

    EXPECT_EQ(styles[crease].name, "thin-creases");
    EXPECT_EQ(styles[crease].rule, 1);
    EXPECT_EQ(styles[crease].brush.width_max_px, 1.0);
    EXPECT_EQ(styles[crease].brush.color, glm::dvec3(1.0, 0.0, 0.0));
    EXPECT_EQ(styles[crease].brush.opacity, 0.5);
    EXPECT_EQ(styles[crease].brush.width_min_px, base.width_min_px);  // not set by any rule

    EXPECT_EQ(styles[silhouette].name, "ink");
    EXPECT_EQ(styles[silhouette].brush.width_max_px, 2.0);
    EXPECT_EQ(styles[silhouette].brush.opacity, 1.0);

    EXPECT_EQ(styles[tree_crease].name, "trees");
    EXPECT_EQ(styles[tree_crease].brush.width_max_px, 1.0);
    EXPECT_EQ(styles[tree_crease].brush.dash_px, (std::vector<double>{4.0, 2.0}));
}

TEST(LineStyles, EveryBrushKeyOfARuleIsApplied) {
    core::BrushPatch p;
    p.width_min_px = 0.3;
    p.width_max_px = 7.0;
    p.gamma = 2.0;
    p.invert = true;
    p.taper_px = 5.0;
    p.max_width_ratio = 0.5;
    p.min_length_px = 9.0;
    p.color = glm::dvec3(0.1, 0.2, 0.3);
    p.opacity = 0.25;
    p.line_width_px = 0.7;
    p.depth_width = core::DepthWidth{1.0, 3.0, 0.2};
    p.curvature_width = core::CurvatureWidth{12.0, 1.5};
    p.dash_px = std::vector<double>{0.0, 5.0};
    p.cap = core::LineCap::kSquare;
    core::BrushStyle b;
    p.apply_to(b);
    EXPECT_EQ(b.width_min_px, 0.3);
    EXPECT_EQ(b.width_max_px, 7.0);
    EXPECT_EQ(b.gamma, 2.0);
    EXPECT_TRUE(b.invert);
    EXPECT_EQ(b.taper_px, 5.0);
    EXPECT_EQ(b.max_width_ratio, 0.5);
    EXPECT_EQ(b.min_length_px, 9.0);
    EXPECT_EQ(b.color, glm::dvec3(0.1, 0.2, 0.3));
    EXPECT_EQ(b.opacity, 0.25);
    EXPECT_EQ(b.line_width_px, 0.7);
    ASSERT_TRUE(b.depth_width);
    EXPECT_EQ(b.depth_width->far_scale, 0.2);
    ASSERT_TRUE(b.curvature_width);
    EXPECT_EQ(b.curvature_width->radius_px, 12.0);
    EXPECT_EQ(b.dash_px, (std::vector<double>{0.0, 5.0}));
    EXPECT_EQ(b.cap, core::LineCap::kSquare);
    // An empty patch changes nothing.
    core::BrushStyle c = b;
    core::BrushPatch{}.apply_to(c);
    EXPECT_EQ(c.width_max_px, b.width_max_px);
    EXPECT_EQ(c.dash_px, b.dash_px);
}

TEST(LineStyles, DashesRepeatFromUZeroSoTheyStayOnTheStroke) {
    const std::vector<double> pattern = {4.0, 2.0};
    const auto a = core::dash_intervals(pattern, 0.0, 13.0);
    ASSERT_EQ(a.size(), 3u);
    EXPECT_EQ(a[0], std::make_pair(0.0, 4.0));
    EXPECT_EQ(a[1], std::make_pair(6.0, 10.0));
    EXPECT_EQ(a[2], std::make_pair(12.0, 13.0));
    // The same stroke with its start moved on by 5 px: the dashes stay where u puts them.
    const auto b = core::dash_intervals(pattern, 5.0, 13.0);
    ASSERT_EQ(b.size(), 2u);
    EXPECT_EQ(b[0], std::make_pair(6.0, 10.0));
    EXPECT_EQ(b[1], std::make_pair(12.0, 13.0));
    // Dots, and an odd pattern repeated (3 on, 1 off, 3 off... as SVG reads "3 1").
    const auto dots = core::dash_intervals(std::vector<double>{0.0, 6.0}, 1.0, 20.0);
    ASSERT_EQ(dots.size(), 3u);
    for (size_t k = 0; k < dots.size(); ++k) EXPECT_EQ(dots[k], std::make_pair(6.0 * double(k + 1), 6.0 * double(k + 1)));
    const auto odd = core::dash_intervals(std::vector<double>{3.0}, 0.0, 12.0);
    ASSERT_EQ(odd.size(), 2u);
    EXPECT_EQ(odd[1], std::make_pair(6.0, 9.0));
}

TEST(LineStyles, CapsCloseEndsRoundFlatOrSquare) {
    const std::vector<glm::dvec2> line = {{0.0, 0.0}, {20.0, 0.0}};
    const std::vector<double> width = {4.0, 4.0};
    const auto area = [&](core::LineCap cap) {
        core::OutlineOptions o;
        o.cap = cap;
        o.join_step_deg = 1.0;
        o.simplify_px = 0.0;
        return core::outline_area(core::build_outline(line, width, false, o));
    };
    EXPECT_NEAR(area(core::LineCap::kButt), 80.0, 1e-6);
    EXPECT_NEAR(area(core::LineCap::kSquare), 80.0 + 16.0, 1e-6);
    EXPECT_NEAR(area(core::LineCap::kRound), 80.0 + std::numbers::pi * 4.0, 0.02);
    // A dot is both caps back to back.
    core::OutlineOptions round;
    round.join_step_deg = 1.0;
    round.simplify_px = 0.0;
    EXPECT_NEAR(core::outline_area(core::dot_outline({5.0, 5.0}, {1.0, 0.0}, 4.0, round)), std::numbers::pi * 4.0, 0.02);
    core::OutlineOptions square;
    square.cap = core::LineCap::kSquare;
    EXPECT_NEAR(core::outline_area(core::dot_outline({5.0, 5.0}, {1.0, 0.0}, 4.0, square)), 16.0, 1e-9);
    core::OutlineOptions butt;
    butt.cap = core::LineCap::kButt;
    EXPECT_TRUE(core::dot_outline({5.0, 5.0}, {1.0, 0.0}, 4.0, butt).empty());
}

// A mesh of two parts: `front` and then `back`, faces after faces.
core::Mesh merged(const core::Mesh& front, const core::Mesh& back, const glm::vec3& back_offset) {
    core::Mesh m = front;
    const auto base = uint32_t(m.positions.size());
    for (const glm::vec3& p : back.positions) m.positions.push_back(p + back_offset);
    for (const glm::uvec3& t : back.triangles) m.triangles.push_back(t + glm::uvec3(base));
    return m;
}

core::StyleRule rule(const std::string& name) {
    core::StyleRule r;
    r.name = name;
    return r;
}

// A sphere alone is all outer contour; in front of a wall, its contour is an inner line and the
// wall's border is the outer one.
TEST(LineStyles, RoleTellsTheOuterContourFromInnerLines) {
    const core::Mesh sphere = test::uv_sphere(64, 32, 0.5);
    std::vector<core::StyleRule> rules = {rule("outer"), rule("inner")};
    rules[0].select.role = LineRole::kOuter;
    rules[1].select.role = LineRole::kInner;
    const auto styles_by_kind = [&](const core::Mesh& mesh) {
        core::Scene scene = test::scene_for({}, mesh);
        scene.styles = rules;
        const test::Drawn d = test::draw(mesh, scene);
        std::map<std::string, std::set<std::string>> out;  // kind -> style names
        for (const core::Stroke& s : d.strokes.strokes) {
            if (!s.geometry.visible) continue;
            out[core::line_kind_name(s.geometry.kind)].insert(d.strokes.styles[s.style].name);
        }
        return out;
    };
    const auto alone = styles_by_kind(sphere);
    EXPECT_EQ(alone.at("silhouette"), (std::set<std::string>{"outer"}));

    const auto with_wall = styles_by_kind(merged(sphere, test::grid(8, 1.0), {0.0f, 0.0f, -1.0f}));
    EXPECT_EQ(with_wall.at("silhouette"), (std::set<std::string>{"inner"}));
    EXPECT_EQ(with_wall.at("boundary"), (std::set<std::string>{"outer"}));
}

// A long floor seen from low down: with width by depth, its side edges thin with distance as the
// documented curve says, point by point.
TEST(LineStyles, WidthByDepthThinsARecedingPlane) {
    core::Mesh floor = test::grid(16, 1.0);
    for (glm::vec3& p : floor.positions) p = {p.x, -0.3f, -4.0f * p.y};  // x in [-1, 1], z in [-4, 4]
    test::View view;
    view.eye = {0.0, 0.2, 5.0};
    view.target = {0.0, -0.3, 0.0};
    core::Scene scene = test::scene_for(view, floor);
    scene.brush.width_min_px = scene.brush.width_max_px = 4.0;  // the light leaves it alone
    scene.brush.taper_px = 0.0;
    core::StyleRule r = rule("depth");
    // The floor's visible part lies between depths of about 3.2 and 9.
    r.set.depth_width = core::DepthWidth{3.5, 8.5, 0.25};
    scene.styles = {r};
    const test::Drawn d = test::draw(floor, scene);
    const core::Camera& camera = d.lines.camera;
    const glm::dvec3 forward = glm::normalize(camera.target - camera.eye);
    size_t checked = 0;
    double nearest = 0.0, farthest = 1e300;
    for (const core::Stroke& s : d.strokes.strokes) {
        if (!s.geometry.visible || s.geometry.kind != LineKind::kBoundary) continue;
        EXPECT_EQ(d.strokes.styles[s.style].name, "depth");
        for (size_t k = 0; k < s.width.size(); ++k) {
            const double depth = glm::dot(s.geometry.points_world[k] - camera.eye, forward);
            const double t = std::clamp((depth - 3.5) / (8.5 - 3.5), 0.0, 1.0);
            const double expected = 4.0 * (1.0 + (0.25 - 1.0) * t);
            EXPECT_NEAR(s.width[k], expected, 0.02 * 4.0) << "depth " << depth;
            nearest = std::max(nearest, s.width[k]);
            farthest = std::min(farthest, s.width[k]);
            ++checked;
        }
    }
    EXPECT_GT(checked, 20u);
    // Both ends of the curve are reached: full width near the camera, a quarter far away.
    EXPECT_NEAR(nearest, 4.0, 0.1);
    EXPECT_NEAR(farthest, 1.0, 0.1);
}

// A sphere's contour is a circle of known radius in the image: width by curvature scales it by
// exactly the documented factor all round.
TEST(LineStyles, WidthByCurvatureFollowsTheBend) {
    const core::Mesh sphere = test::uv_sphere(256, 128, 0.5);
    core::Scene scene = test::scene_for({}, sphere);
    scene.brush.width_min_px = scene.brush.width_max_px = 4.0;
    core::StyleRule r = rule("bend");
    const test::Drawn plain = test::draw(sphere, scene);
    // The circle's radius in the image, from the drawn contour itself.
    double radius = 0.0;
    size_t n = 0;
    for (const core::Stroke& s : plain.strokes.strokes) {
        for (const glm::dvec2& p : s.geometry.points_px) radius += glm::length(p - glm::dvec2(512.0)), ++n;
    }
    ASSERT_GT(n, 100u);
    radius /= double(n);
    r.set.curvature_width = core::CurvatureWidth{0.5 * radius, 0.25};
    scene.styles = {r};
    const test::Drawn bent = test::draw(sphere, scene);
    const double factor = 1.0 + (0.25 - 1.0) * 0.5;  // min(1, radius_px / radius) = 0.5
    size_t checked = 0;
    for (const core::Stroke& s : bent.strokes.strokes) {
        ASSERT_TRUE(s.geometry.closed);
        for (const double w : s.centerline_width) EXPECT_NEAR(w, 4.0 * factor, 0.05);
        checked += s.centerline_width.size();
    }
    EXPECT_GT(checked, 100u);
}

// Hidden lines of the torus sample as a dotted rule: every hidden stroke takes the rule, the
// visible ones do not; visible dashes cut a brush stroke into one outline per dash.
TEST(LineStyles, DottedHiddenLinesAndDashedBrushStrokesOnTheTorus) {
    core::Scene scene = core::load_scene(std::filesystem::path(INKLINE_SAMPLES) / "torus" / "scene.json");
    scene.lines.hidden = true;
    scene.last_frame = scene.first_frame;
    core::StyleRule dots = rule("dotted");
    dots.select = kinds({}, true);
    dots.set.dash_px = std::vector<double>{0.0, 6.0};
    dots.set.line_width_px = 2.0;
    core::StyleRule dashes = rule("dashed");
    dashes.select = kinds({LineKind::kSilhouette});
    dashes.set.dash_px = std::vector<double>{8.0, 4.0};
    dashes.set.cap = core::LineCap::kButt;
    scene.styles = {dots, dashes};
    core::MeshFrames meshes(scene.mesh, scene.first_frame);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    const core::FrameResult r = pipeline.run(scene.first_frame);
    size_t hidden = 0, dashed = 0;
    for (const core::Stroke& s : r.strokes.strokes) {
        const std::string& name = r.strokes.styles[s.style].name;
        if (!s.geometry.visible) {
            EXPECT_EQ(name, "dotted");
            ++hidden;
            continue;
        }
        if (s.geometry.kind != LineKind::kSilhouette || !s.drawn) continue;
        EXPECT_EQ(name, "dashed");
        // One ring per dash of the stroke's u range.
        const double u0 = s.centerline_u.front();
        const double u1 = s.geometry.closed ? u0 + (s.u.back() - s.u.front()) : s.centerline_u.back();
        const auto on = core::dash_intervals(std::vector<double>{8.0, 4.0}, u0, u1);
        EXPECT_EQ(s.outline.size(), on.size()) << "stroke " << s.id;
        // Butt caps: the ink of a dash is its length times about its width.
        ++dashed;
    }
    EXPECT_GT(hidden, 3u);
    EXPECT_GT(dashed, 0u);
}

TEST(LineStyles, SceneStylesParseAndBadRulesNameTheirKey) {
    const std::string head = R"({"mesh": "m.obj", "camera": {"eye": [0, 0, 4], "target": [0, 0, 0]}, )";
    const core::Scene s = core::parse_scene(head + R"("styles": [
        {"name": "outline", "select": {"kind": "silhouette", "role": "outer"}, "width_max_px": 6, "color": "#203040"},
        {"select": {"kind": ["hidden", "crease"], "object": "Tree*"}, "dash_px": [0, 5], "cap": "round", "line_width_px": 1},
        {"name": "far", "depth_width": {"far_scale": 0.3}, "curvature_width": {"radius_px": 10, "scale": 0.5}}]})",
                                              "dir/scene.json");
    ASSERT_EQ(s.styles.size(), 3u);
    EXPECT_EQ(s.styles[0].name, "outline");
    EXPECT_EQ(s.styles[0].select.kinds, uint8_t(1u << unsigned(LineKind::kSilhouette)));
    EXPECT_EQ(s.styles[0].select.role, LineRole::kOuter);
    EXPECT_EQ(s.styles[0].set.width_max_px, 6.0);
    EXPECT_FALSE(s.styles[0].set.width_min_px);
    EXPECT_EQ(s.styles[1].name, "style-2");
    EXPECT_EQ(s.styles[1].select.kinds, uint8_t(core::kSelectHidden | (1u << unsigned(LineKind::kCrease))));
    EXPECT_EQ(s.styles[1].select.object, "Tree*");
    EXPECT_EQ(*s.styles[1].set.dash_px, (std::vector<double>{0.0, 5.0}));
    EXPECT_FALSE(s.styles[2].set.depth_width->near);
    EXPECT_EQ(s.styles[2].set.depth_width->far_scale, 0.3);

    const auto error = [&](const std::string& styles) {
        try {
            core::parse_scene(head + R"("styles": )" + styles + "}", "dir/scene.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(error(R"({"name": "a"})").find("key 'styles': expected an array"), std::string::npos);
    EXPECT_NE(error(R"([{"tip": "x.png"}])").find("key 'styles[0].tip': unknown key"), std::string::npos);
    EXPECT_NE(error(R"([{"select": {"kind": "outline"}}])").find("key 'styles[0].select.kind': 'outline'"), std::string::npos);
    EXPECT_NE(error(R"([{"select": {"role": "middle"}}])").find("key 'styles[0].select.role'"), std::string::npos);
    EXPECT_NE(error(R"([{"name": "a"}, {"name": "a"}])").find("key 'styles[1].name': 'a' names an earlier rule"),
              std::string::npos);
    EXPECT_NE(error(R"([{"name": "a b"}])").find("key 'styles[0].name'"), std::string::npos);
    EXPECT_NE(error(R"([{"dash_px": [0.1, 0.2]}])").find("key 'styles[0].dash_px': the pattern must repeat after 1 px"),
              std::string::npos);
    EXPECT_NE(error(R"([{"dash_px": [1, -1]}])").find("key 'styles[0].dash_px': expected"), std::string::npos);
    EXPECT_NE(error(R"([{"cap": "pointy"}])").find("key 'styles[0].cap'"), std::string::npos);
    EXPECT_NE(error(R"([{"width_max_px": 1, "width_min_px": 2}])").find("key 'styles[0].width_max_px'"), std::string::npos);
    EXPECT_NE(error(R"([{"depth_width": {"near": 5, "far": 5}}])").find("key 'styles[0].depth_width.far'"), std::string::npos);
    EXPECT_NE(error(R"([{"curvature_width": {"radius_px": 0}}])").find("key 'styles[0].curvature_width.radius_px'"),
              std::string::npos);
    EXPECT_NE(error(R"([{"opacity": 2}])").find("key 'styles[0].opacity'"), std::string::npos);
    EXPECT_NE(error(R"([{"texture": {"dry": 2}}])").find("key 'styles[0].texture.dry'"), std::string::npos);
    EXPECT_NE(error(R"([{"texture": {"grain": 1}}])").find("key 'styles[0].texture.grain': unknown key"), std::string::npos);
    const core::Scene t = core::parse_scene(
        head + R"("brush": {"texture": {"dry": 0.2, "dry_px": 30}}, "styles": [{"texture": false}, {"texture": true}]})",
        "dir/scene.json");
    ASSERT_TRUE(t.brush.texture);
    EXPECT_EQ(t.brush.texture->dry, 0.2);
    EXPECT_EQ(t.brush.texture->dry_px, 30.0);
    EXPECT_EQ(t.brush.texture->streaks, core::BrushTexture{}.streaks);
    ASSERT_TRUE(t.styles[0].set.texture);
    EXPECT_FALSE(*t.styles[0].set.texture) << "false turns the texture off";
    EXPECT_TRUE(*t.styles[1].set.texture);
    // The scene's brush takes the new keys too.
    const core::Scene b = core::parse_scene(head + R"("brush": {"dash_px": [6, 3], "cap": "butt"}})", "dir/scene.json");
    EXPECT_EQ(b.brush.dash_px, (std::vector<double>{6.0, 3.0}));
    EXPECT_EQ(b.brush.cap, core::LineCap::kButt);
}

}  // namespace
}  // namespace inkline
