// SPDX-License-Identifier: MIT
// The inkline program end to end: files written, exit codes, one-line errors.
#include "tests/support/obj.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <map>
#include <regex>
#include <set>

namespace inkline {
namespace {

namespace fs = std::filesystem;

using test::RunResult;

RunResult run(const std::string& args) { return test::run_inkline(args); }

class Cli : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // Writes a scene next to a cube mesh and returns its path.
    fs::path scene(const std::string& body) {
        test::write_obj(dir / "cube.obj", test::cube(1.0));
        test::write_text(dir / "scene.json", body);
        return dir / "scene.json";
    }
};

TEST_F(Cli, SampleRoundTripWritesEveryFrame) {
    const RunResult r = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:3 --size 512x512 -q -o " +
                      dir.string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (int frame = 1; frame <= 3; ++frame) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d", frame);
        const fs::path json_file = dir / "json" / (std::string(name) + ".json");
        const fs::path svg_file = dir / "svg" / (std::string(name) + ".svg");
        ASSERT_TRUE(fs::exists(json_file)) << json_file;
        ASSERT_TRUE(fs::exists(svg_file)) << svg_file;
        const auto doc = nlohmann::json::parse(test::read_text(json_file));
        EXPECT_EQ(doc["frame"], frame);
        EXPECT_EQ(doc["image"]["width"], 512);
        EXPECT_FALSE(doc["strokes"].empty());
        EXPECT_GT(doc["stats"]["visible_length_px"]["silhouette"].get<double>(), 500.0);
        EXPECT_NE(test::read_text(svg_file).find("viewBox=\"0 0 512 512\""), std::string::npos);
    }
    EXPECT_FALSE(fs::exists(dir / "json" / "frame_0004.json"));
}

TEST_F(Cli, SmoothContoursDrawTheTorusInFewerStrokesAndNameFacesInTheJson) {
    // The sample torus (9,216 faces) seen from above at an angle, both ways.
    std::map<std::string, nlohmann::json> docs;
    for (const std::string contour : {"mesh", "smooth"}) {
        const RunResult r = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1 -q --contour " +
                                contour + " -o " + (dir / contour).string());
        ASSERT_EQ(r.code, 0) << r.output;
        docs[contour] = nlohmann::json::parse(test::read_text(dir / contour / "json" / "frame_0001.json"));
    }
    auto drawn = [](const nlohmann::json& doc) {
        int n = 0;
        for (const auto& s : doc["strokes"]) n += s["drawn"].get<bool>();
        return n;
    };
    EXPECT_LT(drawn(docs["smooth"]), drawn(docs["mesh"]));
    EXPECT_EQ(docs["smooth"]["stats"]["tracker"], "brute") << "a single frame is traced by brute force";
    const double mesh_px = docs["mesh"]["stats"]["visible_length_px"]["silhouette"].get<double>();
    EXPECT_NEAR(docs["smooth"]["stats"]["visible_length_px"]["silhouette"].get<double>(), mesh_px, 0.05 * mesh_px);
    // A smooth contour's edges are the faces its segments cross.
    const size_t faces = docs["smooth"]["stats"]["faces"].get<size_t>();
    for (const auto& s : docs["smooth"]["strokes"]) {
        ASSERT_EQ(s["edges"].size() + 1, s["points"].size());
        for (const auto& f : s["edges"]) EXPECT_LT(f.get<size_t>(), faces);
    }
    const RunResult bad = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1 -q --contour round -o " +
                              (dir / "bad").string());
    EXPECT_EQ(bad.code, 2);
    EXPECT_EQ(bad.output, "inkline: error: --contour 'round': expected mesh or smooth\n");
    EXPECT_FALSE(fs::exists(dir / "bad"));
}

TEST_F(Cli, BezierPathsInSvgPdfAndPng) {
    std::map<std::string, std::string> svgs;
    for (const std::string format : {"polygon", "bezier"}) {
        const fs::path out = dir / format;
        const RunResult r = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1 -q --path-format " +
                                format + " --svg " + (out / "f%04d.svg").string() + " --png " + (out / "f%04d.png").string() +
                                " --pdf " + (out / "f.pdf").string());
        ASSERT_EQ(r.code, 0) << r.output;
        svgs[format] = test::read_text(out / "f0001.svg");
        EXPECT_TRUE(fs::exists(out / "f0001.png"));
        EXPECT_TRUE(fs::exists(out / "f.pdf"));
    }
    EXPECT_NE(svgs["bezier"].find("Z\" fill="), std::string::npos);
    EXPECT_NE(svgs["polygon"].find(" L"), std::string::npos);
    EXPECT_EQ(svgs["bezier"].find(" L"), std::string::npos) << "curves: relative steps only";
    EXPECT_LT(2 * svgs["bezier"].size(), svgs["polygon"].size());
    const RunResult bad = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1 -q --path-format curves -o " +
                              (dir / "bad").string());
    EXPECT_EQ(bad.code, 2);
    EXPECT_EQ(bad.output, "inkline: error: --path-format 'curves': expected polygon or bezier\n");
    EXPECT_FALSE(fs::exists(dir / "bad"));
}

TEST_F(Cli, PngPdfAndMatchingIds) {
    const RunResult r = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:3 --size 256x256 -q -o " +
                            dir.string() + " --png " + (dir / "png" / "f%04d.png").string() + " --pdf " +
                            (dir / "all.pdf").string() + " --page A4");
    ASSERT_EQ(r.code, 0) << r.output;
    for (int f = 1; f <= 3; ++f) EXPECT_TRUE(fs::exists(dir / "png" / ("f000" + std::to_string(f) + ".png")));
    const RunResult info = test::run_shell("pdfinfo " + (dir / "all.pdf").string());
    EXPECT_NE(info.output.find("Pages:           3"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("Title:           torus"), std::string::npos) << info.output;
    // Every drawn JSON stroke has its SVG element, and every SVG element names a JSON stroke.
    const auto doc = nlohmann::json::parse(test::read_text(dir / "json" / "frame_0002.json"));
    const std::string svg = test::read_text(dir / "svg" / "frame_0002.svg");
    std::set<int> drawn, all;
    for (const auto& stroke : doc["strokes"]) {
        all.insert(stroke["id"].get<int>());
        if (stroke["drawn"].get<bool>()) drawn.insert(stroke["id"].get<int>());
    }
    ASSERT_FALSE(drawn.empty());
    std::set<int> elements;
    const std::regex id(R"re(<path id="stroke-(\d+)")re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), id); it != std::sregex_iterator(); ++it)
        elements.insert(std::stoi((*it)[1]));
    EXPECT_EQ(elements, drawn);
    for (int e : elements) EXPECT_TRUE(all.count(e));
}

TEST_F(Cli, GlPreviewPerFrame) {
    const RunResult r = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:2 --size 256x256 -q --preview " +
                            (dir / "preview" / "f%04d.png").string() + " --preview-underlay toon");
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* name : {"f0001.png", "f0002.png"}) {
        const std::string png = test::read_text(dir / "preview" / name);
        ASSERT_GT(png.size(), 8u) << name;
        EXPECT_EQ(png.substr(1, 3), "PNG") << name;
    }
    const RunResult bad = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:1 -q --preview " +
                              (dir / "p.png").string() + " --preview-underlay glossy");
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.output.find("--preview-underlay 'glossy'"), std::string::npos) << bad.output;
}

// A technical drawing: a cube in isometric orthographic projection, hidden lines on. All twelve
// edges are drawn (three hidden), each as long as the others, and the edges of each direction
// stay parallel: what a perspective view of the same cube does not give.
TEST_F(Cli, OrthographicCubeIsAnIsometricDrawing) {
    const fs::path s = scene(R"({"mesh": "cube.obj", "image": {"width": 600, "height": 600},
        "lines": {"hidden": true},
        "camera": {"eye": [5, 5, 5], "target": [0, 0, 0], "up": [0, 1, 0], "ortho_height": 4}})");
    const RunResult r = run("render " + s.string() + " -q --json " + (dir / "f.json").string() + " --svg " +
                            (dir / "f.svg").string() + " --preview " + (dir / "p.png").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const auto doc = nlohmann::json::parse(test::read_text(dir / "f.json"));
    EXPECT_EQ(doc["camera"]["ortho_height"], 4.0);
    EXPECT_FALSE(doc["camera"].contains("fov_y_deg"));
    EXPECT_NE(test::read_text(dir / "f.svg").find("ortho_height=\"4\""), std::string::npos);
    // Each cube edge (2 units) projects to 2 sqrt(2/3) units at 150 px a unit.
    const double edge_px = 2.0 * std::sqrt(2.0 / 3.0) * 150.0;
    double visible_px = 0.0, hidden_px = 0.0;
    std::vector<std::array<double, 2>> directions;
    for (const auto& stroke : doc["strokes"]) {
        const auto& points = stroke["points"];
        for (size_t k = 0; k + 1 < points.size(); ++k) {
            const double dx = points[k + 1][0].get<double>() - points[k][0].get<double>();
            const double dy = points[k + 1][1].get<double>() - points[k][1].get<double>();
            const double length = std::hypot(dx, dy);
            (stroke["visible"].get<bool>() ? visible_px : hidden_px) += length;
            directions.push_back({dx / length, dy / length});
        }
    }
    EXPECT_NEAR(visible_px, 9.0 * edge_px, 0.5);
    EXPECT_NEAR(hidden_px, 3.0 * edge_px, 0.5);
    // Every segment runs along one of the three image directions of the cube's axes.
    for (const auto& d : directions) {
        double best = 1.0;
        for (const double angle_deg : {90.0, 30.0, -30.0}) {
            const double a = angle_deg * std::numbers::pi / 180.0;
            best = std::min(best, 1.0 - std::abs(d[0] * std::cos(a) + d[1] * std::sin(a)));
        }
        EXPECT_LT(best, 1e-9) << d[0] << " " << d[1];
    }
    EXPECT_EQ(test::read_text(dir / "p.png").substr(1, 3), "PNG");
}

// A frame's files are written on a thread of their own while the next frame is drawn: -v says
// each frame once its files are written, in order, with what writing them took.
TEST_F(Cli, VerboseLinesComeInOrderOnceTheFilesAreWritten) {
    const RunResult r = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:4 --size 256x256 -v -o " +
                            dir.string() + " --png " + (dir / "png" / "f%04d.png").string());
    ASSERT_EQ(r.code, 0) << r.output;
    size_t at = 0;
    for (int f = 1; f <= 4; ++f) {
        const std::string line = "\nframe " + std::to_string(f) + ": ";
        const size_t found = r.output.find(line, at);
        ASSERT_NE(found, std::string::npos) << "frame " << f << " in order\n" << r.output;
        const std::string text = r.output.substr(found + 1, r.output.find('\n', found + 1) - found - 1);
        for (const char* stage : {"strokes ", "svg ", "png ", "pdf ", "write "}) {
            EXPECT_NE(text.find(std::string(", ") + stage), std::string::npos) << stage << " in: " << text;
        }
        at = found + 1;
    }
    for (int f = 1; f <= 4; ++f) {
        const std::string n = "000" + std::to_string(f);
        EXPECT_TRUE(fs::exists(dir / "svg" / ("frame_" + n + ".svg"))) << f;
        EXPECT_TRUE(fs::exists(dir / "json" / ("frame_" + n + ".json"))) << f;
        EXPECT_TRUE(fs::exists(dir / "png" / ("f" + n + ".png"))) << f;
    }
    EXPECT_NE(r.output.find("4 frame(s), "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" 12 files "), std::string::npos) << r.output;
}

TEST_F(Cli, PdfPerFramePattern) {
    const RunResult r = run("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:2 --size 128x96 -q --pdf " +
                            (dir / "p_%02d.pdf").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const RunResult info = test::run_shell("pdfinfo " + (dir / "p_02.pdf").string());
    EXPECT_NE(info.output.find("Pages:           1"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("96 x 72 pts"), std::string::npos) << "128x96 px at 96 dpi\n" << info.output;
}

TEST_F(Cli, ExplicitPatternsOnly) {
    const fs::path s = scene(R"({"mesh": "cube.obj", "frames": [1, 2], "camera": {"eye": [3, 2.5, 4], "target": [0, 0, 0]}})");
    const RunResult r = run("render " + s.string() + " -q --svg " + (dir / "f%02d.svg").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "f01.svg"));
    EXPECT_TRUE(fs::exists(dir / "f02.svg"));
    EXPECT_FALSE(fs::exists(dir / "json"));
}

TEST_F(Cli, CameraInsideTheMeshIsOneWarningAndTheFramesAreDrawn) {
    const fs::path s = scene(R"({"mesh": "cube.obj", "frames": [1, 3], "camera": {"eye": [0.2, 0.1, 0.3], "target": [0, 0, -3]}})");
    const std::string warning = "inkline: warning: frame 1: the camera is inside the mesh's bounds; lines may be hidden";
    const auto count = [](const std::string& text, const std::string& needle) {
        size_t n = 0;
        for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
        return n;
    };
    const RunResult all = run("render " + s.string() + " --size 64x64 --svg " + (dir / "a%d.svg").string());
    ASSERT_EQ(all.code, 0) << all.output;
    EXPECT_EQ(count(all.output, warning), 1u) << all.output;
    EXPECT_TRUE(fs::exists(dir / "a3.svg"));
    // A chunk replays frame 1 without output: the warning still comes, once.
    const RunResult chunk = run("render " + s.string() + " --size 64x64 --chunk 2/3 --svg " + (dir / "c%d.svg").string());
    ASSERT_EQ(chunk.code, 0) << chunk.output;
    EXPECT_EQ(count(chunk.output, warning), 1u) << chunk.output;
    EXPECT_FALSE(fs::exists(dir / "c1.svg"));
    EXPECT_TRUE(fs::exists(dir / "c2.svg"));
    EXPECT_EQ(count(run("render " + s.string() + " --size 64x64 -q --svg " + (dir / "q%d.svg").string()).output, warning), 0u);
}

TEST_F(Cli, BareMeshRendersADefaultTurntable) {
    test::write_obj(dir / "cube.obj", test::cube(1.0));
    const RunResult r = run("render " + (dir / "cube.obj").string() + " --frames 1:2 -q -o " + dir.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const auto doc = nlohmann::json::parse(test::read_text(dir / "json" / "frame_0002.json"));
    EXPECT_GT(doc["stats"]["feature_edges"]["crease"].get<int>() + doc["stats"]["feature_edges"]["silhouette"].get<int>(), 0);
}

TEST_F(Cli, SceneErrorsAreOneLineNamingTheKeyWithExitCode2) {
    struct Case {
        std::string body;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {R"({"camera": {"eye": [0, 0, 4], "target": [0, 0, 0]}})", "key 'mesh': is required"},
        {R"({"mesh": "cube.obj", "camera": {"eye": "far away", "target": [0, 0, 0]}})", "key 'camera.eye'"},
        {R"({"mesh": "missing.obj", "camera": {"eye": [0, 0, 4], "target": [0, 0, 0]}})", "missing.obj: file not found"},
        {R"({"mesh": "cube.obj", "camera": {"eye": [0, 0, 4], "target": [0, 0, 0]}, "extra": 1})", "key 'extra': unknown key"},
    };
    for (const Case& c : cases) {
        const RunResult r = run("render " + scene(c.body).string() + " -o " + (dir / "out").string());
        EXPECT_EQ(r.code, 2) << c.body << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(fs::exists(dir / "out")) << "no output for bad input";
    }
}

TEST_F(Cli, MissingSceneFileAndBadFlagsExit2) {
    EXPECT_EQ(run("render " + (dir / "nope.json").string()).code, 2);
    EXPECT_EQ(run("render").code, 2);
    EXPECT_EQ(run("render " + scene(R"({"mesh": "cube.obj", "camera": {"eye": [3, 2, 4], "target": [0, 0, 0]}})").string() +
                  " --size 0x10").code,
              2);
    const fs::path s = scene(R"({"mesh": "cube.obj", "frames": [1, 3], "camera": {"eye": [3, 2, 4], "target": [0, 0, 0]}})");
    const RunResult r = run("render " + s.string() + " --svg " + (dir / "one.svg").string());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("no frame field"), std::string::npos) << r.output;
}

TEST_F(Cli, UnwritableOutputExits3) {
    test::write_text(dir / "blocker", "a file where a folder should be");
    const fs::path s = scene(R"({"mesh": "cube.obj", "camera": {"eye": [3, 2, 4], "target": [0, 0, 0]}})");
    const RunResult r = run("render " + s.string() + " -o " + (dir / "blocker").string());
    EXPECT_EQ(r.code, 3) << r.output;
    EXPECT_NE(r.output.find("blocker"), std::string::npos) << r.output;
}

TEST_F(Cli, InfoReportsTopology) {
    test::write_obj(dir / "cube.obj", test::cube(1.0));
    const RunResult r = run("info " + (dir / "cube.obj").string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* line : {"vertices: 8", "faces: 12", "edges: 18", "boundary edges: 0", "non-manifold edges: 0",
                             "degenerate faces: 0", "connected components: 1"}) {
        EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
    }
}

}  // namespace
}  // namespace inkline
