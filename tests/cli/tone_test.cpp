// SPDX-License-Identifier: MIT
// `inkline render` with tone (scene "tone", --tone): the dots reach the SVG, PNG and JSON, and
// without tone the files are what they were.
#include "tests/support/obj.h"
#include "tests/support/raster.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>
#include <utility>
#include <vector>

namespace inkline {
namespace {

namespace fs = std::filesystem;

class Tone : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // A cube seen from a corner, lit from above, with the scene keys `extra` (",\"tone\": ...").
    fs::path cube_scene(const std::string& name, const std::string& extra) {
        test::write_obj(dir / "cube.obj", test::cube(1.0));
        test::write_text(dir / name, R"({"mesh": "cube.obj", "frames": [1, 1], "image": {"width": 256, "height": 256},
            "camera": {"eye": [3.0, 2.5, 4.0], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40},
            "light": {"direction": [-0.3, -1.0, -0.5]})" + extra + "}");
        return dir / name;
    }

    // Renders `input` frame 1 with `options` into dir/<name>.svg, .json (and .png with `png`).
    test::RunResult render(const fs::path& input, const std::string& name, const std::string& options, bool png = false) {
        const std::string base = (dir / name).string();
        return test::run_inkline("render " + input.string() + " --frames 1 -q --svg " + base + ".svg --json " + base + ".json" +
                                 (png ? " --png " + base + ".png" : std::string()) + " " + options);
    }

    std::string svg(const std::string& name) { return test::read_text(dir / (name + ".svg")); }
    nlohmann::json json(const std::string& name) { return nlohmann::json::parse(test::read_text(dir / (name + ".json"))); }
};

std::vector<long> circle_samples(const std::string& svg) {
    std::vector<long> samples;
    static const std::regex circle(R"re(<circle data-sample="(\d+)" cx="[-\d.]+" cy="[-\d.]+" r="[\d.]+"/>)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it) {
        samples.push_back(std::stol((*it)[1]));
    }
    return samples;
}

// Two spheres side by side, objects "Left" and "Right" of one OBJ file, lit from the camera's
// side, with the scene keys `extra`.
fs::path two_spheres_scene(const fs::path& dir, const std::string& extra) {
    const core::Mesh sphere = test::icosphere(3);
    std::string obj;
    for (const auto& [name, x] : {std::pair{"Left", -1.2}, std::pair{"Right", 1.2}}) {
        const size_t base = name == std::string("Left") ? 0 : sphere.positions.size();
        obj += std::string("o ") + name + "\n";
        for (const glm::vec3& p : sphere.positions) {
            obj += "v " + std::to_string(p.x + x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
        }
        for (const glm::uvec3& t : sphere.triangles) {
            obj += "f " + std::to_string(base + t.x + 1) + " " + std::to_string(base + t.y + 1) + " " +
                   std::to_string(base + t.z + 1) + "\n";
        }
    }
    test::write_text(dir / "spheres.obj", obj);
    test::write_text(dir / "spheres.json", R"({"mesh": "spheres.obj", "frames": [1, 1], "image": {"width": 320, "height": 160},
        "camera": {"eye": [0, 0, 6], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 30},
        "light": {"direction": [0.0, -0.3, -1.0]})" + extra + "}");
    return dir / "spheres.json";
}

// The tone's marks left and right of the image's middle: dots, or hatch points.
std::pair<size_t, size_t> marks_left_and_right(const nlohmann::json& tone) {
    size_t left = 0, right = 0;
    for (const auto& d : tone.value("dots", nlohmann::json::array())) (d["point"][0].get<double>() < 160.0 ? left : right) += 1;
    for (const auto& h : tone.value("hatches", nlohmann::json::array())) {
        for (const auto& p : h["points"]) (p[0].get<double>() < 160.0 ? left : right) += 1;
    }
    return {left, right};
}

TEST_F(Tone, AnObjectCanHaveAToneCurveOfItsOwn) {
    for (const char* mode : {"stipple", "crosshatch"}) {
        SCOPED_TRACE(mode);
        const std::string tone = std::string(R"(, "tone": {"mode": ")") + mode + R"(", "max": 0.6})";
        auto marks = [&](const std::string& objects, const std::string& name) {
            const test::RunResult r = render(two_spheres_scene(dir, tone + objects), name, "");
            EXPECT_EQ(r.code, 0) << r.output;
            return marks_left_and_right(json(name)["tone"]);
        };
        const auto [left, right] = marks("", std::string(mode) + "_same");
        ASSERT_GT(right, 200u);
        EXPECT_NEAR(double(left), double(right), 0.05 * double(right)) << "alike with the scene's curve";
        const auto [light_left, light_right] = marks(R"(, "objects": {"Left": {"tone": {"max": 0.15}}})", std::string(mode) + "_light");
        EXPECT_EQ(light_right, right) << "the other object keeps the scene's curve";
        EXPECT_LT(double(light_left), 0.45 * double(left)) << "a quarter of the darkest tone";
        EXPECT_GT(light_left, 0u);
        const auto [none_left, none_right] = marks(R"(, "objects": {"Left": {"tone": false}})", std::string(mode) + "_none");
        EXPECT_EQ(none_left, 0u);
        EXPECT_EQ(none_right, right);
        // Rules apply key by key in order: the exact name's max over the glob's, the glob's gamma.
        const auto both = marks(R"(, "objects": {"L*": {"tone": {"max": 0.15, "gamma": 2}}, "Left": {"tone": {"max": 0.6}}})",
                                std::string(mode) + "_both");
        const auto direct = marks(R"(, "objects": {"Left": {"tone": {"max": 0.6, "gamma": 2}}})", std::string(mode) + "_direct");
        EXPECT_EQ(both, direct);
        EXPECT_LT(direct.first, left) << "gamma 2 lightens the mid tones";
        EXPECT_GT(direct.first, light_left) << "max 0.6, not 0.15";
        EXPECT_EQ(direct.second, right);
    }
}

// One object stippled, the other hatched: each object's marks are exactly those of a scene of
// that mode in which the other object is unshaded (it still hides them).
TEST_F(Tone, ObjectsCanHaveModesOfTheirOwn) {
    const std::string lit = R"(, "tone": {"mode": "stipple", "max": 0.6})";
    const auto run = [&](const std::string& extra, const std::string& name) {
        const test::RunResult r = render(two_spheres_scene(dir, extra), name, "", true);
        EXPECT_EQ(r.code, 0) << r.output;
        return json(name)["tone"];
    };
    const nlohmann::json mixed = run(lit + R"(, "objects": {"Right": {"tone": {"mode": "crosshatch"}}})", "mixed");
    const nlohmann::json dots_only = run(lit + R"(, "objects": {"Right": {"tone": false}})", "dots_only");
    const nlohmann::json hatch_only =
        run(R"(, "tone": {"mode": "crosshatch", "max": 0.6}, "objects": {"Left": {"tone": false}})", "hatch_only");
    EXPECT_EQ(mixed["mode"], "stipple");
    EXPECT_EQ(mixed["modes"], nlohmann::json::array({"stipple", "crosshatch"}));
    ASSERT_GT(mixed["dots"].size(), 100u);
    ASSERT_GT(mixed["hatches"].size(), 10u);
    EXPECT_EQ(mixed["dots"], dots_only["dots"]);
    EXPECT_EQ(mixed["hatches"], hatch_only["hatches"]);
    EXPECT_EQ(marks_left_and_right(mixed), std::make_pair(mixed["dots"].size(), marks_left_and_right(hatch_only).second));
    EXPECT_EQ(mixed["stats"], dots_only["stats"]);
    EXPECT_EQ(mixed["hatch_stats"], hatch_only["stats"]);
    EXPECT_FALSE(dots_only.contains("modes")) << "one mode: the JSON is as before";
    // The SVG's tone layer holds both kinds of marks.
    const std::string text = svg("mixed");
    EXPECT_EQ(circle_samples(text).size(), mixed["dots"].size());
    EXPECT_NE(text.find("data-family=\"1\""), std::string::npos) << "the second family of crosshatching";
    // An object's mode does not turn tone on, and --tone none turns it off.
    EXPECT_FALSE(run(R"(, "objects": {"Right": {"tone": {"mode": "hatch"}}})", "off").contains("dots"));
    const test::RunResult none = render(two_spheres_scene(dir, lit + R"(, "objects": {"Right": {"tone": {"mode": "hatch"}}})"),
                                        "none", "--tone none");
    ASSERT_EQ(none.code, 0) << none.output;
    EXPECT_FALSE(json("none").contains("tone"));
}

// The marks of a tone without their inks: what a scene without inks of its own draws.
nlohmann::json without_inks(nlohmann::json tone) {
    for (const char* kind : {"dots", "hatches"}) {
        if (!tone.contains(kind)) continue;
        for (auto& mark : tone[kind]) mark.erase("ink");
    }
    return tone;
}

// The circles of an SVG group, by its id.
std::vector<long> group_samples(const std::string& svg, const std::string& id) {
    const size_t at = svg.find("<g id=\"" + id + "\"");
    if (at == std::string::npos) return {};
    return circle_samples(svg.substr(at, svg.find("</g>", at) - at));
}

// A style's tone gives the objects it selects an ink of its own: the marks stay the same, each
// drawn in its object's ink in every output.
TEST_F(Tone, StylesGiveObjectsInksOfTheirOwn) {
    const std::string lit = R"(, "tone": {"mode": "stipple", "max": 0.6})";
    const auto run = [&](const std::string& extra, const std::string& name) {
        const test::RunResult r = render(two_spheres_scene(dir, lit + extra), name, "", true);
        EXPECT_EQ(r.code, 0) << r.output;
        return json(name)["tone"];
    };
    const nlohmann::json plain = run("", "plain");
    const nlohmann::json inked = run(R"(, "styles": [{"name": "warm", "select": {"object": "Right"},
                                                     "tone": {"color": "#a03010", "opacity": 0.7}}])", "inked");
    EXPECT_FALSE(plain.contains("inks")) << "the scene's ink alone: the JSON is as before";
    EXPECT_EQ(inked["inks"], nlohmann::json::parse(R"([{"color": "#171412", "opacity": 1.0, "style": ""},
                                                       {"color": "#a03010", "opacity": 0.7, "style": "warm"}])"));
    ASSERT_GT(plain["dots"].size(), 200u);
    EXPECT_TRUE(without_inks(inked)["dots"] == plain["dots"]) << "an ink moves no dot";
    size_t left = 0, right = 0;
    for (const auto& dot : inked["dots"]) {
        const bool on_right = dot["point"][0].get<double>() > 160.0;
        EXPECT_EQ(dot["ink"].get<int>(), on_right ? 1 : 0);
        (on_right ? right : left) += 1;
    }
    // The SVG: a group per ink inside the tone layer.
    const std::string text = svg("inked");
    EXPECT_NE(text.find("<g id=\"tone-ink-1\" fill=\"#171412\">"), std::string::npos);
    EXPECT_NE(text.find("<g id=\"tone-ink-2\" data-style=\"warm\" fill=\"#a03010\" opacity=\"0.7\">"),
              std::string::npos);
    EXPECT_EQ(group_samples(text, "tone-ink-1").size(), left);
    EXPECT_EQ(group_samples(text, "tone-ink-2").size(), right);
    EXPECT_EQ(svg("plain").find("tone-ink"), std::string::npos);
    // The PNG: the warm ink on the right sphere only.
    const test::Pixels png = test::png_file_pixels(dir / "inked.png");
    size_t warm_left = 0, warm_right = 0;
    for (int y = 0; y < png.height; ++y) {
        for (int x = 0; x < png.width; ++x) {
            const auto& p = png.rgba[size_t(y) * size_t(png.width) + size_t(x)];
            if (p[3] > 64 && p[0] > 120 && p[1] < 90) (x < 160 ? warm_left : warm_right) += 1;
        }
    }
    EXPECT_EQ(warm_left, 0u);
    EXPECT_GT(warm_right, 100u);

    // Hatches take their object's ink too; an objects rule's colour, and a style over it.
    const nlohmann::json mixed = run(R"(, "objects": {"Left": {"tone": {"color": "#0030a0"}}, "Right": {"tone": {"color": "#00ff00"}}},
        "styles": [{"name": "warm", "select": {"object": "Right"}, "tone": {"color": "#a03010", "mode": "crosshatch"}}])", "mixed");
    EXPECT_EQ(mixed["inks"], nlohmann::json::parse(R"([{"color": "#0030a0", "opacity": 1.0, "style": ""},
                                                       {"color": "#a03010", "opacity": 1.0, "style": "warm"}])"));
    ASSERT_GT(mixed["hatches"].size(), 10u);
    for (const auto& dot : mixed["dots"]) EXPECT_EQ(dot["ink"].get<int>(), 0);
    for (const auto& hatch : mixed["hatches"]) EXPECT_EQ(hatch["ink"].get<int>(), 1);
    nlohmann::json plain_left = nlohmann::json::array();
    for (const auto& dot : plain["dots"]) {
        if (dot["point"][0].get<double>() < 160.0) plain_left.push_back(dot);
    }
    EXPECT_TRUE(without_inks(mixed)["dots"] == plain_left) << "the left sphere's dots, as without inks";

    // A style without a selector inks a mesh without objects: one ink, named in the tone layer.
    test::write_obj(dir / "ball.obj", test::icosphere(3));
    test::write_text(dir / "ball_scene.json", R"({"mesh": "ball.obj", "frames": [1, 1], "image": {"width": 160, "height": 160},
        "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40}, "tone": {"max": 0.6},
        "styles": [{"name": "sepia", "tone": {"color": "#704214"}}]})");
    const test::RunResult ball = render(dir / "ball_scene.json", "ball", "");
    ASSERT_EQ(ball.code, 0) << ball.output;
    EXPECT_NE(svg("ball").find("data-mode=\"stipple\" data-style=\"sepia\" fill=\"#704214\">"), std::string::npos);
    EXPECT_EQ(json("ball")["tone"]["inks"],
              nlohmann::json::parse(R"([{"color": "#704214", "opacity": 1.0, "style": "sepia"}])"));
    EXPECT_FALSE(json("ball")["tone"]["dots"][0].contains("ink")) << "one ink: no ink per dot";
}

// A style with a tone selects surfaces, which have no kind and no role.
TEST_F(Tone, AStyleWithAToneAndAKindFailsWithOneLineAndExitCode2) {
    const test::RunResult r = render(two_spheres_scene(dir, R"(, "tone": {}, "styles": [{"select": {"kind": "silhouette"},
        "tone": {"max": 0.2}}])"), "f", "");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("key 'styles[0].tone': a rule with a tone selects by object only, not by kind or role"),
              std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1);
    EXPECT_FALSE(fs::exists(dir / "f.svg"));
}

TEST_F(Tone, BogusModeFailsWithOneLineAndExitCode2) {
    const test::RunResult r = test::run_inkline("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1 --tone bogus -o " +
                                                (dir / "out").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output, "inkline: error: --tone 'bogus': expected stipple, hatch, crosshatch or none\n");
    EXPECT_FALSE(fs::exists(dir / "out" / "svg" / "frame_0001.svg"));
}

TEST_F(Tone, RenderHelpListsTheFlag) {
    const test::RunResult r = test::run_inkline("render --help");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("--tone"), std::string::npos) << r.output;
}

TEST_F(Tone, TorusSampleWithStippleWritesDotsToSvgJsonAndPng) {
    const test::RunResult r = render(std::string(INKLINE_SAMPLES) + "/torus/scene.json", "torus", "--size 512x512 --tone stipple",
                                     true);
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json doc = json("torus");
    ASSERT_TRUE(doc.contains("tone"));
    const nlohmann::json& tone = doc["tone"];
    EXPECT_EQ(tone["mode"], "stipple");
    const nlohmann::json& dots = tone["dots"];
    ASSERT_GT(dots.size(), 100u) << tone["stats"].dump();
    for (const char* key : {"samples", "considered", "wanted", "inked", "occluded"}) EXPECT_TRUE(tone["stats"].contains(key)) << key;
    const size_t faces = doc["stats"]["faces"].get<size_t>();
    std::vector<long> samples;
    for (const auto& d : dots) {
        samples.push_back(d["sample"].get<long>());
        EXPECT_LT(d["face"].get<size_t>(), faces);
        ASSERT_EQ(d["barycentric"].size(), 3u);
        EXPECT_NEAR(d["barycentric"][0].get<double>() + d["barycentric"][1].get<double>() + d["barycentric"][2].get<double>(), 1.0, 1e-6);
        ASSERT_EQ(d["point"].size(), 2u);
        ASSERT_EQ(d["world"].size(), 3u);
        for (int k = 0; k < 2; ++k) {
            EXPECT_GE(d["point"][k].get<double>(), 0.0);
            EXPECT_LE(d["point"][k].get<double>(), 512.0);
        }
        EXPECT_GT(d["radius"].get<double>(), 0.0);
        EXPECT_GE(d["tone"].get<double>(), 0.0);
    }
    EXPECT_TRUE(std::is_sorted(samples.begin(), samples.end()));
    // The SVG's tone layer, under the lines, holds the same dots in the same order.
    const std::string text = svg("torus");
    const size_t layer = text.find("<g id=\"tone\"");
    ASSERT_NE(layer, std::string::npos);
    EXPECT_LT(layer, text.find("<g id=\"silhouette\""));
    EXPECT_EQ(circle_samples(text), samples);
    // The PNG has ink at the centre of every dot drawn at full size.
    const std::vector<uint8_t> ink = test::png_file_coverage(dir / "torus.png", test::Ink::kAlpha);
    size_t checked = 0;
    for (const auto& d : dots) {
        if (d["radius"].get<double>() < 0.99) continue;
        const auto x = size_t(d["point"][0].get<double>()), y = size_t(d["point"][1].get<double>());
        EXPECT_EQ(ink[y * 512 + x], 1) << "dot " << d["sample"];
        ++checked;
    }
    EXPECT_GT(checked, 50u);
}

TEST_F(Tone, TorusSampleWithCrosshatchWritesHatchesToSvgJsonAndPng) {
    const test::RunResult r =
        render(std::string(INKLINE_SAMPLES) + "/torus/scene.json", "torus", "--size 512x512 --tone crosshatch", true);
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json doc = json("torus");
    const nlohmann::json& tone = doc["tone"];
    EXPECT_EQ(tone["mode"], "crosshatch");
    EXPECT_TRUE(tone["dots"].empty());
    const nlohmann::json& hatches = tone["hatches"];
    ASSERT_GT(hatches.size(), 20u);
    for (const char* key : {"faces", "segments", "points", "occluded", "inked"}) EXPECT_TRUE(tone["stats"].contains(key)) << key;
    const size_t edges = doc["stats"]["edges"].get<size_t>();
    std::vector<std::pair<long, long>> ids;
    bool cross = false;
    const std::vector<uint8_t> ink = test::png_file_coverage(dir / "torus.png", test::Ink::kAlpha);
    size_t checked = 0;
    for (const auto& h : hatches) {
        ids.emplace_back(h["family"].get<long>(), h["plane"].get<long>());
        cross |= h["family"] == 1;
        const size_t n = h["points"].size();
        ASSERT_GE(n, 2u);
        ASSERT_EQ(h["world"].size(), n);
        ASSERT_EQ(h["edges"].size(), n);
        ASSERT_EQ(h["width"].size(), n);
        for (size_t k = 0; k < n; ++k) {
            EXPECT_LT(h["edges"][k].get<size_t>(), edges);
            EXPECT_LE(h["width"][k].get<double>(), 0.8 + 1e-9);
            // Ink where a full-width line passes: at its points inside the line, away from its ends.
            if (k == 0 || k + 1 == n || h["width"][k].get<double>() < 0.79) continue;
            const auto x = size_t(h["points"][k][0].get<double>()), y = size_t(h["points"][k][1].get<double>());
            if (ink[y * 512 + x]) ++checked;
        }
    }
    EXPECT_TRUE(cross) << "crosshatch draws the second family where the torus is dark";
    EXPECT_GT(checked, 100u);
    // The SVG's tone layer: one path per hatch, in the JSON's order.
    const std::string text = svg("torus");
    ASSERT_NE(text.find("<g id=\"tone\" inkscape:groupmode=\"layer\" inkscape:label=\"tone\" data-mode=\"crosshatch\""),
              std::string::npos);
    std::vector<std::pair<long, long>> paths;
    static const std::regex path(R"re(<path data-family="(\d+)" data-plane="(\d+)" d="M)re");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), path); it != std::sregex_iterator(); ++it) {
        paths.emplace_back(std::stol((*it)[1]), std::stol((*it)[2]));
    }
    EXPECT_EQ(paths, ids);
    EXPECT_LT(text.find("<g id=\"tone\""), text.find("<g id=\"silhouette\""));
}

// A chunk of a sequence draws the same tone as the whole run: the samples and the hatch planes
// depend on the mesh and the seed alone, and the chunk replays the frames before it.
TEST_F(Tone, ChunkDrawsWhatTheWholeRunDraws) {
    const std::string scene = std::string(INKLINE_SAMPLES) + "/torus/scene.json";
    for (const char* mode : {"stipple", "crosshatch"}) {
        const std::string whole = (dir / (std::string("whole-") + mode)).string();
        const std::string chunk = (dir / (std::string("chunk-") + mode)).string();
        const std::string common = " --frames 1:6 --size 256x256 -q --tone " + std::string(mode);
        ASSERT_EQ(test::run_inkline("render " + scene + common + " -o " + whole).code, 0);
        ASSERT_EQ(test::run_inkline("render " + scene + common + " -o " + chunk + " --chunk 2/2").code, 0);
        for (const char* frame : {"frame_0004", "frame_0005", "frame_0006"}) {
            const std::string a = test::read_text(fs::path(whole) / "svg" / (std::string(frame) + ".svg"));
            EXPECT_NE(a.find("<g id=\"tone\""), std::string::npos);
            EXPECT_EQ(a, test::read_text(fs::path(chunk) / "svg" / (std::string(frame) + ".svg"))) << mode << " " << frame;
        }
    }
}

TEST_F(Tone, SceneToneBlockSetsTheLayersColourAndOpacity) {
    const fs::path scene = cube_scene("scene.json", R"(, "tone": {"color": "#336699", "opacity": 0.5, "max": 0.6})");
    ASSERT_EQ(render(scene, "f", "").code, 0);
    const std::string text = svg("f");
    EXPECT_NE(text.find("<g id=\"tone\" inkscape:groupmode=\"layer\" inkscape:label=\"tone\" data-mode=\"stipple\" fill=\"#336699\" "
                        "opacity=\"0.5\">"),
              std::string::npos)
        << text.substr(0, 2000);
    EXPECT_FALSE(circle_samples(text).empty());
    EXPECT_EQ(json("f")["tone"]["dots"].size(), circle_samples(text).size());
}

TEST_F(Tone, NoneOverridesTheSceneAndWritesWhatAFrameWithoutToneWrites) {
    const fs::path toned = cube_scene("toned_scene.json", R"(, "tone": {"mode": "stipple", "max": 0.6})");
    const fs::path plain = cube_scene("plain_scene.json", "");
    ASSERT_EQ(render(toned, "none", "--tone none").code, 0);
    ASSERT_EQ(render(plain, "plain", "").code, 0);
    ASSERT_EQ(render(plain, "stipple", "--tone stipple").code, 0);
    EXPECT_EQ(svg("none"), svg("plain")) << "byte for byte";
    EXPECT_EQ(svg("none").find("id=\"tone\""), std::string::npos);
    nlohmann::json none = json("none"), lines_only = json("plain");
    EXPECT_FALSE(none.contains("tone"));
    none["stats"].erase("ms");
    lines_only["stats"].erase("ms");
    EXPECT_EQ(none, lines_only);
    // --tone stipple without a tone block: the default tone (its colour, opaque).
    EXPECT_NE(svg("stipple").find("data-mode=\"stipple\" fill=\"#171412\">"), std::string::npos);
    EXPECT_EQ(json("stipple")["tone"]["mode"], "stipple");
}

}  // namespace
}  // namespace inkline
