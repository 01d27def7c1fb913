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

}  // namespace
}  // namespace inkline
