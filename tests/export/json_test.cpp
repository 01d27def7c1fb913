// SPDX-License-Identifier: MIT
#include "export/json.h"

#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace inkline
