// SPDX-License-Identifier: MIT
#include "core/visibility/visibility.h"

#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace inkline {
namespace {

// Hides every point with x beyond a threshold: an occluder whose edge is a vertical line.
class HideBeyondX final : public core::Occlusion {
  public:
    explicit HideBeyondX(double x) : x_(x) {}
    void occluded(const core::Viewpoint&, std::span<const core::OcclusionQuery> queries,
                  std::span<uint8_t> r_occluded) const override {
        for (size_t i = 0; i < queries.size(); ++i) r_occluded[i] = queries[i].p_object.x > x_;
    }

  private:
    double x_;
};

// Hides nothing and keeps every point it was asked about.
class RecordQueries final : public core::Occlusion {
  public:
    void occluded(const core::Viewpoint&, std::span<const core::OcclusionQuery> queries,
                  std::span<uint8_t> r_occluded) const override {
        for (size_t i = 0; i < queries.size(); ++i) {
            points.push_back(queries[i].p_object);
            r_occluded[i] = 0;
        }
    }
    mutable std::vector<glm::dvec3> points;
};

core::Projection front_view() {
    const core::Camera camera{{0.0, 0.0, 4.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 35.0, 1.0, 10.0};
    return core::Projection(camera, {1024, 1024}, glm::dmat4(1.0));
}

// Regression (found comparing GL and exact visibility): a hidden run that folds back on itself
// ends close to where it began, but it is long and must not be merged away as too short.
TEST(Visibility, HairpinHiddenRunIsMeasuredAlongTheChain) {
    core::Mesh mesh;
    mesh.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0003f, 0.0f}};
    const core::Chain hairpin{.kind = core::LineKind::kSilhouette, .closed = false, .vertices = {0, 1, 2}, .edges = {0, 1}, .points = {}, .crossing_faces = {}, .faces = {}, .first_faces = {}, .facing = {}};
    core::VisibilityOptions options;
    options.keep_hidden = true;
    const auto lines = core::split_by_visibility({hairpin}, mesh, front_view(), HideBeyondX(0.9), options);
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_TRUE(lines[0].visible);
    EXPECT_FALSE(lines[1].visible);
    EXPECT_TRUE(lines[2].visible);
    EXPECT_GT(lines[1].length_px(), 50.0);
    // The cuts sit where the occluder's edge crosses, to the bisection's 1/8 px.
    const double px_per_unit = 512.0 / (4.0 * std::tan(glm::radians(17.5)));
    EXPECT_NEAR(lines[1].points_px.front().x, 512.0 + 0.9 * px_per_unit, 0.2);
}

TEST(Visibility, ShortRunsBelowTheBisectionPrecisionMerge) {
    // A straight chain hidden only within 0.05 px of its end keeps one visible run.
    core::Mesh mesh;
    mesh.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
    const core::Chain line{.kind = core::LineKind::kCrease, .closed = false, .vertices = {0, 1}, .edges = {0}, .points = {}, .crossing_faces = {}, .faces = {}, .first_faces = {}, .facing = {}};
    const double px_per_unit = 512.0 / (4.0 * std::tan(glm::radians(17.5)));
    const auto lines = core::split_by_visibility({line}, mesh, front_view(), HideBeyondX(1.0 - 0.05 / px_per_unit),
                                                 {.keep_hidden = true});
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_TRUE(lines[0].visible);
}

// A straight chain of 0 to 1 along x in `segments` equal segments.
std::pair<core::Mesh, core::Chain> straight_chain(uint32_t segments) {
    core::Mesh mesh;
    core::Chain chain;
    for (uint32_t i = 0; i <= segments; ++i) {
        mesh.positions.push_back({float(i) / float(segments), 0.0f, 0.0f});
        chain.vertices.push_back(i);
        if (i < segments) chain.edges.push_back(i);
    }
    return {mesh, chain};
}

// Queries follow the drawing's length: a chain of sub-pixel segments is sampled about every
// 2 px, not at each of its vertices, and no two neighbouring samples are further apart.
TEST(Visibility, FineChainsAreSampledByLengthNotByVertex) {
    const double px_per_unit = 512.0 / (4.0 * std::tan(glm::radians(17.5)));  // about 403 px
    const auto [mesh, chain] = straight_chain(20000);
    RecordQueries record;
    const auto lines = core::split_by_visibility({chain}, mesh, front_view(), record, {});
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].points_px.size(), 20001u);  // the polyline keeps every vertex
    const auto& p = record.points;
    ASSERT_GE(p.size(), 2u);
    // A sample at least every 2 px, and no closer than 2 px less one segment (0.02 px).
    const double segment_px = px_per_unit / 20000.0;
    EXPECT_GE(double(p.size()), px_per_unit / 2.0 + 1.0);
    EXPECT_LE(double(p.size()), px_per_unit / (2.0 - segment_px) + 2.0);
    EXPECT_DOUBLE_EQ(p.front().x, 0.0);
    EXPECT_DOUBLE_EQ(p.back().x, 1.0);
    for (size_t i = 1; i < p.size(); ++i) EXPECT_LE((p[i].x - p[i - 1].x) * px_per_unit, 2.0 + 1e-9);
}

// Where segments are longer than the spacing, every vertex is a sample, with samples between.
TEST(Visibility, CoarseChainsAreSampledAtEveryVertex) {
    const double px_per_unit = 512.0 / (4.0 * std::tan(glm::radians(17.5)));
    const auto [mesh, chain] = straight_chain(50);  // 8 px segments
    RecordQueries record;
    core::split_by_visibility({chain}, mesh, front_view(), record, {});
    for (uint32_t v = 0; v <= 50; ++v) {
        const double x = double(mesh.positions[v].x);
        EXPECT_TRUE(std::any_of(record.points.begin(), record.points.end(),
                                [&](const glm::dvec3& q) { return std::abs(q.x - x) < 1e-12; }))
            << "vertex " << v;
    }
    for (size_t i = 1; i < record.points.size(); ++i) {
        EXPECT_LE((record.points[i].x - record.points[i - 1].x) * px_per_unit, 2.0 + 1e-9);
    }
}

}  // namespace
}  // namespace inkline
