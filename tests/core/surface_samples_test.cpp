// SPDX-License-Identifier: MIT
// The nested blue-noise set stippling draws from (core/tone/surface_samples.h): each level's
// density is the one it is calibrated to, the points keep their level's spacing, and a tile holds
// the same points whatever was built before it and in whatever order.
#include "core/tone/surface_samples.h"

#include "tests/support/shapes.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

namespace inkline {
namespace {

// A square of side `side` in the plane z = 0, centred on the origin: two triangles.
core::Mesh square(double side) {
    core::Mesh mesh;
    const auto h = float(side / 2);
    mesh.positions = {{-h, -h, 0.0f}, {h, -h, 0.0f}, {h, h, 0.0f}, {-h, h, 0.0f}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

glm::dvec3 point_of(const core::Mesh& mesh, uint32_t face, const core::SurfaceSamples::Sample& s) {
    const glm::uvec3 t = mesh.triangles[face];
    return (1.0 - s.b1 - s.b2) * glm::dvec3(mesh.positions[t.x]) + double(s.b1) * glm::dvec3(mesh.positions[t.y]) +
           double(s.b2) * glm::dvec3(mesh.positions[t.z]);
}

// Builds the levels 0..level over the box [lo, hi].
void build_box(core::SurfaceSamples& samples, int level, const glm::dvec3& lo, const glm::dvec3& hi) {
    for (int k = 0; k <= level; ++k)
        samples.tiles_over(k, lo, hi, [&](const glm::ivec3& at) { samples.build_tile(k, at); });
    samples.finish();
}

// Samples of rank up to `rank` inside the square |x|, |y| <= half.
std::vector<std::pair<uint32_t, core::SurfaceSamples::Sample>> samples_in(const core::Mesh& mesh,
                                                                          const core::SurfaceSamples& samples,
                                                                          double half, double rank) {
    std::vector<std::pair<uint32_t, core::SurfaceSamples::Sample>> in;
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        for (const core::SurfaceSamples::Sample& s : samples.on_face(f)) {
            const glm::dvec3 p = point_of(mesh, f, s);
            if (s.rank <= rank && std::abs(p.x) <= half && std::abs(p.y) <= half) in.emplace_back(f, s);
        }
    }
    return in;
}

TEST(SurfaceSamples, EachLevelHasTheDensityItIsCalibratedTo) {
    // Counted in the middle of a wide plane, over a square of about 20,000 points at each level.
    const core::Mesh mesh = square(1000.0);
    for (uint64_t seed : {1u, 2u}) {
        core::SurfaceSamples samples(mesh, seed);
        for (int level = 0; level < 14; ++level) {
            const double want = samples.density(level);
            // Away from the plane's sides by a spacing, where points have fewer neighbours.
            const double half = std::min(500.0 - samples.radius(level), std::sqrt(20000.0 / want) / 2);
            build_box(samples, level, glm::dvec3(-half, -half, 0.0), glm::dvec3(half, half, 0.0));
            const double count = double(samples_in(mesh, samples, half, want).size());
            const double got = count / (4.0 * half * half);
            std::printf("seed %d level %2d: %.4f points per r^2 (calibrated %.4f)\n", int(seed), level,
                        got * samples.radius(level) * samples.radius(level),
                        want * samples.radius(level) * samples.radius(level));
            EXPECT_NEAR(got / want, 1.0, std::max(0.03, 3.0 / std::sqrt(count))) << "level " << level;
            samples.clear();
        }
    }
}

TEST(SurfaceSamples, PointsOfEachLevelKeepItsSpacing) {
    const core::Mesh mesh = test::icosphere(4);
    core::SurfaceSamples samples(mesh, 7);
    const int deepest = 8;
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        for (int k = 0; k <= deepest; ++k) samples.build_face(f, k);
    }
    samples.finish();
    for (int level : {2, 5, deepest}) {
        std::vector<glm::dvec3> points;
        for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
            for (const core::SurfaceSamples::Sample& s : samples.on_face(f)) {
                if (s.rank <= samples.density(level)) points.push_back(point_of(mesh, f, s));
            }
        }
        double least = INFINITY;
        for (size_t i = 0; i < points.size(); ++i) {
            for (size_t j = i + 1; j < points.size(); ++j) least = std::min(least, glm::distance(points[i], points[j]));
        }
        std::printf("level %d: %zu points, least distance %.5f, spacing %.5f\n", level, points.size(), least,
                    samples.radius(level));
        EXPECT_GE(least, samples.radius(level) * (1.0 - 1e-5)) << "level " << level;
        // Every face's samples are by rank.
        for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
            const auto on = samples.on_face(f);
            EXPECT_TRUE(
                std::is_sorted(on.begin(), on.end(), [](const auto& a, const auto& b) { return a.rank < b.rank; }));
        }
    }
}

TEST(SurfaceSamples, ATileHoldsTheSamePointsWhateverWasBuiltBefore) {
    const core::Mesh mesh = square(100.0);
    const int level = 14;
    const glm::dvec3 lo(-3.0, -3.0, 0.0), hi(3.0, 3.0, 0.0);
    // Built alone; after a large region around it; and after regions on both sides, in reverse.
    core::SurfaceSamples alone(mesh, 3), around(mesh, 3), sides(mesh, 3);
    build_box(alone, level, lo, hi);
    build_box(around, level, glm::dvec3(-12.0, -12.0, 0.0), glm::dvec3(12.0, 12.0, 0.0));
    build_box(sides, level, glm::dvec3(4.0, -5.0, 0.0), glm::dvec3(9.0, 5.0, 0.0));
    build_box(sides, level, glm::dvec3(-9.0, -5.0, 0.0), glm::dvec3(-4.0, 5.0, 0.0));
    for (int k = level; k >= 0; --k) {
        sides.tiles_over(k, lo, hi, [&](const glm::ivec3& at) { sides.build_tile(k, at); });
    }
    sides.finish();
    const auto key = [](const std::pair<uint32_t, core::SurfaceSamples::Sample>& s) {
        return std::make_tuple(s.second.id, s.first, s.second.b1, s.second.b2, s.second.rank);
    };
    const auto keys = [&](const core::SurfaceSamples& samples) {
        std::vector<decltype(key({}))> out;
        for (const auto& s : samples_in(mesh, samples, 3.0, INFINITY)) out.push_back(key(s));
        std::sort(out.begin(), out.end());
        return out;
    };
    const auto want = keys(alone);
    std::printf("%zu samples in the square; held: alone %zu, around %zu, sides %zu\n", want.size(), alone.size(),
                around.size(), sides.size());
    ASSERT_GT(want.size(), 800u);
    EXPECT_EQ(keys(around), want);
    EXPECT_EQ(keys(sides), want);
    // Ids are distinct.
    for (size_t i = 1; i < want.size(); ++i) EXPECT_NE(std::get<0>(want[i]), std::get<0>(want[i - 1]));
}

// Building levels on the whole surface at once gives the points that building them tile by tile
// gives, on a mesh of small faces (whole-face candidates) and one of large ones (clipped to tiles).
TEST(SurfaceSamples, BuildingEverywhereAtOnceGivesTheSamePointsAsTileByTile) {
    for (const core::Mesh& mesh : {test::icosphere(4), square(40.0)}) {
        const int last = mesh.triangles.size() > 2 ? 8 : 11;
        core::SurfaceSamples at_once(mesh, 5), tile_by_tile(mesh, 5);
        at_once.build_everywhere(last);
        for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
            for (int k = 0; k <= last; ++k) tile_by_tile.build_face(f, k);
        }
        tile_by_tile.finish();
        std::printf("%zu faces: %zu samples at once, %zu tile by tile\n", mesh.triangles.size(), at_once.size(),
                    tile_by_tile.size());
        ASSERT_GT(at_once.size(), 2000u);
        ASSERT_EQ(at_once.size(), tile_by_tile.size());
        for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
            const auto a = at_once.on_face(f), b = tile_by_tile.on_face(f);
            ASSERT_EQ(a.size(), b.size()) << "face " << f;
            for (size_t i = 0; i < a.size(); ++i) {
                EXPECT_EQ(a[i].id, b[i].id);
                EXPECT_EQ(a[i].rank, b[i].rank);
                EXPECT_EQ(a[i].b1, b[i].b1);
                EXPECT_EQ(a[i].b2, b[i].b2);
            }
        }
    }
}

}  // namespace
}  // namespace inkline
