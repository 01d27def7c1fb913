// SPDX-License-Identifier: MIT
#include "export/svg.h"

#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <regex>

namespace inkline {
namespace {

output::Drawing cube_drawing(bool hidden) {
    core::LineOptions lines;
    lines.hidden = hidden;
    core::FrameLines frame = test::trace(test::cube(1.0), {.eye = {3.0, 2.5, 4.0}, .size = 640}, lines);
    frame.image = {640, 480};
    return output::centerline_drawing(frame, {});
}

TEST(Svg, SizeLayersAndStrokeIds) {
    const output::Drawing d = cube_drawing(true);
    const std::string svg = output::svg_document(d, {});
    EXPECT_NE(svg.find("width=\"640\" height=\"480\" viewBox=\"0 0 640 480\""), std::string::npos);
    for (const char* layer : {"silhouette", "boundary", "crease", "hidden"}) {
        EXPECT_NE(svg.find(std::string("<g id=\"") + layer + "\" inkscape:groupmode=\"layer\" inkscape:label=\"" + layer),
                  std::string::npos)
            << layer;
    }
    for (const output::Shape& s : d.shapes) {
        EXPECT_NE(svg.find("id=\"stroke-" + std::to_string(s.stroke_id) + "\""), std::string::npos);
    }
    EXPECT_FALSE(std::regex_search(svg, std::regex(R"(\d\.\d{3})"))) << "at most two decimals";
    EXPECT_NE(svg.find("<inkline:frame number="), std::string::npos);
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos) << "hidden lines are dashed";
}

TEST(Svg, NoHiddenLayerWithoutHiddenLines) {
    EXPECT_EQ(output::svg_document(cube_drawing(false), {}).find("id=\"hidden\""), std::string::npos);
}

TEST(Svg, FilledShapesAndBackground) {
    output::Drawing d;
    d.image = {10, 10};
    d.style.background = "#ffffff";
    d.shapes.push_back({.stroke_id = 3, .filled = true, .paths = {{{1, 1}, {9, 1}, {5, 9}}}});
    const std::string svg = output::svg_document(d, {});
    EXPECT_NE(svg.find("<rect id=\"background\" width=\"10\" height=\"10\" fill=\"#ffffff\"/>"), std::string::npos);
    EXPECT_NE(svg.find("<path id=\"stroke-3\" d=\"M1 1 L9 1 L5 9 Z\" fill=\"#000000\" stroke=\"none\"/>"),
              std::string::npos)
        << svg;
}

// A far plane of 1e300 (drawable: only ratios matter) prints as its 301 integer digits in the
// metadata, not cut at a fixed buffer.
TEST(Svg, HugeCameraValuesAreWrittenWhole) {
    output::Drawing d;
    d.image = {10, 10};
    d.camera.near = 1e-300;
    d.camera.far = 1e300;
    const std::string svg = output::svg_document(d, {});
    const std::regex far(R"re(far="1(\d+)")re");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(svg, m, far)) << svg.substr(0, 2000);
    EXPECT_EQ(m[1].length(), 300);
    EXPECT_NE(svg.find("near=\"0\""), std::string::npos);
}

// Three dots of tone: samples 10, 17 and 24, the second at (8, 5.2).
core::FrameTone three_dots() {
    core::FrameTone tone;
    tone.mode = core::ToneMode::kStipple;
    for (uint32_t k = 0; k < 3; ++k) {
        core::Dot dot;
        dot.sample = 10 + 7 * k;
        dot.face = k;
        dot.point_px = {3.0 + 5.0 * k, 4.2 + k};
        dot.radius_px = 1.256;
        dot.tone = 0.3;
        tone.dots.push_back(dot);
    }
    return tone;
}

size_t count_of(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

TEST(Svg, ToneLayerComesFirstWithACirclePerDot) {
    output::Drawing d = cube_drawing(true);
    core::ToneOptions options;
    options.color = {1.0, 0.5, 0.0};
    options.opacity = 0.75;
    d.tone = output::tone_layer(three_dots(), options);
    const std::string svg = output::svg_document(d, {});
    const size_t tone = svg.find("  <g id=\"tone\" inkscape:groupmode=\"layer\" inkscape:label=\"tone\" data-mode=\"stipple\" "
                                 "fill=\"#ff8000\" opacity=\"0.75\">\n");
    ASSERT_NE(tone, std::string::npos) << svg;
    for (const char* layer : {"silhouette", "boundary", "crease", "hidden"}) {
        const size_t at = svg.find(std::string("<g id=\"") + layer + "\"");
        ASSERT_NE(at, std::string::npos) << layer;
        EXPECT_LT(tone, at) << "the tone is drawn under the " << layer << " lines";
    }
    // The dots, and nothing else, inside the tone layer; numbers to two decimals as elsewhere.
    const size_t end = svg.find("  </g>\n", tone);
    const std::string layer = svg.substr(tone, end - tone);
    EXPECT_EQ(count_of(svg, "<circle"), 3u);
    EXPECT_EQ(count_of(layer, "<circle"), 3u);
    EXPECT_EQ(count_of(layer, "<path"), 0u);
    EXPECT_NE(layer.find("    <circle data-sample=\"10\" cx=\"3\" cy=\"4.2\" r=\"1.26\"/>\n"), std::string::npos) << layer;
    EXPECT_NE(layer.find("    <circle data-sample=\"17\" cx=\"8\" cy=\"5.2\" r=\"1.26\"/>\n"), std::string::npos) << layer;
    EXPECT_NE(layer.find("    <circle data-sample=\"24\" cx=\"13\" cy=\"6.2\" r=\"1.26\"/>\n"), std::string::npos) << layer;
}

TEST(Svg, NoToneLayerWithoutTone) {
    output::Drawing d = cube_drawing(true);
    const std::string lines_only = output::svg_document(d, {});
    EXPECT_EQ(lines_only.find("id=\"tone\""), std::string::npos);
    EXPECT_EQ(lines_only.find("<circle"), std::string::npos);
    // A frame whose tone is none draws exactly what a drawing without tone draws.
    d.tone = output::tone_layer(core::FrameTone{}, core::ToneOptions{});
    EXPECT_EQ(output::svg_document(d, {}), lines_only);
}

TEST(Svg, ToneLayerIsKeptWithoutDotsAndUnderObjectAndStyleLayers) {
    // Every frame of a stippled sequence has the layer, dots or not; opaque, no opacity written.
    output::Drawing d = cube_drawing(false);
    core::FrameTone none_drawn;
    none_drawn.mode = core::ToneMode::kStipple;
    d.tone = output::tone_layer(none_drawn, core::ToneOptions{});
    const std::string empty = output::svg_document(d, {});
    EXPECT_NE(empty.find("<g id=\"tone\" inkscape:groupmode=\"layer\" inkscape:label=\"tone\" data-mode=\"stipple\" "
                         "fill=\"#171412\">\n  </g>\n"),
              std::string::npos)
        << empty;
    d.tone = output::tone_layer(three_dots(), core::ToneOptions{});
    output::SvgOptions by_style;
    by_style.layers = output::SvgLayers::kStyle;
    const std::string svg = output::svg_document(d, by_style);
    const size_t tone = svg.find("<g id=\"tone\"");
    ASSERT_NE(tone, std::string::npos);
    EXPECT_LT(tone, svg.find("<g id=\"unstyled\""));
    EXPECT_EQ(count_of(svg, "<circle"), 3u);
}

}  // namespace
}  // namespace inkline
