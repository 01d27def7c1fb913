// SPDX-License-Identifier: MIT
#include "core/scene/scene.h"

#include "core/error.h"
#include "core/mesh/mesh.h"
#include "tests/support/obj.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace inkline {
namespace {

const char* kMinimal = R"({"version": 1, "mesh": "m.obj",
  "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 35}})";

std::string error_of(const std::string& text) {
    try {
        core::parse_scene(text, "dir/scene.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Scene, MinimalSceneGetsDefaults) {
    const core::Scene s = core::parse_scene(kMinimal, "dir/scene.json");
    EXPECT_EQ(s.mesh.path, std::filesystem::path("dir/m.obj"));
    EXPECT_FALSE(s.mesh.is_sequence);
    EXPECT_EQ(s.first_frame, 1);
    EXPECT_EQ(s.last_frame, 1);
    EXPECT_EQ(s.image.width, 1024);
    EXPECT_TRUE(s.lines.silhouette && s.lines.boundary && s.lines.crease && !s.lines.hidden);
    EXPECT_TRUE(s.lines.intersection);
    EXPECT_FALSE(s.lines.self_intersection);
    EXPECT_EQ(s.lines.contour, core::ContourMode::kMesh);
}

TEST(Scene, ContourIsMeshOrSmooth) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "lines": {"contour": "smooth"}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "dir/scene.json");
    EXPECT_EQ(s.lines.contour, core::ContourMode::kSmooth);
}

TEST(Scene, AbsolutePathsStayAbsolute) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": {"sequence": "/data/anim/f_%04d.obj"}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})",
        "dir/scene.json");
    EXPECT_EQ(s.mesh.path, std::filesystem::path("/data/anim/f_%04d.obj"));
    EXPECT_TRUE(s.mesh.is_sequence);
}

TEST(Scene, ErrorsNameTheFileAndKey) {
    struct Case {
        std::string json;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {R"({"camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'mesh': is required"},
        {R"({"mesh": "m.obj"})", "key 'camera': is required"},
        {R"({"mesh": 3, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'mesh'"},
        {R"({"mesh": "m.obj", "colour": 1, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'colour': unknown key"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0], "target": [0,0,0]}})", "key 'camera.eye'"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0], "fov_y_deg": "wide"}})", "key 'camera.fov_y_deg': expected a number"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0], "fov_y_deg": 180}})", "key 'camera.fov_y_deg'"},
        {R"({"mesh": "m.obj", "camera": {"eye": [1,1,1], "target": [1,1,1]}})", "key 'camera.eye': equals the target"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,4,0], "target": [0,0,0], "up": [0,1,0]}})", "key 'camera.up': is parallel"},
        {R"({"mesh": "m.obj", "image": {"width": 0, "height": 10}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'image.width'"},
        {R"({"mesh": "m.obj", "image": {"width": 100000, "height": 100000}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "exceeds the limit"},
        {R"({"mesh": "m.obj", "frames": [10, 1], "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'frames'"},
        {R"({"mesh": "m.obj", "lines": {"silhouette": "yes"}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'lines.silhouette'"},
        {R"({"mesh": "m.obj", "lines": {"self_intersection": 1}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'lines.self_intersection'"},
        {R"({"mesh": "m.obj", "lines": {"contour": "round"}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'lines.contour': expected \"mesh\" or \"smooth\""},
        {R"({"mesh": "m.obj", "lines": {"contour": true}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'lines.contour': expected a string"},
        {R"({"mesh": "m.obj", "objects": {"A": {"lines": {"intersection": "no"}}}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'objects.A.lines.intersection'"},
        {R"({"mesh": "m.obj", "camera": {"frames": [{"frame": 1, "eye": [0,0,4], "target": [0,0,0], "zoom": 2}]}})", "key 'camera.frames[0].zoom'"},
        {R"({"mesh": {"sequence": "f.obj"}, "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'mesh.sequence'"},
        {R"({"version": 2, "mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "key 'version'"},
        {R"({"mesh": "m.obj", "camera": )", "not valid JSON"},
        {R"({"mesh": "m.obj", "frames": [1, 1e400], "camera": {"eye": [0,0,4], "target": [0,0,0]}})", "not valid JSON"},
    };
    for (const Case& c : cases) {
        const std::string error = error_of(c.json);
        EXPECT_NE(error.find("dir/scene.json: "), std::string::npos) << c.json;
        EXPECT_NE(error.find(c.expected), std::string::npos) << c.json << "\n  gave: " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    }
}

// Issue 19: camera values are limited where they are read, and each message names its key.
TEST(Scene, CameraLimitsNameTheirKey) {
    const std::string tail = R"(, "camera": {"eye": [0,0,4], "target": [0,0,0]}})";
    struct Case {
        std::string json;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0,1e20], "target": [0,0,0]}})", "key 'camera.eye': coordinate 1e+20 exceeds the limit of 1e+19"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [-1.5e19,0,0]}})", "key 'camera.target': coordinate"},
        {R"({"mesh": "m.obj", "camera": {"frames": [{"frame": 1, "eye": [0,1e38,4], "target": [0,0,0]}]}})", "key 'camera.frames[0].eye': coordinate 1e+38"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0], "orbit": {"axis": [0,1,0], "degrees": 90, "center": [0,0,1e30]}}})", "key 'camera.orbit.center'"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0], "fov_y_deg": 1e-300}})", "key 'camera.fov_y_deg': must be at least 0.001"},
        {R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0], "up": [0,0,0]}})", "key 'camera.up': must not be the zero vector"},
        {R"({"mesh": "m.obj", "camera": {"eye": [1e18,0,0], "target": [1.0000000000000001e18,0,0]}})", "key 'camera.eye': equals the target"},
        {R"({"mesh": "m.obj", "object": {"rotate": {"axis": [0,0,0], "degrees": 90}})" + tail, "key 'object.rotate.axis': must not be the zero vector"},
        {R"({"mesh": "m.obj", "object": {"rotate": {"axis": [0,1,0], "degrees": 90, "center": [2e19,0,0]}})" + tail, "key 'object.rotate.center'"},
        {R"({"mesh": "m.obj", "light": {"position": [0,-1e300,0]})" + tail, "key 'light.position'"},
        {R"({"mesh": "m.obj", "light": {"direction": [0,0,0]})" + tail, "key 'light.direction'"},
        {R"({"mesh": "m.obj", "frames": [1, 4294967298])" + tail, "key 'frames': frame numbers must be between"},
        {R"({"mesh": "m.obj", "frames": [-18446744073709551615, 1])" + tail, "key 'frames'"},
        {R"({"mesh": "m.obj", "frames": [1, 18446744073709551615])" + tail, "key 'frames': frame numbers must be between"},
        {R"({"mesh": "m.obj", "camera": {"frames": [{"frame": 4294967297, "eye": [0,0,4], "target": [0,0,0]}]}})", "key 'camera.frames[0].frame': frame numbers must be between"},
        {R"({"mesh": "m.obj", "camera": {"frames": [{"frame": 1000000000, "eye": [0,0,4], "target": [0,0,0]}]}})", "key 'camera.frames[0].frame'"},
    };
    for (const Case& c : cases) {
        const std::string error = error_of(c.json);
        EXPECT_EQ(error.rfind("dir/scene.json: ", 0), 0u) << c.json << "\n  gave: " << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << c.json << "\n  gave: " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    }
}

// Directions are taken at any finite length: an axis whose squared length overflows (once a NaN
// that blamed camera.far) or underflows is still a direction.
TEST(Scene, DirectionsOfAnyLengthAreNormalised) {
    const core::Scene s = core::parse_scene(R"({"mesh": "m.obj",
        "camera": {"eye": [0,0,1e-30], "target": [0,0,0], "up": [0,1e-300,0]},
        "object": {"rotate": {"axis": [1e300,1e300,0], "degrees": 90}},
        "light": {"direction": [0,-1e308,0]}})", "dir/scene.json");
    EXPECT_NEAR(glm::length(s.object_rotation->axis), 1.0, 1e-12);
    EXPECT_NEAR(s.object_rotation->axis.x, std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(s.camera.pose.up.y, 1.0, 1e-12);
    EXPECT_NEAR(s.light.direction.y, -1.0, 1e-12);
    core::Bounds bounds;
    bounds.add({-1e-31, -1e-31, -1e-31});
    bounds.add({1e-31, 1e-31, 1e-31});
    const core::Camera camera = core::camera_at(s, 1, core::transformed(bounds, core::world_from_object_at(s, 1)));
    EXPECT_TRUE(std::isfinite(camera.near) && std::isfinite(camera.far));
    EXPECT_GT(camera.far, camera.near);
    const glm::dmat4 m = core::world_from_object_at(s, 1);
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(std::isfinite(m[i][0] + m[i][1] + m[i][2] + m[i][3]));
}

TEST(Scene, LongKeysAndValuesAreCutInMessages) {
    const std::string key(100000, 'k');
    const std::string error = error_of(R"({"mesh": "m.obj", ")" + key + R"(": 1, "camera": {"eye": [0,0,4], "target": [0,0,0]}})");
    EXPECT_NE(error.find("unknown key"), std::string::npos) << error.substr(0, 300);
    EXPECT_NE(error.find("kkk...kkk"), std::string::npos) << error.substr(0, 300);
    EXPECT_LT(error.size(), 300u);
    const std::string broken = error_of(R"({"mesh": ")" + std::string(100000, 'x') + "\n\"}");
    EXPECT_NE(broken.find("not valid JSON"), std::string::npos) << broken.substr(0, 300);
    EXPECT_LT(broken.size(), 500u);
    EXPECT_EQ(broken.find('\n'), std::string::npos);
    EXPECT_EQ(quote_value("short"), "short");
    EXPECT_EQ(quote_value("a\nb"), "a?b");
    EXPECT_LE(quote_value(std::string(1000, 'z')).size(), kMaxQuotedChars);
}

// The bare mesh turntable frames every mesh the readers accept, from extent 1e-30 to the
// coordinate limit, with finite near < far and the eye within the scene limit.
TEST(Scene, DefaultTurntableFramesEveryMeshSize) {
    for (const double size : {1e-30, 1e-6, 1.0, 5e17, 1e18}) {
        for (const double offset : {0.0, 1e3 * size}) {
            if (offset + size > 1e18) continue;
            SCOPED_TRACE(std::to_string(size) + " at " + std::to_string(offset));
            core::Bounds bounds;
            bounds.add(glm::dvec3(offset - size));
            bounds.add(glm::dvec3(offset + size));
            const core::Scene s = core::default_turntable_scene("m.obj", bounds);
            for (const int frame : {1, 13, 48}) {
                const core::Camera camera = core::camera_at(s, frame, bounds);
                EXPECT_GT(camera.near, 0.0);
                EXPECT_GT(camera.far, camera.near);
                EXPECT_TRUE(std::isfinite(camera.far));
                EXPECT_LT(glm::length(camera.eye - bounds.center()), 10.0 * bounds.radius());
                for (int i = 0; i < 3; ++i) EXPECT_LE(std::abs(camera.eye[i]), 1e19);
            }
        }
    }
}

TEST(Scene, OrbitTurnsTheEyeAboutTheTarget) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "frames": [1, 4],
            "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "orbit": {"axis": [0, 1, 0], "degrees": 360}}})",
        "scene.json");
    core::Bounds b;
    b.add({-1, -1, -1});
    b.add({1, 1, 1});
    const core::Camera c1 = core::camera_at(s, 1, b);
    const core::Camera c2 = core::camera_at(s, 2, b);
    EXPECT_NEAR(glm::length(c1.eye - glm::dvec3(0, 0, 4)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(c2.eye - glm::dvec3(4, 0, 0)), 0.0, 1e-9) << "a quarter turn per frame over 4 frames";
    EXPECT_GT(c1.near, 0.0);
    EXPECT_LT(c1.near, 4.0 - std::sqrt(3.0));
    EXPECT_GT(c1.far, 4.0 + std::sqrt(3.0));
}

TEST(Scene, ExplicitCamerasPerFrame) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "frames": [1, 2], "camera": {"near": 0.5, "far": 20, "frames": [
            {"frame": 1, "eye": [0, 0, 4], "target": [0, 0, 0]},
            {"frame": 2, "eye": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 20}]}})",
        "scene.json");
    core::Bounds b;
    b.add({-1, -1, -1});
    b.add({1, 1, 1});
    EXPECT_EQ(core::camera_at(s, 2, b).eye.z, 6.0);
    EXPECT_EQ(core::camera_at(s, 2, b).fov_y_deg, 20.0);
    EXPECT_EQ(core::camera_at(s, 1, b).near, 0.5);
    EXPECT_THROW(core::camera_at(s, 3, b), InputError);
}

TEST(Scene, ObjectRotationAboutItsCenter) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "frames": [0, 1], "camera": {"eye": [0,0,4], "target": [0,0,0]},
            "object": {"rotate": {"axis": [0, 0, 1], "degrees": 180, "center": [1, 0, 0]}}})",
        "scene.json");
    const glm::dmat4 m = core::world_from_object_at(s, 1);
    const glm::dvec4 p = m * glm::dvec4(2, 0, 0, 1);
    EXPECT_NEAR(p.x, 1.0, 1e-12);  // 90 degrees about (1,0,0): (2,0,0) -> (1,1,0)
    EXPECT_NEAR(p.y, 1.0, 1e-12);
}

TEST(Scene, TransformedBoundsHoldTheTurnedBox) {
    core::Bounds box;
    box.add({-1.0, -2.0, -3.0});
    box.add({1.0, 2.0, 3.0});
    // A quarter turn about z and a shift: x and y swap extents, z stays.
    glm::dmat4 m(0.0);
    m[0] = {0.0, 1.0, 0.0, 0.0};
    m[1] = {-1.0, 0.0, 0.0, 0.0};
    m[2] = {0.0, 0.0, 1.0, 0.0};
    m[3] = {10.0, 0.0, 0.0, 1.0};
    const core::Bounds out = core::transformed(box, m);
    ASSERT_TRUE(out.valid);
    EXPECT_EQ(out.min, glm::dvec3(8.0, -1.0, -3.0));
    EXPECT_EQ(out.max, glm::dvec3(12.0, 1.0, 3.0));
    EXPECT_FALSE(core::transformed(core::Bounds{}, m).valid) << "nothing in, nothing out";
}

}  // namespace
}  // namespace inkline

namespace inkline {
namespace {

TEST(Scene, BrushBlockSetsTheStyle) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]},
            "brush": {"width_min_px": 0.5, "width_max_px": 6, "gamma": 2, "invert": true, "taper_px": 10,
                      "min_length_px": 4, "smooth_px": 1.5, "color": "#ff8000", "opacity": 0.75}})",
        "scene.json");
    EXPECT_EQ(s.brush.width_min_px, 0.5);
    EXPECT_EQ(s.brush.width_max_px, 6.0);
    EXPECT_EQ(s.brush.gamma, 2.0);
    EXPECT_TRUE(s.brush.invert);
    EXPECT_EQ(s.brush.taper_px, 10.0);
    EXPECT_EQ(s.brush.min_length_px, 4.0);
    EXPECT_EQ(s.brush.smooth_px, 1.5);
    EXPECT_NEAR(s.brush.color.r, 1.0, 1e-12);
    EXPECT_NEAR(s.brush.color.g, 128.0 / 255.0, 1e-12);
    EXPECT_NEAR(s.brush.color.b, 0.0, 1e-12);
    EXPECT_EQ(s.brush.opacity, 0.75);
    const core::Scene d = core::parse_scene(kMinimal, "scene.json");
    EXPECT_EQ(d.brush.width_max_px, core::BrushStyle{}.width_max_px) << "no block keeps the defaults";
}

TEST(Scene, BrushErrorsNameTheKey) {
    const std::string camera = R"("camera": {"eye": [0,0,4], "target": [0,0,0]})";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"("brush": {"width": 2})", "key 'brush.width': unknown key"},
        {R"("brush": {"gamma": "soft"})", "key 'brush.gamma': expected a number"},
        {R"("brush": {"gamma": 0})", "key 'brush.gamma'"},
        {R"("brush": {"width_min_px": -1})", "key 'brush.width_min_px': must not be negative"},
        {R"("brush": {"width_min_px": 3, "width_max_px": 2})", "key 'brush.width_max_px'"},
        {R"("brush": {"width_max_px": 1e6})", "key 'brush.width_max_px': exceeds the limit"},
        {R"("brush": {"invert": 1})", "key 'brush.invert': expected true or false"},
        {R"("brush": {"color": "black"})", "key 'brush.color'"},
        {R"("brush": {"color": [0, 2, 0]})", "key 'brush.color': components"},
        {R"("brush": {"opacity": 1.5})", "key 'brush.opacity'"},
        {R"("brush": {"turn_angle_deg": 0})", "key 'brush.turn_angle_deg'"},
        {R"("brush": 3)", "key 'brush': expected an object"},
        {R"("brush": {"tip": "no_such_tip.png"})", "key 'brush.tip': no such file: dir/no_such_tip.png"},
        {R"("brush": {"tip": ""})", "key 'brush.tip': is empty"},
        {R"("brush": {"tip": 1})", "key 'brush.tip': expected a string"},
    };
    for (const auto& [brush, expected] : cases) {
        const std::string json = R"({"mesh": "m.obj", )" + camera + ", " + brush + "}";
        const std::string error = error_of(json);
        EXPECT_NE(error.find("dir/scene.json: "), std::string::npos) << json;
        EXPECT_NE(error.find(expected), std::string::npos) << json << "\n  gave: " << error;
    }
}

TEST(Scene, ToneBlockSetsTheTone) {
    const core::Scene d = core::parse_scene(kMinimal, "scene.json");
    EXPECT_EQ(d.tone.mode, core::ToneMode::kNone) << "no block: no tone";
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]},
            "tone": {"min": 0.05, "max": 0.6, "gamma": 2, "levels": 4, "dot_radius_px": 1.5, "fade": 0.25,
                     "color": "#ff0000", "opacity": 0.5, "seed": 7}})",
        "scene.json");
    EXPECT_EQ(s.tone.mode, core::ToneMode::kStipple) << "a block without a mode stipples";
    EXPECT_EQ(s.tone.curve.min, 0.05);
    EXPECT_EQ(s.tone.curve.max, 0.6);
    EXPECT_EQ(s.tone.curve.gamma, 2.0);
    EXPECT_EQ(s.tone.curve.levels, 4);
    EXPECT_EQ(s.tone.dot_radius_px, 1.5);
    EXPECT_EQ(s.tone.fade, 0.25);
    EXPECT_EQ(s.tone.color, glm::dvec3(1.0, 0.0, 0.0));
    EXPECT_EQ(s.tone.opacity, 0.5);
    EXPECT_EQ(s.tone.seed, 7u);
    const core::Scene h = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]},
            "tone": {"mode": "crosshatch", "line_width_px": 1.2, "direction": [0, 0, 2], "cross_direction": [0, 3, 0],
                     "cross_from": 0.3}})",
        "scene.json");
    EXPECT_EQ(h.tone.mode, core::ToneMode::kCrosshatch);
    EXPECT_EQ(h.tone.line_width_px, 1.2);
    EXPECT_EQ(h.tone.direction, glm::dvec3(0.0, 0.0, 1.0)) << "directions are normalised";
    EXPECT_EQ(h.tone.cross_direction, glm::dvec3(0.0, 1.0, 0.0));
    EXPECT_EQ(h.tone.cross_from, 0.3);
    EXPECT_FALSE(h.tone.crease_angle_deg.has_value()) << "unset: the lines' angle";
    const core::Scene c = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}, "tone": {"crease_angle_deg": 35}})",
        "scene.json");
    EXPECT_EQ(c.tone.crease_angle_deg, 35.0);
    EXPECT_EQ(c.tone.max_samples, 8'000'000u) << "the default";
    const core::Scene m = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}, "tone": {"max_samples": 20000000}})",
        "scene.json");
    EXPECT_EQ(m.tone.max_samples, 20'000'000u);
}

TEST(Scene, ToneCurveFollowsTheLight) {
    core::ToneCurve t;
    t.max = 0.5;
    EXPECT_EQ(core::tone_of(1.0, t), 0.0) << "lit: white";
    EXPECT_EQ(core::tone_of(-0.3, t), 0.5) << "turned away: the darkest";
    EXPECT_NEAR(core::tone_of(0.5, t), 0.25, 1e-12);
    t.gamma = 2.0;
    EXPECT_NEAR(core::tone_of(0.5, t), 0.125, 1e-12);
    t.gamma = 1.0;
    t.levels = 3;  // steps 0, 0.5, 1 of the curve
    EXPECT_NEAR(core::tone_of(0.3, t), 0.25, 1e-12);
    EXPECT_NEAR(core::tone_of(0.1, t), 0.5, 1e-12);
}

TEST(Scene, ToneHatchesInScreenSpaceAtAngles) {
    const auto tone_of = [](const std::string& block) {
        return core::parse_scene(R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}, "tone": )" + block + "}",
                                 "scene.json")
            .tone;
    };
    const core::ToneOptions object = tone_of(R"({"mode": "hatch"})");
    EXPECT_EQ(object.space, core::HatchSpace::kObject) << "the default";
    const core::ToneOptions screen = tone_of(R"({"mode": "crosshatch", "space": "screen", "angle_deg": 30})");
    EXPECT_EQ(screen.space, core::HatchSpace::kScreen);
    EXPECT_EQ(screen.angle_deg, 30.0);
    EXPECT_EQ(screen.cross_angle_deg, -45.0) << "the default";
    EXPECT_EQ(tone_of(R"({"space": "screen", "cross_angle_deg": 120})").cross_angle_deg, 120.0);
}

TEST(Scene, ToneErrorsNameTheKey) {
    const std::string camera = R"("camera": {"eye": [0,0,4], "target": [0,0,0]})";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"("tone": {"mode": "engrave"})", "key 'tone.mode': expected \"stipple\", \"hatch\", \"crosshatch\" or \"none\""},
        {R"("tone": {"density": 2})", "key 'tone.density': unknown key"},
        {R"("tone": {"max": 1})", "key 'tone.max': must be between 0 and 0.9"},
        {R"("tone": {"min": -0.1})", "key 'tone.min'"},
        {R"("tone": {"gamma": 0})", "key 'tone.gamma'"},
        {R"("tone": {"levels": -1})", "key 'tone.levels'"},
        {R"("tone": {"levels": 1.5})", "key 'tone.levels': expected an integer"},
        {R"("tone": {"dot_radius_px": 0})", "key 'tone.dot_radius_px'"},
        {R"("tone": {"dot_radius_px": 1e9})", "key 'tone.dot_radius_px'"},
        {R"("tone": {"fade": -1})", "key 'tone.fade'"},
        {R"("tone": {"line_width_px": 0})", "key 'tone.line_width_px'"},
        {R"("tone": {"direction": [0, 0, 0]})", "key 'tone.direction': must not be the zero vector"},
        {R"("tone": {"cross_from": 2})", "key 'tone.cross_from'"},
        {R"("tone": {"color": "grey"})", "key 'tone.color'"},
        {R"("tone": {"opacity": 2})", "key 'tone.opacity'"},
        {R"("tone": {"seed": -3})", "key 'tone.seed'"},
        {R"("tone": {"crease_angle_deg": 181})", "key 'tone.crease_angle_deg': must be between 0 and 180"},
        {R"("tone": {"crease_angle_deg": "sharp"})", "key 'tone.crease_angle_deg'"},
        {R"("tone": {"max_samples": 999})", "key 'tone.max_samples': must be a whole number from 1000 to 2000000000"},
        {R"("tone": {"max_samples": 1500.5})", "key 'tone.max_samples': must be a whole number"},
        {R"("tone": {"max_samples": 3e9})", "key 'tone.max_samples': must be a whole number"},
        {R"("tone": {"max_samples": "many"})", "key 'tone.max_samples'"},
        {R"("tone": "stipple")", "key 'tone': expected an object"},
        {R"("tone": {"space": "page"})", "key 'tone.space': expected \"object\" or \"screen\""},
        {R"("tone": {"space": "screen", "direction": [1, 0, 0]})",
         "key 'tone.direction': is for \"space\": \"object\" (in screen space the lines take angle_deg)"},
        {R"("tone": {"angle_deg": 30})", "key 'tone.angle_deg': is for \"space\": \"screen\""},
        {R"("tone": {"space": "screen", "cross_angle_deg": "steep"})", "key 'tone.cross_angle_deg'"},
        {R"("tone": {"space": "screen", "angle_deg": 400})", "key 'tone.angle_deg': must be between -360 and 360"},
        {R"("objects": {"Ground": {"tone": 1}})", "key 'objects.Ground.tone': expected true, false or {\"mode\", \"gamma\""},
    };
    for (const auto& [tone, expected] : cases) {
        const std::string json = R"({"mesh": "m.obj", )" + camera + ", " + tone + "}";
        const std::string error = error_of(json);
        EXPECT_NE(error.find("dir/scene.json: "), std::string::npos) << json;
        EXPECT_NE(error.find(expected), std::string::npos) << json << "\n  gave: " << error;
    }
}

TEST(Scene, ObjectsCanBeLeftUnshaded) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}, "tone": {},
            "objects": {"Ground": {"tone": false}, "Wall*": {"lines": false}, "Tree.*": {"tone": false},
                        "Tree.1": {"tone": true}}})",
        "scene.json");
    EXPECT_FALSE(core::object_tone(s, "Ground").shaded);
    EXPECT_FALSE(core::object_tone(s, "Wall.north").shaded) << "a holdout is never shaded";
    EXPECT_FALSE(core::object_tone(s, "Tree.2").shaded);
    EXPECT_TRUE(core::object_tone(s, "Tree.1").shaded) << "an exact name overrides a glob";
    EXPECT_TRUE(core::object_tone(s, "Ball").shaded);
}

TEST(Scene, AnObjectsToneBlockSetsItsOwnCurveKeyByKey) {
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]},
            "tone": {"max": 0.5, "gamma": 1.5, "levels": 4},
            "objects": {"Ground*": {"tone": {"max": 0.1, "min": 0.05}}, "Ground.2": {"tone": {"gamma": 2}},
                        "Wall": {"lines": false, "tone": {"max": 0.2}}}})",
        "scene.json");
    const core::ObjectTone ball_tone = core::object_tone(s, "Ball");
    ASSERT_TRUE(ball_tone.shaded);
    const core::ToneCurve* ball = &ball_tone.curve;
    EXPECT_EQ(ball->max, 0.5);
    EXPECT_EQ(ball->gamma, 1.5);
    EXPECT_EQ(ball->levels, 4);
    const core::ObjectTone ground_tone = core::object_tone(s, "Ground.2");
    ASSERT_TRUE(ground_tone.shaded);
    const core::ToneCurve* ground = &ground_tone.curve;
    EXPECT_EQ(ground->max, 0.1) << "the glob's";
    EXPECT_EQ(ground->min, 0.05);
    EXPECT_EQ(ground->gamma, 2.0) << "the exact name's, after the glob";
    EXPECT_EQ(ground->levels, 4) << "the scene's";
    EXPECT_EQ(core::object_tone(s, "Ground.1").curve.gamma, 1.5);
    EXPECT_FALSE(core::object_tone(s, "Wall").shaded) << "a holdout is never shaded";
    const std::string camera = R"("camera": {"eye": [0,0,4], "target": [0,0,0]})";
    for (const auto& [objects, expected] : std::vector<std::pair<std::string, std::string>>{
             {R"({"A": {"tone": {"max": 2}}})", "key 'objects.A.tone.max': must be between 0 and 0.9"},
             {R"({"A": {"tone": {"gamma": 0}}})", "key 'objects.A.tone.gamma': must be above 0"},
             {R"({"A": {"tone": {"levels": -1}}})", "key 'objects.A.tone.levels': must be between 0 and 256"},
             {R"({"A": {"tone": {"mode": "smudge"}}})", "key 'objects.A.tone.mode': expected \"stipple\", \"hatch\""},
             {R"({"A": {"tone": "dark"}})", "objects.A.tone"}}) {
        const std::string json = R"({"mesh": "m.obj", )" + camera + R"(, "objects": )" + objects + "}";
        const std::string error = error_of(json);
        EXPECT_NE(error.find(expected), std::string::npos) << json << "\n  gave: " << error;
    }
}

TEST(Scene, AnObjectsToneModeOverridesTheScenesOnlyWhereTheSceneHasTone) {
    const std::string objects = R"("objects": {"Vase*": {"tone": {"mode": "hatch"}}, "Vase.2": {"tone": {"mode": "crosshatch"}},
                                               "Cup": {"tone": {"mode": "none"}}, "Wall": {"lines": false, "tone": {"mode": "stipple"}},
                                               "Plate": {"tone": false}})";
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}, "tone": {"mode": "stipple"}, )" + objects + "}",
        "scene.json");
    EXPECT_EQ(core::object_tone(s, "Ball").mode, core::ToneMode::kStipple) << "the scene's";
    EXPECT_EQ(core::object_tone(s, "Vase.1").mode, core::ToneMode::kHatch) << "the glob's";
    EXPECT_EQ(core::object_tone(s, "Vase.2").mode, core::ToneMode::kCrosshatch) << "the exact name's, after the glob";
    EXPECT_EQ(core::object_tone(s, "Cup").mode, core::ToneMode::kNone);
    EXPECT_EQ(core::object_tone(s, "Wall").mode, core::ToneMode::kNone) << "a holdout is never shaded";
    EXPECT_EQ(core::object_tone(s, "Plate").mode, core::ToneMode::kNone);
    EXPECT_TRUE(core::object_tone(s, "Cup").shaded) << "mode none leaves the object shaded, on its curve";
    const core::Scene off = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}, )" + objects + "}", "scene.json");
    EXPECT_EQ(core::object_tone(off, "Vase.1").mode, core::ToneMode::kNone) << "an object's mode does not turn tone on";
}

TEST(Scene, StylesShadeTheObjectsTheySelectOverTheObjectsRules) {
    // The scene's tone, then the "objects" rules, then the "styles" rules with a tone, in order,
    // key by key; an ink is named after the last style that set the object's tone.
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]},
            "tone": {"mode": "stipple", "max": 0.5, "color": "#101010", "opacity": 0.9},
            "objects": {"Tree*": {"tone": {"color": "#00ff00", "max": 0.3}}, "Rock": {"tone": false}},
            "styles": [{"name": "lines", "select": {"kind": "crease"}, "color": "#ff0000"},
                       {"name": "trees", "select": {"object": "Tree.*"}, "color": "#2f4f2f",
                        "tone": {"color": "#2f4f2f", "mode": "hatch", "gamma": 2}},
                       {"name": "paper", "tone": {"opacity": 0.5}},
                       {"name": "rock", "select": {"object": "Rock"}, "tone": {"mode": "crosshatch"}}]})",
        "scene.json");
    const core::ObjectTone ball = core::object_tone(s, "Ball");
    EXPECT_TRUE(ball.shaded);
    EXPECT_EQ(ball.mode, core::ToneMode::kStipple);
    EXPECT_EQ(ball.curve.max, 0.5);
    EXPECT_EQ(ball.ink.color, glm::dvec3(16.0 / 255.0));
    EXPECT_EQ(ball.ink.opacity, 0.5) << "the rule without a selector shades every object";
    EXPECT_EQ(ball.ink.style, "paper");
    const core::ObjectTone tree = core::object_tone(s, "Tree.1");
    EXPECT_EQ(tree.mode, core::ToneMode::kHatch);
    EXPECT_EQ(tree.curve.max, 0.3) << "the objects rule's";
    EXPECT_EQ(tree.curve.gamma, 2.0) << "the style's";
    EXPECT_EQ(tree.ink.color, glm::dvec3(0x2f, 0x4f, 0x2f) / 255.0) << "the style's over the objects rule's";
    EXPECT_EQ(tree.ink.opacity, 0.5);
    EXPECT_EQ(tree.ink.style, "paper") << "the last style that set its tone";
    EXPECT_EQ(core::object_tone(s, "Treehouse").ink.color, glm::dvec3(0.0, 1.0, 0.0)) << "the objects rule's alone";
    const core::ObjectTone rock = core::object_tone(s, "Rock");
    EXPECT_FALSE(rock.shaded) << "a style's mode does not shade what an objects rule leaves unshaded";
    EXPECT_EQ(rock.mode, core::ToneMode::kNone);
    // A mesh without objects: only the rule without an object selector applies.
    const core::ObjectTone whole = core::object_tone(s, std::nullopt);
    EXPECT_EQ(whole.mode, core::ToneMode::kStipple);
    EXPECT_EQ(whole.ink.opacity, 0.5);
    EXPECT_EQ(whole.ink.style, "paper");
    EXPECT_EQ(core::object_tone(s, "Tree.2").mode, core::ToneMode::kHatch) << "the styles' mode";
    // Without the scene's tone, a style's mode turns nothing on.
    const core::Scene off = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]},
            "styles": [{"tone": {"mode": "hatch"}}]})", "scene.json");
    EXPECT_EQ(core::object_tone(off, "Ball").mode, core::ToneMode::kNone);
}

TEST(Scene, AStylesToneSelectsByObjectOnlyAndItsKeysAreChecked) {
    const std::string camera = R"("camera": {"eye": [0,0,4], "target": [0,0,0]})";
    for (const auto& [styles, expected] : std::vector<std::pair<std::string, std::string>>{
             {R"([{"select": {"kind": "crease"}, "tone": {"max": 0.2}}])",
              "key 'styles[0].tone': a rule with a tone selects by object only, not by kind or role"},
             {R"([{"select": {"object": "A", "role": "outer"}, "tone": {}}])", "key 'styles[0].tone': a rule with a tone"},
             {R"([{"tone": {"max": 2}}])", "key 'styles[0].tone.max': must be between 0 and 0.9"},
             {R"([{"tone": {"color": "red"}}])", "key 'styles[0].tone.color'"},
             {R"([{"tone": {"opacity": 1.5}}])", "key 'styles[0].tone.opacity': must be between 0 and 1"},
             {R"([{"tone": {"dot_radius_px": 2}}])", "styles[0].tone"},
             {R"([{"tone": true}])", "key 'styles[0].tone': expected {"}}) {
        const std::string json = R"({"mesh": "m.obj", )" + camera + R"(, "styles": )" + styles + "}";
        const std::string error = error_of(json);
        EXPECT_NE(error.find(expected), std::string::npos) << json << "\n  gave: " << error;
    }
    const std::string error =
        error_of(R"({"mesh": "m.obj", )" + camera + R"(, "objects": {"A": {"tone": {"opacity": -1}}}})");
    EXPECT_NE(error.find("key 'objects.A.tone.opacity': must be between 0 and 1"), std::string::npos) << error;
}

TEST(Scene, BrushTipResolvesAgainstTheSceneFolder) {
    namespace fs = std::filesystem;
    const fs::path dir = test::fresh_temp_dir("BrushTipResolvesAgainstTheSceneFolder");
    test::write_text(dir / "tip.png", "not read by the scene parser");
    const core::Scene s = core::parse_scene(
        R"({"mesh": "m.obj", "camera": {"eye": [0,0,4], "target": [0,0,0]}, "brush": {"tip": "tip.png"}})",
        dir / "scene.json");
    EXPECT_EQ(s.brush.tip, dir / "tip.png");
    EXPECT_TRUE(core::parse_scene(kMinimal, "scene.json").brush.tip.empty()) << "no tip: the built-in one";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace inkline
