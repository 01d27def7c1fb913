// SPDX-License-Identifier: MIT
// `inkline render` with line styles: what each rule selects, as the SVG, PNG and JSON show it.
#include "core/strokes/line_styles.h"
#include "tests/support/gltf.h"
#include "tests/support/obj.h"
#include "tests/support/raster.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace inkline {
namespace {

namespace fs = std::filesystem;

class Styles : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }
};

// The torus sample seen from low down, its hidden lines as dots 6 px apart and its visible lines
// made invisible by a rule: the PNG holds one dot for each multiple of 6 px of u along every
// hidden stroke.
TEST_F(Styles, DottedHiddenLinesOnTheTorusDrawADotEverySixPixelsOfU) {
    test::write_text(dir / "scene.json", R"({"mesh": ")" + std::string(INKLINE_SAMPLES) + R"(/torus/torus.obj",
        "frames": [1, 1], "image": {"width": 1024, "height": 1024},
        "camera": {"eye": [0.0, 0.8, 4.6], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40},
        "lines": {"hidden": true},
        "styles": [{"name": "unseen", "select": {"kind": ["silhouette", "boundary", "crease"]}, "opacity": 0},
                   {"name": "dotted", "select": {"kind": "hidden"}, "dash_px": [0, 6], "line_width_px": 2.5}]})");
    const auto r = test::run_inkline("render " + (dir / "scene.json").string() + " -q --svg " + (dir / "%04d.svg").string() +
                                     " --png " + (dir / "%04d.png").string() + " --json " + (dir / "%04d.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    // Where the dots belong: u = 6 k along every hidden stroke's drawn centerline, as the SVG has
    // it, u starting at the stroke's first u.
    const nlohmann::json j = nlohmann::json::parse(test::read_text(dir / "0001.json"));
    const std::string svg = test::read_text(dir / "0001.svg");
    std::vector<glm::dvec2> dots;
    for (const auto& s : j["strokes"]) {
        if (s["visible"]) {
            EXPECT_EQ(s["style"], "unseen");
            continue;
        }
        EXPECT_EQ(s["style"], "dotted");
        const size_t at = svg.find("<path id=\"stroke-" + std::to_string(s["id"].get<int>()) + "\"");
        ASSERT_NE(at, std::string::npos);
        const size_t d_at = svg.find(" d=\"", at) + 4;
        std::string data = svg.substr(d_at, svg.find('"', d_at) - d_at);
        for (char& c : data) c = (c == 'M' || c == 'L') ? ' ' : c;
        std::istringstream d(data);
        std::vector<glm::dvec2> path;
        for (std::string x; d >> x;) {
            if (x == "Z") {
                path.push_back(path.front());
                continue;
            }
            glm::dvec2 p{std::stod(x), 0.0};
            d >> p.y;
            path.push_back(p);
        }
        double u = s["u"].front().get<double>();
        for (size_t k = 0; k + 1 < path.size(); ++k) {
            const double len = glm::length(path[k + 1] - path[k]);
            for (double next = std::ceil(u / 6.0) * 6.0; next <= u + len && len > 0.0; next += 6.0) {
                dots.push_back(path[k] + (path[k + 1] - path[k]) * ((next - u) / len));
            }
            u += len;
        }
    }
    ASSERT_GT(dots.size(), 100u);
    EXPECT_NE(svg.find("data-style=\"dotted\""), std::string::npos);
    EXPECT_NE(svg.find("stroke-width=\"2.5\" stroke-linecap=\"round\" stroke-linejoin=\"round\" stroke-dasharray=\"0 6\""),
              std::string::npos);
    EXPECT_EQ(test::run_shell("xmllint --noout " + (dir / "0001.svg").string()).code, 0);
    // Every inked pixel belongs to a dot (within its radius and half a pixel's diagonal), and every
    // dot is inked. Hidden lines are drawn at half opacity.
    const std::vector<uint8_t> ink = test::png_file_coverage(dir / "0001.png", test::Ink::kFaint);
    const auto nearest_dot = [&](const glm::dvec2& q) {
        double best = 1e300;
        for (const glm::dvec2& d : dots) best = std::min(best, glm::length(d - q));
        return best;
    };
    size_t inked = 0, stray = 0;
    for (int y = 0; y < 1024; ++y) {
        for (int x = 0; x < 1024; ++x) {
            if (!ink[size_t(y) * 1024 + size_t(x)]) continue;
            ++inked;
            const double far = nearest_dot({x + 0.5, y + 0.5});
            stray += far > 1.25 + 0.75;
        }
    }
    EXPECT_GT(inked, dots.size());
    EXPECT_EQ(stray, 0u) << "of " << inked << " inked pixels";
    size_t missing = 0;
    for (const glm::dvec2& d : dots) {
        bool found = false;
        for (int y = int(d.y) - 1; y <= int(d.y) + 1 && !found; ++y) {
            for (int x = int(d.x) - 1; x <= int(d.x) + 1 && !found; ++x) {
                found = x >= 0 && y >= 0 && x < 1024 && y < 1024 && ink[size_t(y) * 1024 + size_t(x)];
            }
        }
        missing += !found;
    }
    EXPECT_EQ(missing, 0u) << "of " << dots.size() << " dots";
}

// Rules by object and role on a glTF shot: colours, opacities and names in SVG and JSON, and
// --layers style puts every path in its style's layer.
TEST_F(Styles, RulesByObjectAndRoleColourLayerAndNameTheStrokes) {
    const core::Mesh cube = test::cube(0.5);
    std::vector<float> positions;
    for (const glm::vec3& p : cube.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    std::vector<uint32_t> indices;
    for (const glm::uvec3& t : cube.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
    test::GltfBuilder b;
    b.mesh_node("Cube", positions, indices);
    b.mesh_node("Wall", {-3, -1, -2, 3, -1, -2, 3, 1, -2, -3, 1, -2}, {0, 1, 2, 0, 2, 3});
    const int cam = b.node("Camera");
    b.json()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"aspectRatio", 1.0}, {"znear", 0.1}}}}};
    b.json()["nodes"][size_t(cam)]["camera"] = 0;
    b.json()["nodes"][size_t(cam)]["translation"] = {0.3, 0.2, 6};
    b.finish_scene();
    b.write(dir / "shot.glb");
    test::write_text(dir / "scene.json", R"({"mesh": "shot.glb", "image": {"width": 512, "height": 512},
        "styles": [{"name": "cube-ink", "select": {"object": "Cu*"}, "color": "#ff0000"},
                   {"name": "wall-outer", "select": {"object": "Wall", "role": "outer"}, "opacity": 0.5, "width_max_px": 2}]})");
    const auto r = test::run_inkline("render " + (dir / "scene.json").string() + " -q --layers style --svg " +
                                     (dir / "%04d.svg").string() + " --json " + (dir / "%04d.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(test::read_text(dir / "0001.json"));
    std::set<std::string> cube_styles, wall_styles;
    for (const auto& s : j["strokes"]) {
        const std::string style = s.contains("style") ? s["style"].get<std::string>() : "";
        (s["object"] == "Cube" ? cube_styles : wall_styles).insert(style);
        if (style == "wall-outer") {
            for (const auto& w : s["width"]) EXPECT_LE(w.get<double>(), 2.0 + 1e-9);
        }
    }
    EXPECT_EQ(cube_styles, (std::set<std::string>{"cube-ink"}));
    // The wall's border is its outer contour; the wall's part of the cube's outline is not the wall's.
    EXPECT_EQ(wall_styles, (std::set<std::string>{"wall-outer"}));

    const std::string svg = test::read_text(dir / "0001.svg");
    const size_t cube_layer = svg.find("<g id=\"style-cube-ink\" inkscape:groupmode=\"layer\" inkscape:label=\"cube-ink\"");
    const size_t wall_layer = svg.find("<g id=\"style-wall-outer\" inkscape:groupmode=\"layer\" inkscape:label=\"wall-outer\"");
    ASSERT_NE(cube_layer, std::string::npos) << svg.substr(0, 2000);
    ASSERT_NE(wall_layer, std::string::npos) << svg.substr(0, 2000);
    EXPECT_LT(cube_layer, wall_layer);  // in the order of the rules
    EXPECT_NE(svg.find("<g id=\"style-cube-ink-silhouette\"", cube_layer), std::string::npos);
    for (size_t at = svg.find("data-style=\"cube-ink\""); at != std::string::npos; at = svg.find("data-style=\"cube-ink\"", at + 1)) {
        EXPECT_GT(at, cube_layer);
        EXPECT_LT(at, wall_layer);
        const std::string red = " fill=\"#ff0000\"";
        EXPECT_EQ(svg.compare(svg.find(" fill=", at), red.size(), red), 0);
    }
    // One opacity for the whole layer.
    EXPECT_NE(svg.find("<g id=\"style-wall-outer-boundary\" inkscape:groupmode=\"layer\" inkscape:label=\"boundary\" opacity=\"0.5\">"),
              std::string::npos);
    EXPECT_EQ(test::run_shell("xmllint --noout " + (dir / "0001.svg").string()).code, 0);

    // Bad rules stop the run before any file is written.
    test::write_text(dir / "bad.json", R"({"mesh": "shot.glb", "styles": [{"select": {"kind": "outline"}}]})");
    const auto bad = test::run_inkline("render " + (dir / "bad.json").string() + " -q --svg " + (dir / "bad/%04d.svg").string());
    EXPECT_EQ(bad.code, 2) << bad.output;
    EXPECT_NE(bad.output.find("key 'styles[0].select.kind': 'outline'"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir / "bad"));
}

// The SVG of a styled frame (colours, a layer opacity, dots and dashes, Bézier paths or polygons)
// renders the same in librsvg and in Inkscape.
TEST_F(Styles, SvgRendersTheSameInRsvgAndInkscape) {
    if (test::run_shell("command -v inkscape").code != 0) GTEST_SKIP() << "inkscape is not installed (.ci/setup installs it)";
    test::write_text(dir / "scene.json", R"({"mesh": ")" + std::string(INKLINE_SAMPLES) + R"(/torus/torus.obj",
        "frames": [1, 1], "image": {"width": 800, "height": 800},
        "camera": {"eye": [0.0, 0.8, 4.6], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40},
        "lines": {"hidden": true},
        "styles": [{"name": "outer", "select": {"role": "outer"}, "width_max_px": 6, "color": "#1d3557"},
                   {"name": "inner", "select": {"role": "inner"}, "dash_px": [10, 4], "cap": "butt", "opacity": 0.7},
                   {"name": "dotted", "select": {"kind": "hidden"}, "dash_px": [0, 6], "line_width_px": 2.5}]})");
    for (const char* format : {"polygon", "bezier"}) {
        const fs::path svg = dir / (std::string(format) + ".svg");
        const auto r = test::run_inkline("render " + (dir / "scene.json").string() + " -q --path-format " + format +
                                         " --svg " + svg.string());
        ASSERT_EQ(r.code, 0) << r.output;
        const fs::path by_rsvg = dir / (std::string(format) + "-rsvg.png"), by_inkscape = dir / (std::string(format) + "-inkscape.png");
        ASSERT_EQ(test::run_shell("rsvg-convert -o " + by_rsvg.string() + " " + svg.string()).code, 0);
        const auto ink = test::run_shell("HOME=" + dir.string() + " inkscape --export-type=png --export-filename=" +
                                         by_inkscape.string() + " " + svg.string());
        ASSERT_EQ(ink.code, 0) << ink.output;
        const std::vector<uint8_t> a = test::png_file_coverage(by_rsvg, test::Ink::kFaint);
        const std::vector<uint8_t> b = test::png_file_coverage(by_inkscape, test::Ink::kFaint);
        EXPECT_GT(std::count(a.begin(), a.end(), uint8_t(1)), 5000) << format;
        const double iou = test::iou(a, b);
        std::printf("%s: ink IoU between rsvg-convert and Inkscape %.4f\n", format, iou);
        EXPECT_GE(iou, 0.98) << format;
    }
}

// brush.texture on the bundled sample: the SVG, rasterised by rsvg-convert, covers what the GL
// preview's textured tip covers, and the files stay within five times the flat ones' size.
TEST_F(Styles, TexturedSvgMatchesTheGlPreviewAndStaysSmall) {
    const std::string sample = std::string(INKLINE_SAMPLES) + "/torus/scene.json";
    nlohmann::json scene = nlohmann::json::parse(test::read_text(sample));
    scene["mesh"] = std::string(INKLINE_SAMPLES) + "/torus/torus.obj";
    scene["brush"] = {{"texture", true}};
    test::write_text(dir / "textured.json", scene.dump());
    const auto flat = test::run_inkline("render " + sample + " -q --frames 1:6 --svg " + (dir / "flat/%04d.svg").string());
    ASSERT_EQ(flat.code, 0) << flat.output;
    const auto r = test::run_inkline("render " + (dir / "textured.json").string() + " -q --frames 1:6 --svg " +
                                     (dir / "tex/%04d.svg").string() + " --preview " + (dir / "tex/p%04d.png").string());
    ASSERT_EQ(r.code, 0) << r.output;
    uintmax_t flat_bytes = 0, textured_bytes = 0;
    for (int f = 1; f <= 6; ++f) {
        char name[16];
        std::snprintf(name, sizeof name, "%04d", f);
        flat_bytes += fs::file_size(dir / "flat" / (std::string(name) + ".svg"));
        textured_bytes += fs::file_size(dir / "tex" / (std::string(name) + ".svg"));
        const fs::path svg = dir / "tex" / (std::string(name) + ".svg"), png = dir / "tex" / (std::string(name) + ".png");
        ASSERT_EQ(test::run_shell("rsvg-convert -o " + png.string() + " " + svg.string()).code, 0);
        const std::vector<uint8_t> vector_ink = test::png_file_coverage(png, test::Ink::kAlpha);
        const std::vector<uint8_t> preview_ink =
            test::png_file_coverage(dir / "tex" / ("p" + std::string(name) + ".png"), test::Ink::kAlpha);
        EXPECT_GT(std::count(vector_ink.begin(), vector_ink.end(), uint8_t(1)), 5000);
        const double iou = test::iou(vector_ink, preview_ink);
        std::printf("frame %d: ink IoU of the textured SVG with the GL preview %.4f\n", f, iou);
        EXPECT_GE(iou, 0.9) << "frame " << f;
        // The texture is there: holes in the ink, written as rings after each outline.
        if (f == 1) {
            EXPECT_NE(test::read_text(svg).find(" Z M"), std::string::npos);
        }
    }
    const double ratio = double(textured_bytes) / double(flat_bytes);
    std::printf("textured SVG %.2fx the flat SVG's size\n", ratio);
    EXPECT_LE(ratio, 5.0);
    EXPECT_GT(ratio, 1.2) << "the texture adds shapes";
}

// The three looks of docs/guide.md render, every rule of theirs draws something, and the SVG is
// well-formed.
TEST_F(Styles, TheGuidesLooksRender) {
    for (const char* look : {"pen-and-ink", "technical", "brush"}) {
        const std::string scene = std::string(INKLINE_SAMPLES) + "/looks/" + look + ".json";
        const fs::path svg = dir / (std::string(look) + ".svg");
        const auto r = test::run_inkline("render " + scene + " -q --svg " + svg.string());
        ASSERT_EQ(r.code, 0) << look << ": " << r.output;
        EXPECT_EQ(test::run_shell("xmllint --noout " + svg.string()).code, 0) << look;
        const std::string text = test::read_text(svg);
        const auto parsed = nlohmann::json::parse(test::read_text(scene));
        for (const auto& rule : parsed.at("styles")) {
            EXPECT_NE(text.find("data-style=\"" + rule["name"].get<std::string>() + "\""), std::string::npos)
                << look << ": " << rule["name"];
        }
    }
}

}  // namespace
}  // namespace inkline
