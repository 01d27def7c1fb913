// SPDX-License-Identifier: MIT
#include "export/json.h"

#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace inkline {
namespace {

TEST(PolylinesJson, CarriesTheFrameAndEveryStroke) {
    core::LineOptions lines;
    lines.hidden = true;
    core::FrameLines frame = test::trace(test::cube(1.0), {.eye = {3.0, 2.5, 4.0}, .size = 512}, lines);
    frame.frame = 7;
    const auto doc = nlohmann::json::parse(output::polylines_json(frame));
    EXPECT_EQ(doc["format"], "inkline.polylines");
    EXPECT_EQ(doc["version"], 1);
    EXPECT_EQ(doc["frame"], 7);
    EXPECT_EQ(doc["image"]["width"], 512);
    EXPECT_EQ(doc["camera"]["eye"][0], 3.0);
    for (const char* key : {"eye", "target", "up", "fov_y_deg", "near", "far"}) EXPECT_TRUE(doc["camera"].contains(key)) << key;
    EXPECT_TRUE(doc["light"].contains("direction"));
    ASSERT_EQ(doc["strokes"].size(), frame.polylines.size());
    for (size_t i = 0; i < frame.polylines.size(); ++i) {
        const auto& s = doc["strokes"][i];
        const core::Polyline& line = frame.polylines[i];
        EXPECT_EQ(s["id"], line.id);
        EXPECT_EQ(s["kind"], core::line_kind_name(line.kind));
        EXPECT_EQ(s["visible"], line.visible);
        ASSERT_EQ(s["points"].size(), line.points_px.size());
        ASSERT_EQ(s["world"].size(), line.points_world.size());
        ASSERT_EQ(s["edges"].size() + 1, line.points_px.size());
        EXPECT_NEAR(s["points"][0][0].get<double>(), line.points_px[0].x, 1e-4);
    }
    for (const char* key : {"faces", "edges", "edges_tested", "feature_edges", "visible_length_px", "ms"})
        EXPECT_TRUE(doc["stats"].contains(key)) << key;
    EXPECT_EQ(doc["stats"]["feature_edges"]["silhouette"], 6);
}

core::FrameLines cube_frame() {
    return test::trace(test::cube(1.0), {.eye = {3.0, 2.5, 4.0}, .size = 512});
}

TEST(PolylinesJson, ListsTheToneDots) {
    const core::FrameLines frame = cube_frame();
    core::FrameTone tone;
    tone.mode = core::ToneMode::kStipple;
    core::Dot dot;
    dot.sample = 42;
    dot.face = 7;
    dot.barycentric = {0.25, 0.5, 0.25};
    dot.point_px = {100.123456, 200.5};
    dot.point_world = {0.1, -0.2, 0.3};
    dot.radius_px = 0.75;
    dot.tone = 0.123456;
    tone.dots = {dot, dot};
    tone.dots[1].sample = 43;
    tone.stipple_stats = {.samples = 1000, .considered = 500, .wanted = 40, .inked = 3, .occluded = 2};
    const auto doc = nlohmann::json::parse(output::polylines_json(frame, nullptr, &tone));
    ASSERT_TRUE(doc.contains("tone"));
    const auto& t = doc["tone"];
    EXPECT_EQ(t["mode"], "stipple");
    ASSERT_EQ(t["dots"].size(), 2u);
    const auto& d = t["dots"][0];
    EXPECT_EQ(d.size(), 7u) << d.dump();
    EXPECT_EQ(d["sample"], 42);
    EXPECT_EQ(t["dots"][1]["sample"], 43);
    EXPECT_EQ(d["face"], 7);
    EXPECT_EQ(d["barycentric"], nlohmann::json::array({0.25, 0.5, 0.25}));
    EXPECT_EQ(d["point"], nlohmann::json::array({100.1235, 200.5})) << "px to 1e-4, as the strokes' points";
    EXPECT_EQ(d["world"], nlohmann::json::array({0.1, -0.2, 0.3}));
    EXPECT_EQ(d["radius"], 0.75);
    EXPECT_EQ(d["tone"], 0.1235);
    EXPECT_EQ(t["stats"], nlohmann::json({{"samples", 1000}, {"considered", 500}, {"wanted", 40}, {"inked", 3},
                                          {"occluded", 2}}));
    // An empty frame of a stippled sequence still says so.
    tone.dots.clear();
    const auto empty = nlohmann::json::parse(output::polylines_json(frame, nullptr, &tone));
    EXPECT_TRUE(empty["tone"]["dots"].is_array());
    EXPECT_TRUE(empty["tone"]["dots"].empty());
}

// The dots and hatches are written one by one as text (a frame's dots can run to millions): the
// text is what dumping the whole document would give, also with objects named as the markers an
// earlier writer spliced them in at.
TEST(PolylinesJson, ToneIsWrittenAsTheWholeDocumentWouldBe) {
    core::FrameLines frame = cube_frame();
    frame.objects = {{.name = "\x01inkline-dots"}, {.name = "\x01inkline-hatches"}};
    for (core::Polyline& line : frame.polylines) line.object = 0;
    for (const core::ToneMode mode : {core::ToneMode::kStipple, core::ToneMode::kCrosshatch}) {
        core::FrameTone tone;
        tone.mode = mode;
        if (mode == core::ToneMode::kStipple) {
            for (uint32_t i = 0; i < 1000; ++i) {
                tone.dots.push_back({.sample = i, .face = i % 7, .barycentric = {0.2, 0.3, 0.5},
                                     .point_px = {i * 0.37, 1e4 / (i + 1.0)}, .point_world = {i * 1e-3, -1.0 / 3.0, 2.0},
                                     .radius_px = 0.5 + i % 3, .tone = i / 1000.0});
            }
        } else {
            for (uint32_t i = 0; i < 50; ++i) {
                core::Hatch h;
                h.family = i % 2;
                h.plane = 1000 + i;
                h.level = 3;
                h.points_px = {{i, 2.0 * i}, {i + 0.5, 2.0 * i + 1.0 / 3.0}};
                h.points_world = {{0.1, 0.2, 0.3}, {0.4, 0.5, 1.0 / 7.0}};
                h.edges = {i, i + 1};
                h.width_px = {0.8, 0.4};
                tone.hatches.push_back(h);
            }
        }
        const std::string text = output::polylines_json(frame, nullptr, &tone);
        const nlohmann::json doc = nlohmann::json::parse(text);
        EXPECT_EQ(doc.dump() + "\n", text) << core::tone_mode_name(mode);
        EXPECT_EQ(doc["tone"]["dots"].size(), tone.dots.size());
        if (mode == core::ToneMode::kCrosshatch) {
            ASSERT_EQ(doc["tone"]["hatches"].size(), 50u);
            EXPECT_EQ(doc["tone"]["hatches"][49]["plane"], 1049);
            EXPECT_EQ(doc["tone"]["hatches"][3]["edges"], nlohmann::json::array({3, 4}));
        } else {
            EXPECT_EQ(doc["tone"]["dots"][999]["sample"], 999);
        }
        EXPECT_NE(text.find("\"\\u0001inkline-dots\""), std::string::npos) << "the object's name is kept";
    }
}

// The strokes are written as text, not built as a document first: the text is what dumping the
// whole document gives, with every optional key, names that need escaping, and numbers of every
// kind (a non-finite one is null).
TEST(PolylinesJson, StrokesAreWrittenAsTheWholeDocumentWouldBe) {
    test::Drawn drawn = test::draw(test::torus(1.0, 0.4, 48, 24), test::scene_for({.eye = {0.5, 2.5, 3.0}, .size = 512},
                                                                                  test::torus(1.0, 0.4, 48, 24)));
    core::FrameStrokes& strokes = drawn.strokes;
    ASSERT_GE(strokes.strokes.size(), 3u);
    drawn.lines.objects = {{.name = "ring \"\xc3\xa4\" \\ tab\t\x01", .node = 4}, {.name = "plain"}};
    core::StrokeStyle dotted;
    dotted.name = "dotted \"hidden\"";
    dotted.rule = 0;
    strokes.styles.push_back(dotted);
    core::WriteOnFrame write_on;
    write_on.time_s = 0.25;
    write_on.seconds = 1.0 / 3.0;
    write_on.speed_px_s = 1234.5678;
    for (size_t k = 0; k < strokes.strokes.size(); ++k) {
        core::Stroke& s = strokes.strokes[k];
        s.geometry.object = int32_t(k % 3) - 1;  // none, the first object, the second
        s.style = uint32_t(k % 2);
        s.parent = k % 2 ? int64_t(k) : -1;
        if (k == 0) {
            s.geometry.bridged.assign(s.geometry.edges.size(), 0);
            s.geometry.bridged.back() = 1;
            s.intensity.front() = std::nan("");
            s.u.back() = 1e21;
            s.width.front() = -0.0;
        }
        write_on.strokes.push_back({.start_s = k % 2 ? -1.0 : k / 7.0, .end_s = k % 2 ? -1.0 : k / 3.0,
                                    .drawn_px = 12.3456, .length_px = 1.0 / 3.0});
    }
    strokes.write_on = write_on;
    const std::string text = output::polylines_json(drawn.lines, &strokes);
    const nlohmann::json doc = nlohmann::json::parse(text);
    EXPECT_EQ(doc.dump() + "\n", text);
    const nlohmann::json& first = doc["strokes"][0];
    EXPECT_TRUE(first["intensity"][0].is_null());
    EXPECT_EQ(first["hidden_segments"], nlohmann::json::array({first["edges"].size() - 1}));
    EXPECT_EQ(doc["strokes"][1]["object"], drawn.lines.objects[0].name);
    EXPECT_EQ(doc["strokes"][1]["node"], 4);
    EXPECT_EQ(doc["strokes"][1]["style"], "dotted \"hidden\"");
    EXPECT_TRUE(doc["strokes"][1]["write_on"]["start"].is_null());
    EXPECT_EQ(doc["strokes"][2]["write_on"]["end"], 0.666667);
    EXPECT_FALSE(doc["strokes"][2].contains("node"));
    EXPECT_EQ(doc["strokes"].size(), strokes.strokes.size());
}

TEST(PolylinesJson, NoToneWithoutTone) {
    const core::FrameLines frame = cube_frame();
    const std::string lines_only = output::polylines_json(frame);
    EXPECT_FALSE(nlohmann::json::parse(lines_only).contains("tone"));
    const core::FrameTone none;
    EXPECT_EQ(output::polylines_json(frame, nullptr, &none), lines_only) << "byte for byte";
}

}  // namespace
}  // namespace inkline
