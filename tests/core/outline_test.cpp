// SPDX-License-Identifier: MIT
#include "core/strokes/outline.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/strokes/brush.h"
#include "core/strokes/pure_strokes.h"
#include "core/strokes/stroke_path.h"

namespace inkline {
namespace {

using glm::dvec2;

// Area covered by the centerline swept with its width: the trapezoid integral of width over
// length, plus the half-disc caps the outline puts on ends that keep their width.
double swept_area(const std::vector<dvec2>& c, const std::vector<double>& w, bool closed) {
    double area = 0.0;
    const size_t n = c.size();
    for (size_t i = 0; i + 1 < n + (closed ? 1 : 0); ++i) {
        const size_t j = (i + 1) % n;
        area += 0.5 * (w[i] + w[j]) * glm::length(c[j] - c[i]);
    }
    if (!closed) {
        for (const double end : {w.front(), w.back()}) area += std::numbers::pi * end * end / 8.0;
    }
    return area;
}

// How far (px) an outline point lies outside the centerline's disc of radius width / 2.
double excess(const dvec2& p, const std::vector<dvec2>& c, const std::vector<double>& w, bool closed) {
    double best = HUGE_VAL;
    const size_t n = c.size();
    for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
        const size_t j = (i + 1) % n;
        const dvec2 ab = c[j] - c[i];
        const double len2 = glm::dot(ab, ab);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(p - c[i], ab) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, glm::length(p - (c[i] + ab * t)) - 0.5 * (w[i] + (w[j] - w[i]) * t));
    }
    return best;
}

struct Shape {
    std::string name;
    std::vector<dvec2> points;
    bool closed = false;
};

std::vector<Shape> shapes() {
    std::vector<Shape> out;
    const double pi = std::numbers::pi;
    Shape zigzag{"sharp zig-zag", {}, false};
    for (int i = 0; i <= 10; ++i) zigzag.points.push_back({4.0 * i, 20.0 * (i % 2)});
    out.push_back(zigzag);
    Shape hairpin{"hairpin", {}, false};
    for (int i = 0; i <= 30; ++i) hairpin.points.push_back({2.0 * i, 0.0});
    for (int i = 29; i >= 0; --i) hairpin.points.push_back({2.0 * i, 3.0});
    out.push_back(hairpin);
    Shape round_hairpin{"round hairpin", {}, false};
    for (int i = 0; i <= 20; ++i) round_hairpin.points.push_back({60.0 - 3.0 * i, -4.0});
    for (int i = 1; i < 12; ++i)
        round_hairpin.points.push_back({-4.0 * std::sin(pi * i / 12), -4.0 * std::cos(pi * i / 12)});
    for (int i = 0; i <= 20; ++i) round_hairpin.points.push_back({3.0 * i, 4.0});
    out.push_back(round_hairpin);
    Shape wave{"wave", {}, false};
    for (int i = 0; i <= 100; ++i) wave.points.push_back({2.0 * i, 12.0 * std::sin(0.15 * i)});
    out.push_back(wave);
    Shape spiral{"spiral", {}, false};
    for (int i = 0; i <= 300; ++i) {
        const double a = 0.05 * i, r = 6.0 + 3.0 * a;
        spiral.points.push_back({r * std::cos(a), r * std::sin(a)});
    }
    out.push_back(spiral);
    Shape noisy{"noisy line", {}, false};
    for (int i = 0; i <= 150; ++i)
        noisy.points.push_back({1.3 * i, 0.6 * std::sin(12.9898 * i) * std::cos(78.233 * i)});
    out.push_back(noisy);
    for (const double r : {40.0, 4.0}) {
        Shape loop{"loop r=" + std::to_string(int(r)), {}, true};
        for (int i = 0; i <= 60; ++i)
            loop.points.push_back(r * dvec2(std::cos(2 * pi * (i % 60) / 60), std::sin(2 * pi * (i % 60) / 60)));
        out.push_back(loop);
    }
    return out;
}

core::Polyline polyline(const Shape& s) {
    core::Polyline l;
    l.closed = s.closed;
    l.points_px = s.points;
    for (const dvec2& p : s.points) l.points_world.emplace_back(p.x, p.y, 0.0);
    for (size_t i = 0; i + 1 < s.points.size(); ++i) l.edges.push_back(uint32_t(i));
    return l;
}

// Every shape drawn as build_strokes draws it (pure strokes, cleanup, brush), with the light
// varying along the stroke; each outline is checked against its centerline and width.
TEST(Outline, FaithfulToCenterlineAndWidth) {
    core::BrushStyle style;
    int checked = 0;
    for (const Shape& shape : shapes()) {
        const core::PureStrokes pure = core::build_pure_strokes({polyline(shape)}, {style.turn_angle_deg});
        for (const core::StrokeGeometry& g : pure.strokes) {
            const core::StrokePath path =
                core::build_stroke_path(g.points_px, g.closed, {.smooth_px = style.smooth_px});
            std::vector<double> facing;
            for (size_t k = 0; k < g.points_px.size(); ++k) facing.push_back(std::sin(0.1 * double(k)));
            const core::BrushSamples brush = core::brush_samples(path, facing, g.ends, style);
            if (path.length_px < style.min_length_px) continue;
            const std::vector<core::Ring> rings = core::build_outline(path.points_px, brush.width, path.closed, {});
            SCOPED_TRACE(shape.name + ", stroke of " + std::to_string(path.length_px) + " px");
            ASSERT_EQ(rings.size(), path.closed ? 2u : 1u);
            double worst = 0.0;
            for (const core::Ring& ring : rings) {
                EXPECT_TRUE(core::is_simple(ring));
                for (const dvec2& p : ring) {
                    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
                    worst = std::max(worst, excess(p, path.points_px, brush.width, path.closed));
                }
            }
            EXPECT_LE(worst, 0.25) << "an outline point sticks out";
            const double expected = swept_area(path.points_px, brush.width, path.closed);
            EXPECT_NEAR(core::outline_area(rings), expected, 0.03 * expected);
            ++checked;
        }
    }
    EXPECT_GE(checked, 15);
}

TEST(Outline, StraightStrokeWithRoundCaps) {
    const std::vector<dvec2> c = {{0, 0}, {50, 0}, {100, 0}};
    const std::vector<double> w = {4.0, 4.0, 4.0};
    const std::vector<core::Ring> rings = core::build_outline(c, w, false, {});
    ASSERT_EQ(rings.size(), 1u);
    EXPECT_NEAR(core::outline_area(rings), 400.0 + std::numbers::pi * 4.0, 0.5);
    double min_x = HUGE_VAL, max_x = -HUGE_VAL;
    for (const dvec2& p : rings[0]) min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
    EXPECT_NEAR(min_x, -2.0, 1e-9) << "a cap reaches half the width past the end";
    EXPECT_NEAR(max_x, 102.0, 1e-9);
}

TEST(Outline, SharpTurnsNeverSpike) {
    // Centerlines that turn back on themselves without being split: the joins stay round and
    // the inner side's fold is cut away, so nothing sticks out and nothing is NaN.
    for (const double turn_deg : {90.0, 150.0, 179.0, 180.0}) {
        std::vector<dvec2> c;
        for (int i = 0; i <= 40; ++i) c.push_back({0.5 * i, 0.0});
        const double a = glm::radians(180.0 - turn_deg);
        for (int i = 1; i <= 40; ++i) c.push_back({20.0 + 0.5 * i * std::cos(a), 0.5 * i * std::sin(a)});
        const std::vector<double> w(c.size(), 5.0);
        const std::vector<core::Ring> rings = core::build_outline(c, w, false, {});
        ASSERT_EQ(rings.size(), 1u);
        for (const dvec2& p : rings[0]) {
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
            EXPECT_LE(excess(p, c, w, false), 0.25) << turn_deg << " degrees at " << p.x << ", " << p.y;
        }
    }
}

TEST(Outline, LoopHasOuterAndInnerRing) {
    std::vector<dvec2> c;
    std::vector<double> w;
    for (int i = 0; i < 200; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 200;
        c.push_back(50.0 * dvec2(std::cos(a), std::sin(a)));
        w.push_back(2.0 + std::cos(a));
    }
    const std::vector<core::Ring> rings = core::build_outline(c, w, true, {});
    ASSERT_EQ(rings.size(), 2u);
    EXPECT_LT(core::signed_area(rings[0]) * core::signed_area(rings[1]), 0.0) << "opposite orientations";
    EXPECT_NEAR(core::outline_area(rings), swept_area(c, w, true), 0.01 * swept_area(c, w, true));
}

TEST(Outline, SimplifyKeepsShapeWithinTolerance) {
    core::Ring ring;
    for (int i = 0; i < 400; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 400;
        ring.push_back(30.0 * dvec2(std::cos(a), std::sin(a)));
    }
    const core::Ring simple = core::simplify_ring(ring, 0.05);
    EXPECT_LT(simple.size(), ring.size() / 2);
    EXPECT_NEAR(core::signed_area(simple), core::signed_area(ring), 0.01 * core::signed_area(ring));
}

// Douglas-Peucker as written plainly: every point of a chord's span measured, in order.
core::Ring plain_simplify(const core::Ring& ring, double tolerance) {
    const size_t n = ring.size();
    if (n < 4) return ring;
    size_t far = 0;
    double far_d = -1.0;
    for (size_t i = 1; i < n; ++i) {
        const double d = glm::length(ring[i] - ring[0]);
        if (d > far_d) far_d = d, far = i;
    }
    std::vector<uint8_t> keep(n, 0);
    keep[0] = keep[far] = 1;
    std::vector<std::pair<size_t, size_t>> stack = {{0, far}, {far, n}};
    while (!stack.empty()) {
        const auto [lo, hi] = stack.back();
        stack.pop_back();
        const dvec2 a = ring[lo], b = ring[hi % n], ab = b - a;
        const double len2 = glm::dot(ab, ab);
        size_t worst = 0;
        double worst_d = -1.0;
        for (size_t i = lo + 1; i < hi; ++i) {
            const double t = len2 > 0.0 ? std::clamp(glm::dot(ring[i] - a, ab) / len2, 0.0, 1.0) : 0.0;
            const dvec2 off = ring[i] - (a + ab * t);
            const double d = std::sqrt(glm::dot(off, off));
            if (d > worst_d) worst_d = d, worst = i;
        }
        if (worst_d > tolerance) {
            keep[worst] = 1;
            stack.emplace_back(lo, worst);
            stack.emplace_back(worst, hi);
        }
    }
    core::Ring out;
    for (size_t i = 0; i < n; ++i) {
        if (keep[i]) out.push_back(ring[i]);
    }
    return out;
}

// The search passes over runs of points by their boxes; it keeps exactly the points that
// measuring every point keeps, ties (points at the same distance, repeated points, straight
// runs) to the first, on rings of every size.
TEST(Outline, SimplifyKeepsWhatMeasuringEveryPointKeeps) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int round = 0; round < 300; ++round) {
        SCOPED_TRACE(round);
        const size_t n = 4 + size_t(round) * 7 % 900;
        core::Ring ring;
        for (size_t i = 0; i < n; ++i) {
            const double a = 2.0 * std::numbers::pi * double(i) / double(n);
            double r = 40.0 + 3.0 * std::sin(7.0 * a) + (round % 3 == 0 ? unit(random) : 0.0);
            dvec2 p = r * dvec2(std::cos(a), std::sin(a));
            if (round % 5 == 1) p = glm::round(p);                                                    // ties on a grid
            if (round % 7 == 2 && i % 9 < 4) p = dvec2(40.0, 0.0) + dvec2(0.0, 0.5 * double(i % 9));  // repeats, lines
            ring.push_back(p);
        }
        for (const double tolerance : {0.01, 0.05, 0.5, 3.0}) {
            EXPECT_EQ(core::simplify_ring(ring, tolerance), plain_simplify(ring, tolerance))
                << "tolerance " << tolerance;
        }
    }
}

// An open stroke that comes round to overlap its own start (a silhouette cut just past where it
// began): its ring touches itself whatever is done, so it is simplified like any other.
TEST(Outline, StrokeWhoseEndsOverlapIsSimplifiedToo) {
    std::vector<dvec2> c;
    for (int i = 0; i <= 2000; ++i) {
        const double a = 2.0 * std::numbers::pi * 1.01 * i / 2000;  // a little more than a turn
        c.push_back(100.0 * dvec2(std::cos(a), std::sin(a)));
    }
    const std::vector<double> w(c.size(), 4.0);
    const std::vector<core::Ring> rings = core::build_outline(c, w, false, {});
    ASSERT_EQ(rings.size(), 1u);
    EXPECT_LT(rings[0].size(), c.size() / 4) << "simplified";
    for (const dvec2& p : rings[0]) EXPECT_LE(excess(p, c, w, false), 0.05 + 1e-9);
    // The same stroke a little shorter, its ends apart, has the same ring outside the overlap:
    // about as many points, and a simple ring.
    const std::vector<dvec2> shorter(c.begin(), c.end() - 40);
    const std::vector<core::Ring> apart = core::build_outline(shorter, std::vector<double>(shorter.size(), 4.0), false, {});
    ASSERT_EQ(apart.size(), 1u);
    EXPECT_TRUE(core::is_simple(apart[0]));
    EXPECT_NEAR(double(rings[0].size()), double(apart[0].size()), 0.1 * double(apart[0].size()));
}

// is_simple answers as CGAL's sweep does: on rings with every degeneracy a small grid gives
// (points twice, edges folding back, straight runs, a point on another edge, touching corners),
// and on larger rings, simple or crossing, some past the sweep's budget.
TEST(Outline, IsSimpleAnswersAsCgalsSweep) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    const auto cgal = [](const core::Ring& ring) {
        std::vector<Kernel::Point_2> points;
        for (const dvec2& p : ring) points.emplace_back(p.x, p.y);
        return CGAL::is_simple_2(points.begin(), points.end(), Kernel());
    };
    std::mt19937 random(11);
    size_t simple = 0, rings = 0;
    const auto check = [&](const core::Ring& ring, int round) {
        const bool expected = cgal(ring);
        ASSERT_EQ(core::is_simple(ring), expected) << "round " << round << ", " << ring.size() << " points";
        simple += expected ? 1 : 0;
        ++rings;
    };
    for (int round = 0; round < 20000; ++round) {
        const size_t n = 3 + size_t(round) % 10;
        std::uniform_int_distribution<int> coordinate(0, round % 2 == 0 ? 3 : 6);
        core::Ring ring;
        for (size_t i = 0; i < n; ++i) ring.push_back(dvec2(coordinate(random), coordinate(random)));
        check(ring, round);
    }
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int round = 0; round < 400; ++round) {
        // A wobbly circle, simple; every fourth crossed by swapping two points; every third
        // pinched so that one point lands on another edge; every fifth a star of spikes into
        // its centre, whose edges all overlap there (past the sweep's budget when large).
        const size_t n = 4 + size_t(round) * 13 % 600;
        core::Ring ring;
        for (size_t i = 0; i < n; ++i) {
            const double a = 2.0 * std::numbers::pi * double(i) / double(n);
            double r = 50.0 + 5.0 * std::sin(9.0 * a) * unit(random);
            if (round % 5 == 4 && i % 2 == 1) r = 0.5;
            ring.push_back(r * dvec2(std::cos(a), std::sin(a)));
        }
        if (round % 4 == 1) std::swap(ring[n / 3], ring[2 * n / 3]);
        if (round % 3 == 2 && n > 8) ring[n / 2] = 0.5 * (ring[1] + ring[2]);
        check(ring, round);
    }
    // Points a few units in the last place from an edge (after J. R. Shewchuk's example), on it
    // or either side of it: the answer rests on exact orientation.
    const dvec2 a(12.0, 12.0), b(-12.0, -12.0);
    for (int i = 0; i < 32; ++i) {
        for (int j = 0; j < 32; ++j) {
            const dvec2 near(0.5 + std::ldexp(double(i), -53), 0.5 + std::ldexp(double(j), -53));
            for (const dvec2& side : {dvec2(3.0, -3.0), dvec2(-3.0, 3.0)}) {
                check({a, b, side, near}, i * 32 + j);
                check({b, near, a, side}, i * 32 + j);
            }
        }
    }
    // Both answers were asked for often.
    EXPECT_GT(simple, rings / 10);
    EXPECT_LT(simple, rings - rings / 10);
}

}  // namespace
}  // namespace inkline
