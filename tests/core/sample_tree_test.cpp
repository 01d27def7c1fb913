// SPDX-License-Identifier: MIT
#include "core/strokes/internal/sample_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <numbers>
#include <tuple>
#include <vector>

namespace inkline {
namespace {

using core::internal::AngleCone;
using core::internal::SampleTree;
using core::internal::TracedSample;
using glm::dvec2;

// Numbers in [0, 1), the same every run.
class Random {
  public:
    explicit Random(uint32_t seed) : seed_(seed) {}
    double operator()() {
        seed_ = seed_ * 1664525u + 1013904223u;
        return double(seed_ >> 8) / double(1u << 24);
    }

  private:
    uint32_t seed_;
};

// The nearest accepted sample within radius by a search over every sample, ties to the lower
// (trace, sample).
template <typename Filter>
SampleTree::Hit every_sample(const std::vector<TracedSample>& samples, dvec2 p, double radius, Filter use) {
    SampleTree::Hit best;
    for (const TracedSample& s : samples) {
        if (!use(s.trace, s.sample)) continue;
        const double d = glm::length(s.p_px - p);
        if (!(d <= radius)) continue;
        if (d < best.distance ||
            (d == best.distance && std::tie(s.trace, s.sample) < std::tie(best.trace, best.sample)))
            best = {s.trace, s.sample, d};
    }
    return best;
}

::testing::AssertionResult same_hit(const SampleTree::Hit& got, const SampleTree::Hit& want) {
    if (got.trace == want.trace && got.sample == want.sample &&
        (want.trace == size_t(-1) || got.distance == want.distance))
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "found (" << got.trace << ", " << got.sample << ") at " << got.distance
                                         << ", every sample gives (" << want.trace << ", " << want.sample << ") at "
                                         << want.distance;
}

// Strokes 40 px long through one point (every one has a sample exactly there, the rest 2 px
// apart), as where thousands of faces share an edge; and sparse short strokes around them.
std::vector<TracedSample> star_and_scatter(Random& random, size_t star, size_t scatter) {
    std::vector<TracedSample> samples;
    const dvec2 center(100.0, 100.0);
    for (size_t t = 0; t < star; ++t) {
        const double a = std::numbers::pi * double(t) / double(star);
        const dvec2 d(std::cos(a), std::sin(a));
        for (size_t s = 0; s <= 20; ++s) samples.push_back({center + d * (2.0 * double(s) - 20.0), t, s, a});
    }
    for (size_t t = star; t < star + scatter; ++t) {
        const dvec2 a(400.0 * random() - 100.0, 400.0 * random() - 100.0);
        const double angle = std::numbers::pi * random();
        for (size_t s = 0; s < 8; ++s) samples.push_back({a + 2.0 * double(s) * dvec2(std::cos(angle), std::sin(angle)), t, s, angle});
    }
    return samples;
}

// Points near the crowded one, exactly on it and on samples, and anywhere.
std::vector<dvec2> queries(Random& random, const std::vector<TracedSample>& samples) {
    std::vector<dvec2> out{{100.0, 100.0}, samples[5].p_px, samples.back().p_px};
    for (int i = 0; i < 1500; ++i) out.push_back({100.0 + 30.0 * random() - 15.0, 100.0 + 30.0 * random() - 15.0});
    for (int i = 0; i < 1500; ++i) out.push_back({450.0 * random() - 125.0, 450.0 * random() - 125.0});
    return out;
}

TEST(SampleTree, NearestIsTheSearchOverEverySampleWhereThousandsOfStrokesCross) {
    Random random(11);
    const std::vector<TracedSample> samples = star_and_scatter(random, 3000, 400);
    const SampleTree tree(samples);
    const std::vector<dvec2> points = queries(random, samples);
    auto all = [](size_t, size_t) { return true; };
    auto some = [](size_t trace, size_t sample) { return trace % 3 != 0 && sample != 10; };
    for (size_t i = 0; i < points.size(); ++i) {
        ASSERT_TRUE(same_hit(tree.nearest(points[i], 12.0), every_sample(samples, points[i], 12.0, all))) << i;
        ASSERT_TRUE(same_hit(tree.nearest(points[i], 12.0, some), every_sample(samples, points[i], 12.0, some))) << i;
        ASSERT_TRUE(same_hit(tree.nearest(points[i], 3.0, some), every_sample(samples, points[i], 3.0, some))) << i;
    }
    // At the crossing itself: 3000 samples at distance 0, the lowest accepted one wins.
    const SampleTree::Hit at = tree.nearest({100.0, 100.0}, 12.0, [](size_t trace, size_t) { return trace >= 2; });
    EXPECT_EQ(at.trace, 2u);
    EXPECT_EQ(at.sample, 10u);
    EXPECT_EQ(at.distance, 0.0);
}

TEST(SampleTree, TiesGoToTheLowerTraceThenSample) {
    // Four samples 1 px from the origin, and three at one point 1 px away, given in reverse.
    const std::vector<TracedSample> samples = {
        {{1.0, 0.0}, 9, 0}, {{0.0, 1.0}, 4, 7}, {{-1.0, 0.0}, 4, 3}, {{0.0, -1.0}, 6, 1},
        {{0.0, 3.0}, 8, 2}, {{0.0, 3.0}, 8, 1}, {{0.0, 3.0}, 2, 5},
    };
    const SampleTree tree(samples);
    const SampleTree::Hit hit = tree.nearest({0.0, 0.0}, 12.0);
    EXPECT_EQ(hit.trace, 4u);
    EXPECT_EQ(hit.sample, 3u);
    EXPECT_EQ(hit.distance, 1.0);
    const SampleTree::Hit up = tree.nearest({0.0, 4.0}, 12.0);
    EXPECT_EQ(up.trace, 2u);
    EXPECT_EQ(up.sample, 5u);
    const SampleTree::Hit refused = tree.nearest({0.0, 4.0}, 12.0, [](size_t t, size_t) { return t != 2; });
    EXPECT_EQ(refused.trace, 8u);
    EXPECT_EQ(refused.sample, 1u);
    EXPECT_EQ(tree.nearest({0.0, 0.0}, 0.999).trace, size_t(-1)) << "nothing within the radius";
    EXPECT_EQ(tree.nearest({0.0, 0.0}, 1.0).trace, 4u) << "the radius itself counts";
}

TEST(SampleTree, AConePassesOverOnlySamplesRunningAcrossIt) {
    // With a cone, the search may skip samples of strokes running outside it; a filter that
    // refuses exactly those (as side_memory's does) finds what a search over every sample finds.
    Random random(5);
    std::vector<TracedSample> samples = star_and_scatter(random, 1000, 200);
    for (size_t i = 0; i < samples.size(); i += 97) samples[i].angle = NAN;  // no direction: never skipped
    const double half = std::acos(0.5);
    const std::vector<dvec2> points = queries(random, samples);
    // Each cone's edges exactly on some strokes' angles, and a hair either side.
    std::vector<double> axes;
    for (int i = 0; i < 16; ++i) axes.push_back(std::numbers::pi * random());
    axes.push_back(std::numbers::pi * 250.0 / 1000.0 + half);
    axes.push_back(std::numbers::pi * 750.0 / 1000.0 - half + 1e-13);
    const SampleTree tree(samples);
    for (size_t k = 0; k < axes.size(); ++k) {
        const dvec2 along(std::cos(axes[k]), std::sin(axes[k]));
        const AngleCone cone{core::internal::line_angle(along), half};
        auto runs_along = [&](size_t trace, size_t sample) {
            const TracedSample& s = samples[trace < 1000 ? trace * 21 + sample : 1000 * 21 + (trace - 1000) * 8 + sample];
            if (std::isnan(s.angle)) return true;
            const dvec2 tangent(std::cos(s.angle), std::sin(s.angle));
            return std::abs(glm::dot(along, tangent)) >= 0.5 * glm::length(along) * glm::length(tangent);
        };
        for (size_t i = k; i < points.size(); i += 11) {
            ASSERT_TRUE(same_hit(tree.nearest(points[i], 12.0, runs_along, cone),
                                 every_sample(samples, points[i], 12.0, runs_along)))
                << "point " << i << ", cone " << k;
        }
    }
}

TEST(SampleTree, TiesAcrossBoxesGoToTheLowerTrace) {
    // Samples on the integer lattice, numbered at random: a point between lattice points lies
    // as near to two or four of them, often in different boxes of the tree.
    Random random(3);
    std::vector<TracedSample> samples;
    for (int y = 0; y < 120; ++y) {
        for (int x = 0; x < 120; ++x) samples.push_back({{double(x), double(y)}, size_t(random() * 1e6), size_t(x)});
    }
    const SampleTree tree(samples);
    auto all = [](size_t, size_t) { return true; };
    size_t i = 0;
    for (int y = 0; y < 120; y += 3) {
        for (int x = 0; x < 120; x += 3, ++i) {
            for (const dvec2 p : {dvec2(x + 0.5, y + 0.5), dvec2(x + 0.5, y), dvec2(x, y + 0.5)}) {
                ASSERT_TRUE(same_hit(tree.nearest(p, 12.0), every_sample(samples, p, 12.0, all))) << i;
                ASSERT_TRUE(same_hit(tree.nearest(p, 0.5), every_sample(samples, p, 0.5, all))) << i;
            }
        }
    }
}

TEST(SampleTree, SamplesAndPointsOffTheImageFindNothing) {
    const std::vector<TracedSample> samples = {{{NAN, 0.0}, 0, 0}, {{HUGE_VAL, 1.0}, 1, 0}, {{2.0, 2.0}, 2, 0}};
    const SampleTree tree(samples);
    EXPECT_EQ(tree.nearest({2.0, 2.5}, 12.0).trace, 2u);
    EXPECT_EQ(tree.nearest({NAN, 2.0}, 12.0).trace, size_t(-1));
    EXPECT_EQ(tree.nearest({HUGE_VAL, 1.0}, 12.0).trace, size_t(-1));
    EXPECT_EQ(tree.nearest({2.0, 2.0}, NAN).trace, size_t(-1));
    EXPECT_TRUE(SampleTree({{{NAN, NAN}, 0, 0}}).empty());
    // Samples spread wider than a double spans.
    const SampleTree wide({{{-1e308, 0.0}, 0, 0}, {{1e308, 0.0}, 1, 0}, {{0.0, 0.0}, 2, 0}, {{0.0, 1e308}, 3, 0}});
    EXPECT_EQ(wide.nearest({1.0, 0.0}, 12.0).trace, 2u);
    EXPECT_EQ(wide.nearest({1e308, 5.0}, 12.0).trace, 1u);
    EXPECT_EQ(SampleTree().nearest({0.0, 0.0}, 12.0).trace, size_t(-1));
}

TEST(SampleTree, LineAngleIsTheDirectionEitherWay) {
    EXPECT_EQ(core::internal::line_angle({1.0, 0.0}), 0.0);
    EXPECT_EQ(core::internal::line_angle({-1.0, 0.0}), 0.0);
    EXPECT_EQ(core::internal::line_angle({-1.0, -0.0}), 0.0);
    EXPECT_NEAR(core::internal::line_angle({0.0, -2.0}), std::numbers::pi / 2, 1e-15);
    EXPECT_NEAR(core::internal::line_angle({-1.0, 1.0}), 0.75 * std::numbers::pi, 1e-15);
    EXPECT_NEAR(core::internal::line_angle({1.0, -1.0}), 0.75 * std::numbers::pi, 1e-15);
    EXPECT_TRUE(std::isnan(core::internal::line_angle({0.0, 0.0})));
    EXPECT_TRUE(std::isnan(core::internal::line_angle({NAN, 1.0})));
}

}  // namespace
}  // namespace inkline
