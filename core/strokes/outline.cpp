// SPDX-License-Identifier: MIT
#include "core/strokes/outline.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <optional>
#include <tuple>

#include "core/strokes/stroke_path.h"

namespace inkline::core {
namespace {

// Widths below this (px) are a point: no cap is drawn around it.
constexpr double kCapMinWidthPx = 1e-3;
// Consecutive outline points closer than this (px) are merged.
constexpr double kSamePointPx = 1e-9;
// Simplification error stays below this fraction of a stroke's mean width (and simplify_px).
constexpr double kSimplifyWidthFraction = 0.02;
// edges_meet files at most this many cells, and tests at most this many edge pairs, per edge
// before leaving the ring to is_simple.
constexpr size_t kEdgePairsPerEdge = 16;
// simplify_ring bounds the distances of runs of this many points together.
constexpr size_t kSimplifyBlock = 8;
// A run is passed over when it stays nearer the chord than a point found by more than this
// (px): far more than rounding can move a distance.
constexpr double kSimplifyBoundMarginPx = 1e-9;
// Folds are looked for this far (px of centerline, beyond the widest width) ahead of a segment.
constexpr double kFoldReachPx = 2.0;

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }
glm::dvec2 perp(const glm::dvec2& v) { return {-v.y, v.x}; }
glm::dvec2 rotate(const glm::dvec2& v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// Where segments ab and cd cross, if they do.
std::optional<glm::dvec2> intersect(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                                    const glm::dvec2& d) {
    const glm::dvec2 r = b - a, s = d - c;
    const double denom = cross(r, s);
    if (std::abs(denom) < 1e-18) return std::nullopt;
    const double t = cross(c - a, s) / denom;
    const double u = cross(c - a, r) / denom;
    if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0) return std::nullopt;
    return a + r * t;
}

struct Side {
    std::vector<glm::dvec2> points;
    std::vector<double> arc;  // centerline arc of each point's source, for the fold search
};

// One side's offset points, with extra points wherever the normal turns by more than a step.
Side offset_side(std::span<const glm::dvec2> c, std::span<const double> w, const std::vector<glm::dvec2>& t,
                 bool closed, double sign, double step_rad) {
    Side side;
    const size_t n = c.size();
    side.points.reserve(n + n / 4);
    side.arc.reserve(n + n / 4);
    // Unit normals turning by less than this sine (and forwards) turn by less than a step: no
    // extra point, and no need for the angle. The margin keeps rounding on the safe side.
    const double sin_step = step_rad < 0.5 * std::numbers::pi ? std::sin(step_rad) * (1.0 - 1e-9) : 0.0;
    double arc = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 normal = perp(t[i]) * sign;
        side.points.push_back(c[i] + normal * (0.5 * w[i]));
        side.arc.push_back(arc);
        const size_t j = i + 1 < n ? i + 1 : (closed ? 0 : n);
        if (j == n) break;
        const glm::dvec2 next = perp(t[j]) * sign;
        const double seg = glm::length(c[j] - c[i]);
        const double sine = cross(normal, next), cosine = glm::dot(normal, next);
        if (cosine > 0.0 && std::abs(sine) < sin_step) {
            arc += seg;
            continue;
        }
        const double turn = std::atan2(sine, cosine);
        const int steps = int(std::ceil(std::abs(turn) / step_rad));
        for (int k = 1; k < steps; ++k) {
            const double f = double(k) / steps;
            const glm::dvec2 center = c[i] + (c[j] - c[i]) * f;
            side.points.push_back(center + rotate(normal, turn * f) * (0.5 * (w[i] + (w[j] - w[i]) * f)));
            side.arc.push_back(arc + seg * f);
        }
        arc += seg;
    }
    return side;
}

// Segments shorter than this (px) may touch their neighbours' neighbours in floating point
// without any turn between them: a window that has one is always searched.
constexpr double kTinySegmentPx = 1e-6;

// Turning (radians) below which a window of a side cannot cross itself. A polyline that crosses
// itself closes a loop, whose exterior angles sum to 2 pi with at most pi at the crossing: the
// vertices between two segments that cross turn by more than pi in all. Kept below pi so that
// rounding of the angles cannot matter.
constexpr double kNoFoldTurning = 3.0;

// Cuts the loops an offset makes where the centerline bends tighter than the half-width:
// a segment that crosses a later one within reach skips everything in between. A window that
// turns too little to cross itself (most of a stroke) is not searched.
std::vector<glm::dvec2> remove_folds(const Side& side, double reach) {
    const std::vector<glm::dvec2>& p = side.points;
    const size_t n = p.size();
    std::vector<glm::dvec2> out;
    if (n == 0) return out;
    out.reserve(n);
    // turned[k]: absolute turning at points 1..k; tiny[k]: tiny segments among 0..k-1.
    std::vector<double> turned(n, 0.0);
    std::vector<uint32_t> tiny(n + 1, 0);
    glm::dvec2 heading(0.0);
    for (size_t k = 0; k + 1 < n; ++k) {
        const glm::dvec2 d = p[k + 1] - p[k];
        tiny[k + 1] = tiny[k] + (glm::length(d) < kTinySegmentPx ? 1 : 0);
        double turn = 0.0;
        if (d != glm::dvec2(0.0)) {
            if (heading != glm::dvec2(0.0)) {
                // A small turn counts as its tangent, which is never less than the angle: the
                // windows' turning is over-estimated (by under 2% of each turn), never under.
                const double sine = std::abs(cross(heading, d)), cosine = glm::dot(heading, d);
                turn = sine < 0.25 * cosine ? sine / cosine : std::abs(std::atan2(sine, cosine));
            }
            heading = d;
        }
        if (k > 0) turned[k] = turned[k - 1] + turn;
    }
    if (n > 1) turned[n - 1] = turned[n - 2];
    out.push_back(p[0]);
    size_t i = 0;
    size_t last = 0;  // the last segment within reach of segment i (never decreases)
    while (i + 1 < n) {
        const glm::dvec2 a = out.back(), b = p[i + 1];
        last = std::max(last, i + 1);
        while (last + 2 < n && side.arc[last + 1] - side.arc[i + 1] <= reach) ++last;
        const bool may_cross = last >= i + 2 && (turned[last] - turned[i] >= kNoFoldTurning || tiny[last + 1] != tiny[i]);
        size_t hit = 0;
        glm::dvec2 x{};
        for (size_t j = i + 2; may_cross && j + 1 < n && side.arc[j] - side.arc[i + 1] <= reach; ++j) {
            if (const auto q = intersect(a, b, p[j], p[j + 1])) hit = j, x = *q;
        }
        if (hit) {
            out.push_back(x);
            i = hit;
        } else {
            out.push_back(b);
            ++i;
        }
    }
    return out;
}

// Half circle of radius r around c from `from` (a unit normal) turning through `through`.
void cap(const glm::dvec2& c, const glm::dvec2& from, const glm::dvec2& through, double r, double step_rad,
         std::vector<glm::dvec2>& out) {
    const int steps = std::max(2, int(std::ceil(std::numbers::pi / step_rad)));
    for (int k = 1; k < steps; ++k) {
        const double a = std::numbers::pi * double(k) / steps;
        out.push_back(c + (from * std::cos(a) + through * std::sin(a)) * r);
    }
}

// The cap of an end at c of half width r, from the side at `from` (a unit normal) round to the
// other, bulging along `through` (the unit tangent out of the stroke): butt caps add nothing.
void end_cap(const glm::dvec2& c, const glm::dvec2& from, const glm::dvec2& through, double r, double step_rad,
             LineCap kind, std::vector<glm::dvec2>& out) {
    switch (kind) {
        case LineCap::kRound: cap(c, from, through, r, step_rad, out); break;
        case LineCap::kButt: break;
        case LineCap::kSquare:
            out.push_back(c + (from + through) * r);
            out.push_back(c + (through - from) * r);
            break;
    }
}

// True when two edges of the ring that do not follow one another meet (exact predicates): then
// the ring is not simple. False says nothing: is_simple decides. The edges are bucketed in a
// grid of about one cell per edge, so that a ring of thousands of points costs a few pair tests
// per edge where CGAL's sweep sorts every vertex.
bool edges_meet(const Ring& ring) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    const size_t n = ring.size();
    if (n < 4) return false;
    glm::dvec2 lo = ring[0], hi = ring[0];
    for (const glm::dvec2& p : ring) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const double cell = std::max(std::max(hi.x - lo.x, hi.y - lo.y) / std::sqrt(double(n)), 1e-9);
    const auto columns = size_t(std::floor((hi.x - lo.x) / cell)) + 1;
    // Points crowded into a few cells, or edges across many, would make this quadratic: past a
    // budget of cells and of pair tests, is_simple decides.
    size_t budget = kEdgePairsPerEdge * n;
    std::vector<std::pair<size_t, uint32_t>> cells;  // (cell, edge)
    for (size_t e = 0; e < n; ++e) {
        const glm::dvec2 a = ring[e], b = ring[(e + 1) % n];
        const auto x0 = size_t((std::min(a.x, b.x) - lo.x) / cell), x1 = size_t((std::max(a.x, b.x) - lo.x) / cell);
        const auto y0 = size_t((std::min(a.y, b.y) - lo.y) / cell), y1 = size_t((std::max(a.y, b.y) - lo.y) / cell);
        if ((x1 - x0 + 1) * (y1 - y0 + 1) > budget - cells.size()) return false;
        for (size_t y = y0; y <= y1; ++y) {
            for (size_t x = x0; x <= x1; ++x) cells.emplace_back(y * columns + x, uint32_t(e));
        }
    }
    std::sort(cells.begin(), cells.end());
    auto segment = [&](uint32_t e) {
        const glm::dvec2 a = ring[e], b = ring[(e + 1) % n];
        return Kernel::Segment_2({a.x, a.y}, {b.x, b.y});
    };
    for (size_t begin = 0, end = 0; begin < cells.size(); begin = end) {
        while (end < cells.size() && cells[end].first == cells[begin].first) ++end;
        for (size_t i = begin; i < end; ++i) {
            for (size_t j = i + 1; j < end; ++j) {
                const size_t d = cells[j].second - cells[i].second;  // edges ascend within a cell
                if (d <= 1 || d == n - 1) continue;                  // neighbours share a corner
                if (budget-- == 0) return false;
                if (CGAL::do_intersect(segment(cells[i].second), segment(cells[j].second))) return true;
            }
        }
    }
    return false;
}

// The sign of the turn a -> b -> c (+1 left, -1 right, 0 on one line), exact: from doubles where
// their error bound settles it (J. R. Shewchuk, Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates, 1997: orient2d's first stage), else from CGAL.
int orientation(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    const double left = (a.x - c.x) * (b.y - c.y), right = (a.y - c.y) * (b.x - c.x);
    const double det = left - right, magnitude = std::abs(left) + std::abs(right);
    // (3 + 16 eps) eps, eps = 2^-53; far from underflow, where the bound holds.
    constexpr double kErrorBound = 3.3306690738754716e-16;
    if (std::abs(det) > kErrorBound * magnitude && magnitude > 1e-280) return det > 0.0 ? 1 : -1;
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    switch (CGAL::orientation(Kernel::Point_2(a.x, a.y), Kernel::Point_2(b.x, b.y), Kernel::Point_2(c.x, c.y))) {
        case CGAL::LEFT_TURN:
            return 1;
        case CGAL::RIGHT_TURN:
            return -1;
        default:
            return 0;
    }
}

// Whether c, on the line through a and b, lies on the segment ab.
bool within(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
}

// Whether the closed segments pq and rs share a point (exact).
bool segments_meet(const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r, const glm::dvec2& s) {
    const int d1 = orientation(r, s, p), d2 = orientation(r, s, q);
    const int d3 = orientation(p, q, r), d4 = orientation(p, q, s);
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && within(r, s, p)) || (d2 == 0 && within(r, s, q)) || (d3 == 0 && within(p, q, r)) ||
           (d4 == 0 && within(p, q, s));
}

// CGAL::is_simple_2's answer without its sweep, or none past a budget of edge pairs: a ring of
// four points or more is simple when no two edges that do not follow one another meet. A point
// that comes twice makes two such edges meet, and so does an edge that folds back over the one
// before it: the edge after the shorter of the two starts on the longer. The edges are swept
// along the ring's longer side, each tested against those whose span there it overlaps.
std::optional<bool> simple_by_sweep(const Ring& ring) {
    const size_t n = ring.size();
    for (const glm::dvec2& p : ring) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) return std::nullopt;
    }
    // A triangle: three distinct points not on one line.
    if (n == 3) {
        return ring[0] != ring[1] && ring[1] != ring[2] && ring[2] != ring[0] &&
               orientation(ring[0], ring[1], ring[2]) != 0;
    }
    glm::dvec2 lo = ring[0], hi = ring[0];
    for (const glm::dvec2& p : ring) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const int axis = hi.x - lo.x >= hi.y - lo.y ? 0 : 1;
    struct Edge {
        glm::dvec2 lo, hi;  // its box
        uint32_t index;
    };
    std::vector<Edge> edges(n);
    for (size_t e = 0; e < n; ++e) {
        const glm::dvec2 &a = ring[e], &b = ring[(e + 1) % n];
        edges[e] = {glm::min(a, b), glm::max(a, b), uint32_t(e)};
    }
    std::sort(edges.begin(), edges.end(), [axis](const Edge& a, const Edge& b) {
        return std::tie(a.lo[axis], a.index) < std::tie(b.lo[axis], b.index);
    });
    std::vector<const Edge*> active;
    size_t budget = kEdgePairsPerEdge * n;
    for (const Edge& e : edges) {
        std::erase_if(active, [&](const Edge* f) { return f->hi[axis] < e.lo[axis]; });
        for (const Edge* f : active) {
            const int other = 1 - axis;
            if (f->hi[other] < e.lo[other] || e.hi[other] < f->lo[other]) continue;
            const size_t d = e.index > f->index ? e.index - f->index : f->index - e.index;
            if (d <= 1 || d == n - 1) continue;  // neighbours share a corner
            if (budget-- == 0) return std::nullopt;
            if (segments_meet(ring[e.index], ring[(e.index + 1) % n], ring[f->index], ring[(f->index + 1) % n])) {
                return false;
            }
        }
        active.push_back(&e);
    }
    return true;
}

Ring dedupe(std::vector<glm::dvec2> ring) {
    Ring out;
    out.reserve(ring.size());
    for (const glm::dvec2& p : ring) {
        if (out.empty() || glm::length(p - out.back()) > kSamePointPx) out.push_back(p);
    }
    while (out.size() > 1 && glm::length(out.front() - out.back()) <= kSamePointPx) out.pop_back();
    return out;
}

}  // namespace

std::vector<Ring> build_outline(std::span<const glm::dvec2> c, std::span<const double> w, bool closed,
                                const OutlineOptions& options) {
    std::vector<Ring> rings;
    const size_t n = c.size();
    if (n < 2 || w.size() != n) return rings;
    const double step = glm::radians(std::max(options.join_step_deg, 1.0));
    const std::vector<glm::dvec2> t = centerline_tangents(c, closed);
    const double reach = *std::max_element(w.begin(), w.end()) + kFoldReachPx;
    const std::vector<glm::dvec2> left = remove_folds(offset_side(c, w, t, closed, 1.0, step), reach);
    const std::vector<glm::dvec2> right = remove_folds(offset_side(c, w, t, closed, -1.0, step), reach);

    if (closed) {
        rings.push_back(dedupe(left));
        rings.push_back(dedupe({right.rbegin(), right.rend()}));
    } else {
        // Left side forwards, end cap, right side backwards, start cap.
        std::vector<glm::dvec2> ring;
        ring.reserve(left.size() + right.size() + 64);
        ring.assign(left.begin(), left.end());
        if (w.back() > kCapMinWidthPx) end_cap(c.back(), perp(t.back()), t.back(), 0.5 * w.back(), step, options.cap, ring);
        ring.insert(ring.end(), right.rbegin(), right.rend());
        if (w.front() > kCapMinWidthPx) {
            end_cap(c.front(), -perp(t.front()), -t.front(), 0.5 * w.front(), step, options.cap, ring);
        }
        rings.push_back(dedupe(std::move(ring)));
    }
    // Thin strokes simplify finer, so that the tolerance stays a small part of their width.
    double mean_width = 0.0;
    for (const double x : w) mean_width += x / double(n);
    const double tolerance = std::min(options.simplify_px, kSimplifyWidthFraction * mean_width);
    for (Ring& ring : rings) {
        if (!(tolerance > 0.0)) continue;
        // Simplification can make a thin ring touch itself; then the full ring is kept, unless it
        // touches itself already (an open stroke whose end overlaps its own ink, a hairpin: then
        // two of its edges are usually found to meet without the full test).
        Ring simple = simplify_ring(ring, tolerance);
        if (simple.size() >= 3 && (is_simple(simple) || edges_meet(ring) || !is_simple(ring))) ring = std::move(simple);
    }
    std::erase_if(rings, [](const Ring& r) { return r.size() < 3; });
    return rings;
}

std::vector<Ring> dot_outline(const glm::dvec2& c, const glm::dvec2& tangent, double width, const OutlineOptions& options) {
    if (!(width > kCapMinWidthPx) || options.cap == LineCap::kButt) return {};
    const glm::dvec2 n = perp(tangent);
    Ring ring;
    // Both caps of a stroke of no length, back to back.
    ring.push_back(c + n * (0.5 * width));
    end_cap(c, n, tangent, 0.5 * width, glm::radians(std::max(options.join_step_deg, 1.0)), options.cap, ring);
    ring.push_back(c - n * (0.5 * width));
    end_cap(c, -n, -tangent, 0.5 * width, glm::radians(std::max(options.join_step_deg, 1.0)), options.cap, ring);
    return {dedupe(std::move(ring))};
}

std::vector<glm::dvec2> centerline_tangents(std::span<const glm::dvec2> c, bool closed) {
    const auto n = std::ptrdiff_t(c.size());
    std::vector<glm::dvec2> t(c.size(), glm::dvec2(1.0, 0.0));
    auto at = [&](std::ptrdiff_t i) {
        return c[size_t(closed ? ((i % n) + n) % n : std::clamp<std::ptrdiff_t>(i, 0, n - 1))];
    };
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        for (std::ptrdiff_t k = 1; k < n; ++k) {
            const glm::dvec2 d = at(i + k) - at(i - k);
            if (glm::length(d) > kSamePointPx) {
                t[size_t(i)] = glm::normalize(d);
                break;
            }
        }
    }
    return t;
}

double signed_area(const Ring& ring) {
    double sum = 0.0;
    for (size_t i = 0; i < ring.size(); ++i) sum += cross(ring[i], ring[(i + 1) % ring.size()]);
    return 0.5 * sum;
}

double outline_area(const std::vector<Ring>& rings) {
    double sum = 0.0;
    for (const Ring& ring : rings) sum += signed_area(ring);
    return std::abs(sum);
}

bool is_simple(const Ring& ring) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    if (ring.size() < 3) return false;
    if (const std::optional<bool> known = simple_by_sweep(ring)) return *known;
    std::vector<Kernel::Point_2> points;
    for (const glm::dvec2& p : ring) points.emplace_back(p.x, p.y);
    return points.size() >= 3 && CGAL::is_simple_2(points.begin(), points.end(), Kernel());
}

Ring simplify_ring(const Ring& ring, double tolerance) {
    const size_t n = ring.size();
    if (n < 4) return ring;
    // Split at the first point and the point farthest from it; simplify both chains.
    size_t far = 0;
    double far_d = -1.0;
    for (size_t i = 1; i < n; ++i) {
        const double d = glm::length(ring[i] - ring[0]);
        if (d > far_d) far_d = d, far = i;
    }
    // Runs of kSimplifyBlock points, each within `bend` of the segment between its first and
    // last point: the distance to a chord is convex and grows no faster than the point moves, so
    // no point of a run lies farther from it than the farther of those two plus the bend. The
    // farthest point lies in a run that may reach at least as far as a point found already; the
    // other runs are passed over.
    const size_t blocks = n / kSimplifyBlock;
    std::vector<double> bend(blocks, 0.0), block_reach(blocks);
    for (size_t b = 0; b < blocks; ++b) {
        const glm::dvec2 first = ring[b * kSimplifyBlock], last = ring[(b + 1) * kSimplifyBlock - 1];
        // sqrt is monotone and correctly rounded: the root of the largest square is the largest root.
        double bend2 = 0.0;
        for (size_t i = b * kSimplifyBlock + 1; i + 1 < (b + 1) * kSimplifyBlock; ++i) {
            bend2 = std::max(bend2, distance2_to_segment(ring[i], first, last));
        }
        bend[b] = std::sqrt(bend2);
    }
    std::vector<uint8_t> keep(n, 0);
    keep[0] = keep[far] = 1;
    auto point = [&](size_t i) { return ring[i < n ? i : i - n]; };  // hi may be n: the first point again
    std::vector<std::pair<size_t, size_t>> stack = {{0, far}, {far, n}};
    while (!stack.empty()) {
        const auto [lo, hi] = stack.back();
        stack.pop_back();
        if (hi <= lo + 1) continue;
        const glm::dvec2 a = point(lo), b = point(hi);
        const glm::dvec2 ab = b - a;
        const double len2 = glm::dot(ab, ab);
        auto distance2 = [&](const glm::dvec2& p) {
            const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
            const glm::dvec2 off = p - (a + ab * t);
            return glm::dot(off, off);
        };
        // The farthest point, the first of equals, as one pass in order finds it.
        size_t worst = 0;
        double worst_d = -1.0, worst_d2 = -1.0;
        auto visit = [&](size_t first, size_t last) {
            for (size_t i = first; i < last; ++i) {
                // sqrt is monotone: a squared distance no larger than the worst's cannot beat it.
                const double d2 = distance2(point(i));
                if (d2 <= worst_d2) continue;
                const double d = std::sqrt(d2);
                if (d > worst_d) worst_d = d, worst_d2 = d2, worst = i;
            }
        };
        // Whole runs strictly inside (lo, hi); a point of each gives a distance the farthest
        // reaches at least.
        const size_t first_block = (lo + 1 + kSimplifyBlock - 1) / kSimplifyBlock;
        const size_t end_block = std::max(first_block, hi / kSimplifyBlock);
        double reached = -1.0;
        for (size_t k = first_block; k < end_block; ++k) {
            const double ends =
                std::sqrt(std::max(distance2(ring[k * kSimplifyBlock]), distance2(ring[(k + 1) * kSimplifyBlock - 1])));
            block_reach[k] = ends + bend[k];
            reached = std::max(reached, ends);
        }
        if (first_block == end_block) {
            visit(lo + 1, hi);
        } else {
            visit(lo + 1, first_block * kSimplifyBlock);
            for (size_t k = first_block; k < end_block; ++k) {
                // Rounding moves a distance by far less than the margin.
                if (block_reach[k] + kSimplifyBoundMarginPx < std::max(reached, worst_d)) continue;
                visit(k * kSimplifyBlock, (k + 1) * kSimplifyBlock);
            }
            visit(end_block * kSimplifyBlock, hi);
        }
        if (worst_d > tolerance) {
            keep[worst % n] = 1;
            stack.emplace_back(lo, worst);
            stack.emplace_back(worst, hi);
        }
    }
    Ring out;
    for (size_t i = 0; i < n; ++i) {
        if (keep[i]) out.push_back(ring[i]);
    }
    return out;
}

}  // namespace inkline::core
