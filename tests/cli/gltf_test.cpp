// SPDX-License-Identifier: MIT
// `inkline render` on glTF shots: the file's frames, camera and animation; the scene JSON over
// them; broken files refused before any output.
#include "tests/support/gltf.h"
#include "tests/support/obj.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

namespace inkline {
namespace {

namespace fs = std::filesystem;

class Gltf : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // A unit cube moving from x = -1 at frame 1 to x = +1 at frame 24 (24 fps), seen by a
    // camera at z = 8 with a 2:1 aspect.
    static test::GltfBuilder moving_cube() {
        const core::Mesh cube = test::cube(0.5);
        std::vector<float> positions;
        for (const glm::vec3& p : cube.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
        std::vector<uint32_t> indices;
        for (const glm::uvec3& t : cube.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
        test::GltfBuilder b;
        const int node = b.mesh_node("Cube", positions, indices);
        const int cam = b.node("Camera");
        b.json()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"aspectRatio", 2.0}, {"znear", 0.1}}}}};
        b.json()["nodes"][size_t(cam)]["camera"] = 0;
        b.json()["nodes"][size_t(cam)]["translation"] = {0, 0, 8};
        const int input = b.floats({1.0f / 24.0f, 1.0f}, "SCALAR");
        const int output = b.floats({-1, 0, 0, 1, 0, 0}, "VEC3");
        b.json()["animations"] = {{{"name", "Slide"},
                                   {"samplers", {{{"input", input}, {"output", output}}}},
                                   {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}}}}}};
        b.finish_scene();
        return b;
    }

    // The middle of the drawing's horizontal extent, px.
    static double middle_x(const fs::path& json_file) {
        const nlohmann::json j = nlohmann::json::parse(test::read_text(json_file));
        double lo = 1e300, hi = -1e300;
        for (const auto& s : j["strokes"]) {
            for (const auto& p : s["points"]) {
                lo = std::min(lo, p[0].get<double>());
                hi = std::max(hi, p[0].get<double>());
            }
        }
        return 0.5 * (lo + hi);
    }
};

TEST_F(Gltf, RendersTheShotsFramesThroughItsCamera) {
    moving_cube().write(dir / "shot.glb");
    const auto r = test::run_inkline("render " + (dir / "shot.glb").string() + " --json " + (dir / "out/%04d.json").string() + " -q");
    ASSERT_EQ(r.code, 0) << r.output;
    for (int f = 1; f <= 24; ++f) {
        char name[16];
        std::snprintf(name, sizeof name, "%04d.json", f);
        EXPECT_TRUE(fs::exists(dir / "out" / name)) << name;
    }
    EXPECT_FALSE(fs::exists(dir / "out/0025.json"));
    const nlohmann::json first = nlohmann::json::parse(test::read_text(dir / "out/0001.json"));
    EXPECT_EQ(first["image"]["width"], 1024);
    EXPECT_EQ(first["image"]["height"], 512);
    // The cube slides right through the image, centred at frame 12.5.
    const double x1 = middle_x(dir / "out/0001.json"), x24 = middle_x(dir / "out/0024.json");
    EXPECT_LT(x1, 512.0 - 50.0);
    EXPECT_GT(x24, 512.0 + 50.0);
    EXPECT_NEAR(x1 + x24, 1024.0, 1.0);
}

TEST_F(Gltf, SceneJsonOverridesFramesAndSizeAndCommandLineTheScene) {
    moving_cube().write(dir / "shot.gltf", "shot.bin");
    test::write_text(dir / "scene.json", R"({"mesh": "shot.gltf", "frames": [2, 4], "image": {"width": 300, "height": 300}})");
    const auto r = test::run_inkline("render " + (dir / "scene.json").string() + " --json " + (dir / "a/%04d.json").string() + " -q");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_FALSE(fs::exists(dir / "a/0001.json"));
    EXPECT_TRUE(fs::exists(dir / "a/0004.json"));
    EXPECT_FALSE(fs::exists(dir / "a/0005.json"));
    const nlohmann::json j = nlohmann::json::parse(test::read_text(dir / "a/0002.json"));
    EXPECT_EQ(j["image"]["width"], 300);
    const auto r2 = test::run_inkline("render " + (dir / "scene.json").string() + " --frames 7:7 --fps 48 --animation Slide --json " +
                                      (dir / "b/%04d.json").string() + " -q");
    ASSERT_EQ(r2.code, 0) << r2.output;
    EXPECT_TRUE(fs::exists(dir / "b/0007.json"));
}

// A wall in front of the left half of the cube, as a holdout: it hides the cube's lines there and
// draws none of its own; every stroke names its object in JSON and SVG.
TEST_F(Gltf, HoldoutObjectsHideLinesAndDrawNone) {
    test::GltfBuilder b = moving_cube();
    b.json().erase("animations");
    const int wall = b.mesh_node("Wall", {-3, -3, 2, 0, -3, 2, 0, 3, 2, -3, 3, 2}, {0, 1, 2, 0, 2, 3});
    b.json()["scenes"][0]["nodes"].push_back(wall);
    b.write(dir / "shot.glb");
    test::write_text(dir / "scene.json", R"({"mesh": "shot.glb", "objects": {"Wa*": {"lines": false}}})");
    const auto with_wall = test::run_inkline("render " + (dir / "shot.glb").string() + " --json " + (dir / "a/%04d.json").string() +
                                             " --svg " + (dir / "a/%04d.svg").string() + " -q");
    ASSERT_EQ(with_wall.code, 0) << with_wall.output;
    const auto holdout = test::run_inkline("render " + (dir / "scene.json").string() + " --json " + (dir / "b/%04d.json").string() +
                                           " --svg " + (dir / "b/%04d.svg").string() + " -q");
    ASSERT_EQ(holdout.code, 0) << holdout.output;
    const auto objects = [](const fs::path& file) {
        std::set<std::string> names;
        const nlohmann::json j = nlohmann::json::parse(test::read_text(file));
        for (const auto& s : j["strokes"]) names.insert(s["object"].get<std::string>());
        return names;
    };
    EXPECT_EQ(objects(dir / "a/0001.json"), (std::set<std::string>{"Cube", "Wall"}));
    EXPECT_EQ(objects(dir / "b/0001.json"), (std::set<std::string>{"Cube"}));
    // The cube's lines start right of the wall's edge (x = 0 projects to the image centre).
    const nlohmann::json held = nlohmann::json::parse(test::read_text(dir / "b/0001.json"));
    for (const auto& s : held["strokes"]) {
        for (const auto& p : s["points"]) EXPECT_GT(p[0].get<double>(), 512.0 - 0.5);
    }
    const std::string svg = test::read_text(dir / "b/0001.svg");
    EXPECT_NE(svg.find("data-object=\"Cube\""), std::string::npos);
    EXPECT_EQ(svg.find("data-object=\"Wall\""), std::string::npos);
}

// A wall through the cube's middle: an intersection line of the cube and the wall, drawn in its
// own layer and counted in the stats; off with lines.intersection false or when one object turns
// the kind off. An OBJ file of the same two groups draws the same lines.
// A ball mirrored by its node's scale is the same ball: the file winds its triangles clockwise
// (glTF 2.0: a negative determinant turns the winding), which inkline turns back, so it is lit,
// stippled and drawn as the plain one. Before, its faces were read as turned inwards: no dot was
// drawn on its visible side, and the brush took its width from the light on the far side.
TEST_F(Gltf, AMirroredObjectIsLitAndStippledAsThePlainOne) {
    const core::Mesh ball = test::uv_sphere(48, 24, 1.0);  // symmetric about x = 0
    std::vector<float> positions;
    for (const glm::vec3& p : ball.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    std::vector<uint32_t> indices;
    for (const glm::uvec3& t : ball.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
    struct Drawn {
        size_t dots = 0;
        double mean_width = 0.0;
    };
    auto draw = [&](double scale_x, const std::string& name) {
        test::GltfBuilder b;
        const int node = b.mesh_node("Ball", positions, indices);
        b.json()["nodes"][size_t(node)]["scale"] = {scale_x, 1, 1};
        const int cam = b.node("Camera");
        b.json()["cameras"] = {
            {{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"aspectRatio", 1.0}, {"znear", 0.1}}}}};
        b.json()["nodes"][size_t(cam)]["camera"] = 0;
        b.json()["nodes"][size_t(cam)]["translation"] = {0, 0, 5};
        b.finish_scene();
        b.write(dir / (name + ".glb"));
        const auto r =
            test::run_inkline("render " + (dir / (name + ".glb")).string() + " --size 400x400 --tone stipple --json " +
                              (dir / (name + "/%04d.json")).string() + " -q");
        EXPECT_EQ(r.code, 0) << r.output;
        const nlohmann::json j = nlohmann::json::parse(test::read_text(dir / name / "0001.json"));
        Drawn d;
        d.dots = j["tone"]["dots"].size();
        size_t samples = 0;
        for (const auto& s : j["strokes"]) {
            for (const auto& w : s["width"]) d.mean_width += w.get<double>(), ++samples;
        }
        d.mean_width /= double(std::max<size_t>(samples, 1));
        return d;
    };
    const Drawn plain = draw(1.0, "plain"), mirrored = draw(-1.0, "mirrored");
    ASSERT_GT(plain.dots, 1000u);
    EXPECT_NEAR(double(mirrored.dots), double(plain.dots), 0.05 * double(plain.dots));
    EXPECT_NEAR(mirrored.mean_width, plain.mean_width, 0.01 * plain.mean_width);
}

TEST_F(Gltf, ObjectsThatCrossDrawIntersectionLinesInTheirOwnLayer) {
    test::GltfBuilder b = moving_cube();
    b.json().erase("animations");
    // Left of the camera's axis, so that the crossing along the cube's right side is in view.
    b.json()["nodes"][0]["translation"] = {-1.5, 0, 0};
    const int wall = b.mesh_node("Wall", {-3, -3, 0, 3, -3, 0, 3, 3, 0, -3, 3, 0}, {0, 1, 2, 0, 2, 3});
    b.json()["scenes"][0]["nodes"].push_back(wall);
    b.write(dir / "shot.glb");
    const auto r = test::run_inkline("render " + (dir / "shot.glb").string() + " --json " + (dir / "a/%04d.json").string() +
                                     " --svg " + (dir / "a/%04d.svg").string() + " -q");
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(test::read_text(dir / "a/0001.json"));
    size_t crossing = 0;
    for (const auto& s : j["strokes"]) {
        if (s["kind"] != "intersection") continue;
        ++crossing;
        EXPECT_EQ(s["object"], "Cube");
        EXPECT_EQ(s["edges"].size() + 1, s["points"].size());
        for (const auto& w : s["world"]) EXPECT_NEAR(w[2].get<double>(), 0.0, 1e-9);
    }
    EXPECT_GT(crossing, 0u);
    EXPECT_GT(j["stats"]["feature_edges"]["intersection"].get<int>(), 0);
    EXPECT_GT(j["stats"]["visible_length_px"]["intersection"].get<double>(), 10.0);
    const std::string svg = test::read_text(dir / "a/0001.svg");
    EXPECT_NE(svg.find("<g id=\"intersection\" inkscape:groupmode=\"layer\""), std::string::npos);
    EXPECT_EQ(test::run_shell("xmllint --noout " + (dir / "a/0001.svg").string()).code, 0);

    for (const char* scene : {R"({"mesh": "shot.glb", "lines": {"intersection": false}})",
                              R"({"mesh": "shot.glb", "objects": {"Wall": {"lines": {"intersection": false}}}})"}) {
        test::write_text(dir / "scene.json", scene);
        fs::remove_all(dir / "b");
        const auto off = test::run_inkline("render " + (dir / "scene.json").string() + " --json " + (dir / "b/%04d.json").string() +
                                           " --svg " + (dir / "b/%04d.svg").string() + " -q");
        ASSERT_EQ(off.code, 0) << off.output;
        const nlohmann::json k = nlohmann::json::parse(test::read_text(dir / "b/0001.json"));
        for (const auto& s : k["strokes"]) EXPECT_NE(s["kind"], "intersection") << scene;
        EXPECT_EQ(test::read_text(dir / "b/0001.svg").find("id=\"intersection\""), std::string::npos) << scene;
    }

    // The same two objects as OBJ groups, seen from the same place.
    std::string obj = "o Cube\n";
    const core::Mesh cube = test::cube(0.5);
    for (const glm::vec3& p : cube.positions) obj += "v " + std::to_string(p.x - 1.5f) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    for (const glm::uvec3& t : cube.triangles) obj += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    obj += "o Wall\nv -3 -3 0\nv 3 -3 0\nv 3 3 0\nv -3 3 0\nf 9 10 11\nf 9 11 12\n";
    test::write_text(dir / "shot.obj", obj);
    test::write_text(dir / "obj.json", R"({"mesh": "shot.obj", "frames": [1, 1], "image": {"width": 512, "height": 512},
        "camera": {"eye": [0, 0, 8], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 34}})");
    const auto o = test::run_inkline("render " + (dir / "obj.json").string() + " --json " + (dir / "c/%04d.json").string() + " -q");
    ASSERT_EQ(o.code, 0) << o.output;
    const nlohmann::json c = nlohmann::json::parse(test::read_text(dir / "c/0001.json"));
    EXPECT_GT(c["stats"]["visible_length_px"]["intersection"].get<double>(), 10.0);
}

// A coarse ball sunk into the ground, drawn with smooth contours: in every visibility mode the
// intersection line ends where the ball's outline goes into the ground, so both strokes end there
// as junctions (docs/contours.md, "Intersection lines"), and the modes agree on its length.
TEST_F(Gltf, SmoothOutlinesMeetTheGroundInEveryVisibilityMode) {
    std::string obj = "o Ball\n";
    const core::Mesh ball = test::uv_sphere(48, 24, 1.0);
    for (const glm::vec3& p : ball.positions) {
        obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    for (const glm::uvec3& t : ball.triangles) {
        obj += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    }
    obj += "o Ground\nv -3 -3 0.3\nv 3 -3 0.3\nv 3 3 0.3\nv -3 3 0.3\n";
    const auto v = [&](int k) { return std::to_string(ball.positions.size() + size_t(k)); };
    obj += "f " + v(1) + " " + v(2) + " " + v(3) + "\nf " + v(1) + " " + v(3) + " " + v(4) + "\n";
    test::write_text(dir / "contact.obj", obj);
    test::write_text(dir / "contact.json", R"({"mesh": "contact.obj", "frames": [1, 1], "image": {"width": 1024, "height": 1024},
        "camera": {"eye": [0, -2.2, 3.4], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 40}})");
    std::vector<double> lengths;
    for (const std::string mode : {"exact", "raycast", "gl"}) {
        SCOPED_TRACE(mode);
        const fs::path out = dir / mode;
        const auto r = test::run_inkline("render " + (dir / "contact.json").string() + " --contour smooth --visibility " +
                                         mode + " --json " + (out / "%04d.json").string() + " -q");
        ASSERT_EQ(r.code, 0) << r.output;
        const nlohmann::json doc = nlohmann::json::parse(test::read_text(out / "0001.json"));
        size_t ends = 0;
        for (const auto& s : doc["strokes"]) {
            if (s["kind"] != "intersection") continue;
            for (const auto& end : s["ends"]) {
                EXPECT_EQ(end, "C");
                ++ends;
            }
        }
        EXPECT_EQ(ends, 2u);
        lengths.push_back(doc["stats"]["visible_length_px"]["intersection"].get<double>());
    }
    EXPECT_GT(lengths[0], 500.0);
    for (const double length : lengths) EXPECT_NEAR(length, lengths[0], 0.005 * lengths[0]);
}

// --layers object: a layer per object, its kind layers inside, every path in its object's layer.
TEST_F(Gltf, LayersByObjectNestKindLayersInObjectLayers) {
    test::GltfBuilder b = moving_cube();
    const int wall = b.mesh_node("Wall <&>", {-3, -3, -2, 3, -3, -2, 3, -1, -2, -3, -1, -2}, {0, 1, 2, 0, 2, 3});
    b.json()["scenes"][0]["nodes"].push_back(wall);
    b.write(dir / "shot.glb");
    const auto r = test::run_inkline("render " + (dir / "shot.glb").string() + " --frames 1:1 --layers object --svg " +
                                     (dir / "o/%04d.svg").string() + " -q");
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = test::read_text(dir / "o/0001.svg");
    const size_t cube = svg.find("<g id=\"object-0\" inkscape:groupmode=\"layer\" inkscape:label=\"Cube\" data-object=\"Cube\">");
    const size_t wall_layer = svg.find("<g id=\"object-1\" inkscape:groupmode=\"layer\" inkscape:label=\"Wall &lt;&amp;&gt;\"");
    ASSERT_NE(cube, std::string::npos) << svg.substr(0, 2000);
    ASSERT_NE(wall_layer, std::string::npos) << svg.substr(0, 2000);
    EXPECT_NE(svg.find("<g id=\"object-0-silhouette\"", cube), std::string::npos);
    EXPECT_NE(svg.find("<g id=\"object-1-boundary\"", wall_layer), std::string::npos);
    // Every Cube path lies between the Cube layer and the Wall layer.
    for (size_t at = svg.find("data-object=\"Cube\" d="); at != std::string::npos; at = svg.find("data-object=\"Cube\" d=", at + 1)) {
        EXPECT_GT(at, cube);
        EXPECT_LT(at, wall_layer);
    }
    EXPECT_EQ(test::run_shell("xmllint --noout " + (dir / "o/0001.svg").string()).code, 0);
    const auto bad = test::run_inkline("render " + (dir / "shot.glb").string() + " --layers material -o " + (dir / "x").string());
    EXPECT_EQ(bad.code, 2) << bad.output;
    EXPECT_NE(bad.output.find("--layers 'material': expected kind, object or style"), std::string::npos) << bad.output;
}

// A torus whose morph target ripples it while a skin's joint turns it: the incremental tracker
// (refitting, never rebuilding) draws exactly what brute force draws on every frame.
TEST_F(Gltf, TrackerEqualsBruteForceUnderSkinningAndMorphing) {
    const core::Mesh torus = test::torus(1.0, 0.35, 48, 24);
    std::vector<float> positions, ripple;
    for (const glm::vec3& p : torus.positions) {
        positions.insert(positions.end(), {p.x, p.y, p.z});
        const float s = 0.15f * std::sin(5.0f * std::atan2(p.z, p.x));
        ripple.insert(ripple.end(), {s * p.x, s, s * p.z});
    }
    std::vector<uint32_t> indices;
    for (const glm::uvec3& t : torus.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
    test::GltfBuilder b;
    const int mesh_node = b.mesh_node("Torus", positions, indices);
    const int joint = b.node("Joint");
    auto& prim = b.json()["meshes"][0]["primitives"][0];
    prim["targets"] = {{{"POSITION", b.floats(ripple, "VEC3")}}};
    const size_t n = torus.positions.size();
    const std::vector<uint8_t> joints(4 * n, 0);
    std::vector<float> weights(4 * n, 0.0f);
    for (size_t v = 0; v < n; ++v) weights[4 * v] = 1.0f;
    prim["attributes"]["JOINTS_0"] = b.accessor(b.view(joints.data(), joints.size()), 5121, n, "VEC4");
    prim["attributes"]["WEIGHTS_0"] = b.floats(weights, "VEC4");
    b.json()["skins"] = {{{"joints", {joint}}}};
    b.json()["nodes"][size_t(mesh_node)]["skin"] = 0;
    const int t = b.floats({0.0f, 1.0f}, "SCALAR");
    const float h = float(std::sin(0.6)), c = float(std::cos(0.6));
    b.json()["animations"] = {{{"samplers", {{{"input", t}, {"output", b.floats({0, 0, 0, 1, h, 0, 0, c}, "VEC4")}},
                                             {{"input", t}, {"output", b.floats({0.0f, 1.0f}, "SCALAR")}}}},
                               {"channels", {{{"sampler", 0}, {"target", {{"node", joint}, {"path", "rotation"}}}},
                                             {{"sampler", 1}, {"target", {{"node", mesh_node}, {"path", "weights"}}}}}}}};
    b.finish_scene();
    b.write(dir / "shot.glb");
    for (const char* tracker : {"incremental", "brute"}) {
        const auto r = test::run_inkline("render " + (dir / "shot.glb").string() + " --frames 0:24 --tracker " + tracker +
                                         " --json " + (dir / tracker / "%04d.json").string() + " -q");
        ASSERT_EQ(r.code, 0) << r.output;
    }
    for (int f = 0; f <= 24; ++f) {
        char name[16];
        std::snprintf(name, sizeof name, "%04d.json", f);
        nlohmann::json a = nlohmann::json::parse(test::read_text(dir / "incremental" / name));
        nlohmann::json b2 = nlohmann::json::parse(test::read_text(dir / "brute" / name));
        EXPECT_LT(a["stats"]["edges_tested"].get<size_t>(), f == 0 ? SIZE_MAX : a["stats"]["edges"].get<size_t>()) << name;
        for (nlohmann::json* j : {&a, &b2}) {
            for (const char* key : {"ms", "tracker", "edges_tested", "faces_tested"}) (*j)["stats"].erase(key);
        }
        EXPECT_EQ(a, b2) << name;
    }
}

TEST_F(Gltf, InfoReportsTheWeldedMeshItsObjectsFramesAndCamera) {
    moving_cube().write(dir / "shot.glb");
    const auto r = test::run_inkline("info " + (dir / "shot.glb").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("vertices: 8\n"), std::string::npos) << r.output;  // welded cube
    EXPECT_NE(r.output.find("boundary edges: 0\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("objects: 1\n  Cube (node 0): 12 faces\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("frames: 1..24 at 24 fps\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("animations: 1 (--animation NAME or INDEX)\n  0: Slide\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("camera: Camera (perspective)\n"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("cameras:"), std::string::npos) << r.output;  // one camera: no list
    // A second camera, unnamed: every camera listed with its index.
    test::GltfBuilder b = moving_cube();
    b.json()["cameras"].push_back(
        {{"type", "orthographic"}, {"orthographic", {{"xmag", 2}, {"ymag", 1}, {"znear", 0}, {"zfar", 50}}}});
    const int second = b.node("");
    b.json()["nodes"][size_t(second)]["camera"] = 1;
    b.json()["scenes"][0]["nodes"].push_back(second);
    b.write(dir / "two.glb");
    const auto two = test::run_inkline("info " + (dir / "two.glb").string());
    ASSERT_EQ(two.code, 0) << two.output;
    EXPECT_NE(two.output.find("cameras: 2 (--camera NAME or INDEX)\n  0: Camera (node 1, perspective)\n"
                              "  1: cameras[1] (node 2, orthographic)\n"),
              std::string::npos)
        << two.output;
}

TEST_F(Gltf, BrokenShotExitsTwoWithOneLineAndWritesNothing) {
    test::GltfBuilder b = moving_cube();
    b.json()["accessors"][0]["count"] = 100000;  // POSITION reads past its view
    b.write(dir / "shot.glb");
    const auto r = test::run_inkline("render " + (dir / "shot.glb").string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("shot.glb: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("accessors[0]"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(Gltf, UnknownAnimationOrCameraAndGltfOptionsOnMeshesAreInputErrors) {
    moving_cube().write(dir / "shot.glb");
    const auto a = test::run_inkline("render " + (dir / "shot.glb").string() + " --animation Walk -o " + (dir / "out").string());
    EXPECT_EQ(a.code, 2) << a.output;
    EXPECT_NE(a.output.find("no animation named 'Walk' (the file has 'Slide')"), std::string::npos) << a.output;
    const auto c = test::run_inkline("render " + (dir / "shot.glb").string() + " --camera Nope -o " + (dir / "out").string());
    EXPECT_EQ(c.code, 2) << c.output;
    test::write_obj(dir / "cube.obj", test::cube(1.0));
    const auto m = test::run_inkline("render " + (dir / "cube.obj").string() + " --fps 30 -o " + (dir / "out").string());
    EXPECT_EQ(m.code, 2) << m.output;
    EXPECT_NE(m.output.find("--fps: applies only to glTF input"), std::string::npos) << m.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace inkline
