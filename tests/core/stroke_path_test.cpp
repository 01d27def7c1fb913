// SPDX-License-Identifier: MIT
#include "core/strokes/stroke_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

namespace inkline {
namespace {

using glm::dvec2;

// Distance from p to an exact polyline.
double distance_to(const std::vector<dvec2>& line, const dvec2& p) {
    double best = HUGE_VAL;
    for (size_t i = 0; i + 1 < line.size(); ++i)
        best = std::min(best, core::distance_to_segment(p, line[i], line[i + 1]));
    return best;
}

// A deterministic wobble in [-1, 1].
double wobble(int i) { return std::sin(12.9898 * i) * std::cos(78.233 * i); }

TEST(StrokePath, BacktrackingSpikeIsRemoved) {
    // Runs right, steps 1 px back, runs right again: the step back is removed.
    const std::vector<dvec2> line = {{0, 0}, {10, 0}, {9, 0.1}, {20, 0}};
    EXPECT_EQ(core::remove_backtracking(line, false), (std::vector<size_t>{0, 2, 3}));
    const core::StrokePath path = core::build_stroke_path(line, false, {});
    for (size_t i = 1; i < path.points_px.size(); ++i) EXPECT_GT(path.points_px[i].x, path.points_px[i - 1].x) << i;
    EXPECT_LT(core::removed_extent_px(line, path), 0.5) << "the spike's tip lies on the line drawn anyway";
    // A spike off to the side is removed too, and what it took away is measured.
    const std::vector<dvec2> side = {{0, 0}, {10, 0}, {9, 1}, {20, 1}};
    EXPECT_EQ(core::remove_backtracking(side, false), (std::vector<size_t>{0, 2, 3}));
    const double removed = core::removed_extent_px(side, core::build_stroke_path(side, false, {}));
    EXPECT_GT(removed, 0.5);
    EXPECT_LT(removed, 1.5);
}

TEST(StrokePath, LongArmsAreNoBacktracking) {
    // A real hairpin (arms longer than kBacktrackPx) stays: pure strokes split it instead.
    const std::vector<dvec2> line = {{0, 0}, {10, 0}, {0, 3}};
    EXPECT_EQ(core::remove_backtracking(line, false).size(), 3u);
}

TEST(StrokePath, RepeatedPointsAreDropped) {
    const std::vector<dvec2> line = {{0, 0}, {0, 0}, {5, 0}, {5, 0}, {5, 0}, {9, 1}};
    EXPECT_EQ(core::remove_backtracking(line, false), (std::vector<size_t>{0, 4, 5}));
}

TEST(StrokePath, SmoothingStaysWithinTheDeviationBound) {
    // A saw-tooth (3 px amplitude, 8 px period) and a noisy line: smoothing would cut their
    // corners by more than the bound; the bound holds.
    std::vector<dvec2> saw, noisy;
    for (int i = 0; i <= 40; ++i) saw.push_back({4.0 * i, (i % 2) * 3.0});
    for (int i = 0; i <= 200; ++i) noisy.push_back({0.7 * i, 0.4 * wobble(i)});
    for (const double bound : {0.5, 0.2}) {
        for (const auto* line : {&saw, &noisy}) {
            core::StrokePathOptions options;
            options.max_deviation_px = bound;
            options.smooth_px = 6.0;
            const core::StrokePath path = core::build_stroke_path(*line, false, options);
            double worst = 0.0;
            for (const dvec2& p : path.points_px) worst = std::max(worst, distance_to(*line, p));
            EXPECT_LE(worst, bound + 1e-9);
            EXPECT_LE(path.deviation_px, bound + 1e-9);
            EXPECT_NEAR(path.deviation_px, worst, 1e-6) << "the reported deviation is the measured one";
        }
    }
}

TEST(StrokePath, OpenEndsStayInPlace) {
    std::vector<dvec2> line;
    for (int i = 0; i <= 30; ++i) line.push_back({3.0 * i, 10.0 * std::sin(0.3 * i)});
    const core::StrokePath path = core::build_stroke_path(line, false, {});
    EXPECT_LT(glm::length(path.points_px.front() - line.front()), 1e-9);
    EXPECT_LT(glm::length(path.points_px.back() - line.back()), 1e-9);
    EXPECT_DOUBLE_EQ(path.sample_at(0.0), 0.0);
    EXPECT_DOUBLE_EQ(path.sample_at(double(line.size() - 1)), double(path.points_px.size() - 1));
    for (size_t i = 1; i < path.g.size(); ++i) EXPECT_GT(path.g[i], path.g[i - 1]);
}

TEST(StrokePath, LoopIsSmoothedPeriodically) {
    // A 64-gon of radius 50: the drawn loop stays closed, near the polygon, with its length.
    std::vector<dvec2> loop;
    for (int i = 0; i <= 64; ++i) {
        const double a = 2.0 * std::numbers::pi * (i % 64) / 64.0;
        loop.push_back({50.0 * std::cos(a), 50.0 * std::sin(a)});
    }
    const core::StrokePath path = core::build_stroke_path(loop, true, {});
    EXPECT_TRUE(path.closed);
    EXPECT_NEAR(path.length_px, 2.0 * std::numbers::pi * 50.0, 1.0);
    EXPECT_LE(path.deviation_px, 0.5 + 1e-9);
    EXPECT_NEAR(path.arc_at(path.sample_at(64.0)), path.length_px, 1e-9) << "the seam maps to the end";
    for (const dvec2& p : path.points_px) EXPECT_NEAR(glm::length(p), 50.0, 0.6);
}

TEST(StrokePath, SmoothSamplesKeepsConstantsAndWraps) {
    const std::vector<double> flat(50, 0.25);
    for (const double v : core::smooth_samples(flat, 0.5, 3.0, false)) EXPECT_NEAR(v, 0.25, 1e-12);
    // A loop's smoothing wraps: a spike at sample 0 spreads to both ends equally.
    std::vector<double> spike(40, 0.0);
    spike[0] = 1.0;
    const std::vector<double> s = core::smooth_samples(spike, 1.0, 2.0, true);
    EXPECT_NEAR(s[1], s[39], 1e-12);
    EXPECT_GT(s[39], 0.0);
}

}  // namespace
}  // namespace inkline
