// SPDX-License-Identifier: MIT
#include "export/svg.h"

#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <regex>

namespace inkline {
namespace {

TEST(Svg, SizeLayersAndStrokeIds) {
    core::LineOptions lines;
    lines.hidden = true;
    core::FrameLines frame = test::trace(test::cube(1.0), {.eye = {3.0, 2.5, 4.0}, .size = 640}, lines);
    frame.image = {640, 480};
    const std::string svg = output::centerline_svg(frame, {});
    EXPECT_NE(svg.find("width=\"640\" height=\"480\" viewBox=\"0 0 640 480\""), std::string::npos);
    for (const char* layer : {"silhouette", "boundary", "crease", "hidden"}) {
        EXPECT_NE(svg.find(std::string("<g id=\"") + layer + "\" inkscape:groupmode=\"layer\""), std::string::npos) << layer;
    }
    for (const core::Polyline& line : frame.strokes) {
        EXPECT_NE(svg.find("id=\"stroke-" + std::to_string(line.id) + "\""), std::string::npos);
    }
    // Coordinates carry at most two decimals.
    EXPECT_FALSE(std::regex_search(svg, std::regex(R"(\d\.\d{3})")));
    EXPECT_NE(svg.find("<inkline:frame number="), std::string::npos);
}

TEST(Svg, NoHiddenLayerWithoutHiddenLines) {
    const core::FrameLines frame = test::trace(test::cube(1.0), {.eye = {3.0, 2.5, 4.0}});
    EXPECT_EQ(output::centerline_svg(frame, {}).find("id=\"hidden\""), std::string::npos);
}

}  // namespace
}  // namespace inkline
