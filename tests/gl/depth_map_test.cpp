// SPDX-License-Identifier: MIT
// The CPU side of the depth-map test on hand-made maps: planes, discontinuities, borders.
#include "gl/internal/depth_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace inkline {
namespace {

using gl::internal::DepthMap;
using gl::internal::DepthSample;
using gl::internal::DepthTexel;
using gl::internal::DepthVerdict;

bool hidden_in_depth_map(const DepthMap& map, const DepthSample& sample) {
    return gl::internal::classify_in_depth_map(map, sample) == DepthVerdict::kHidden;
}

// A map whose texel (i, j) sees the plane q(x, y) chosen by `surface` at its centre, or
// nothing where `surface` gives no plane.
struct Plane {
    double q0, dq_dx, dq_dy;  // q = q0 + dq_dx * x + dq_dy * y, window texels
    double at(double x, double y) const { return q0 + dq_dx * x + dq_dy * y; }
};

DepthMap make_map(int w, int h, const std::function<const Plane*(int, int)>& surface) {
    DepthMap map{w, h, std::vector<DepthTexel>(size_t(w * h))};
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const Plane* p = surface(i, j);
            if (!p) continue;
            map.texels[size_t(j * w + i)] = {float(p->at(i + 0.5, j + 0.5)), float(p->dq_dx), float(p->dq_dy),
                                             float(j * w + i + 1)};
        }
    }
    return map;
}

TEST(DepthMap, EmptyMapHidesNothing) {
    const DepthMap map = make_map(8, 8, [](int, int) { return nullptr; });
    EXPECT_FALSE(hidden_in_depth_map(map, {{3.3, 4.7}, 0.25}));
}

TEST(DepthMap, PointOnASlopedPlaneIsVisibleBetweenTexelCentres) {
    // A steep plane (grazing view): its own points must pass wherever they fall.
    const Plane plane{0.25, 0.004, -0.001};
    const DepthMap map = make_map(16, 16, [&](int, int) { return &plane; });
    for (double x : {2.0, 5.37, 7.5, 11.91}) {
        for (double y : {3.0, 6.5, 9.13}) {
            const double q = plane.at(x, y);
            EXPECT_FALSE(hidden_in_depth_map(map, {{x, y}, q})) << x << ", " << y;
            EXPECT_TRUE(hidden_in_depth_map(map, {{x, y}, q * 0.99})) << "just behind at " << x << ", " << y;
            EXPECT_FALSE(hidden_in_depth_map(map, {{x, y}, q * 1.01})) << "in front at " << x << ", " << y;
        }
    }
}

TEST(DepthMap, PointOnADepthEdgeIsAnEdge) {
    // Left of x = 8: a near surface; right: a far one. A silhouette point on the near surface's
    // edge is level with one side and behind nothing: visible.
    const Plane near{0.5, 0.0, 0.0}, far{0.2, 0.0, 0.0};
    const DepthMap map = make_map(16, 16, [&](int i, int) { return i < 8 ? &near : &far; });
    EXPECT_EQ(classify_in_depth_map(map, {{8.0, 5.3}, 0.5}), DepthVerdict::kVisible);
    // A far-surface point near the near surface's edge: the texels disagree.
    EXPECT_EQ(classify_in_depth_map(map, {{8.0, 5.3}, 0.2}), DepthVerdict::kEdge);
    EXPECT_EQ(classify_in_depth_map(map, {{7.9, 5.3}, 0.3}), DepthVerdict::kEdge);
    // Well inside the near surface it is hidden; right of the edge, visible.
    EXPECT_EQ(classify_in_depth_map(map, {{6.4, 5.3}, 0.2}), DepthVerdict::kHidden);
    EXPECT_EQ(classify_in_depth_map(map, {{8.6, 5.3}, 0.2}), DepthVerdict::kVisible);
}

TEST(DepthMap, EdgeBandIsOneTexelWide) {
    const Plane near{0.5, 0.0, 0.0}, far{0.2, 0.0, 0.0};
    const DepthMap map = make_map(16, 16, [&](int i, int) { return i < 8 ? &near : &far; });
    for (double x = 0.0; x <= 16.0; x += 0.05) {
        const DepthVerdict verdict = classify_in_depth_map(map, {{x, 5.5}, 0.2});
        const DepthVerdict expected = x < 7.5 ? DepthVerdict::kHidden : x < 8.5 ? DepthVerdict::kEdge : DepthVerdict::kVisible;
        if (std::abs(x - 7.5) > 1e-9 && std::abs(x - 8.5) > 1e-9) {
            EXPECT_EQ(verdict, expected) << x;
        }
    }
}

TEST(DepthMap, FacesAroundListsEachFaceOnce) {
    const Plane near{0.5, 0.0, 0.0};
    DepthMap map = make_map(8, 8, [&](int, int) { return &near; });
    for (size_t k = 0; k < map.texels.size(); ++k) map.texels[k].face = float(1 + k % 2);  // faces 0 and 1
    std::vector<uint32_t> faces{1};
    gl::internal::faces_around(map, {4.2, 4.7}, 1, faces);
    EXPECT_EQ(faces, (std::vector<uint32_t>{1, 0}));
    faces.clear();
    gl::internal::faces_around(map, {0.0, 0.0}, 1, faces);  // clipped to the map
    EXPECT_EQ(faces.size(), 2u);
}

TEST(DepthMap, BordersUseTheNearestTexels) {
    const Plane plane{0.5, 0.0, 0.0};
    const DepthMap map = make_map(4, 4, [&](int, int) { return &plane; });
    for (const glm::dvec2 p : {glm::dvec2(0.0, 0.0), glm::dvec2(4.0, 4.0), glm::dvec2(0.0, 4.0)}) {
        EXPECT_TRUE(hidden_in_depth_map(map, {p, 0.3}));
        EXPECT_FALSE(hidden_in_depth_map(map, {p, 0.5}));
    }
}

}  // namespace
}  // namespace inkline
