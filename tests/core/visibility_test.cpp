// SPDX-License-Identifier: MIT
#include "core/visibility/visibility.h"

#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace inkline {
namespace {

// Hides every point with x beyond a threshold: an occluder whose edge is a vertical line.
class HideBeyondX final : public core::Occlusion {
  public:
    explicit HideBeyondX(double x) : x_(x) {}
    void occluded(const glm::dvec3&, std::span<const core::OcclusionQuery> queries,
                  std::span<uint8_t> r_occluded) const override {
        for (size_t i = 0; i < queries.size(); ++i) r_occluded[i] = queries[i].p_object.x > x_;
    }

  private:
    double x_;
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
    const core::Chain hairpin{core::LineKind::kSilhouette, false, {0, 1, 2}, {0, 1}};
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
    const core::Chain line{core::LineKind::kCrease, false, {0, 1}, {0}};
    const double px_per_unit = 512.0 / (4.0 * std::tan(glm::radians(17.5)));
    const auto lines = core::split_by_visibility({line}, mesh, front_view(), HideBeyondX(1.0 - 0.05 / px_per_unit),
                                                 {.keep_hidden = true});
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_TRUE(lines[0].visible);
}

}  // namespace
}  // namespace inkline
