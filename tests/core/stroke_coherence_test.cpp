// SPDX-License-Identifier: MIT
#include "core/strokes/stroke_coherence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

namespace inkline {
namespace {

using glm::dvec2;

// A straight stroke from a to b, sampled every kTraceSpacingPx, on edge_count edges of equal
// length from first_edge on.
core::StrokeCandidate candidate(dvec2 a, dvec2 b, uint32_t first_edge, uint32_t edge_count = 10) {
    core::StrokeCandidate c;
    c.length_px = glm::length(b - a);
    for (uint32_t e = 0; e <= edge_count; ++e) {
        const dvec2 p = a + (b - a) * (double(e) / edge_count);
        c.geometry.points_px.push_back(p);
        c.geometry.points_world.push_back(glm::dvec3(p, 0.0));
        if (e < edge_count) c.geometry.edges.push_back(first_edge + e);
    }
    for (double s = 0.0; s <= c.length_px + 1e-9; s += core::kTraceSpacingPx) {
        c.samples_px.push_back(a + (b - a) * (s / c.length_px));
        c.samples_arc.push_back(s);
    }
    return c;
}

// What the state remembers of a candidate given an id and u offset.
core::StrokeTrace trace(const core::StrokeCandidate& c, uint32_t id, double u_offset) {
    core::StrokeTrace t;
    t.id = id;
    t.length_px = c.length_px;
    t.edges = c.geometry.edges;
    t.samples_px = c.samples_px;
    for (double s : c.samples_arc) t.samples_u.push_back(u_offset + s);
    return t;
}

TEST(StrokeCoherence, FirstFrameGetsFreshIdsInOrder) {
    const core::StrokeCoherence state({}, 7);
    const auto m = state.match({candidate({0, 0}, {100, 0}, 0), candidate({0, 50}, {100, 50}, 100)});
    ASSERT_EQ(m.size(), 2u);
    EXPECT_EQ(m[0].id, 7u);
    EXPECT_EQ(m[1].id, 8u);
    EXPECT_FALSE(m[0].inherited || m[1].inherited);
}

TEST(StrokeCoherence, SameStrokeKeepsIdAndParameter) {
    const core::StrokeCandidate c = candidate({0, 0}, {100, 0}, 0);
    const core::StrokeCoherence state({trace(c, 42, 17.0)}, 43);
    const auto m = state.match({c});
    ASSERT_EQ(m.size(), 1u);
    EXPECT_EQ(m[0].id, 42u);
    EXPECT_TRUE(m[0].inherited);
    EXPECT_FALSE(m[0].reverse);
    EXPECT_NEAR(m[0].u_offset, 17.0, 1e-9);
}

TEST(StrokeCoherence, ReversedStrokeIsTurnedBack) {
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0), 3, 0.0)}, 4);
    const auto m = state.match({candidate({100, 0}, {0, 0}, 0)});
    EXPECT_EQ(m[0].id, 3u);
    EXPECT_TRUE(m[0].reverse);
    EXPECT_NEAR(m[0].u_offset, 0.0, 1e-9);
}

TEST(StrokeCoherence, ParameterStaysOnTheImageWhenAStrokeGrowsAndMoves) {
    // Last frame: x in [0, 100], u = x. Now the stroke moved 3 px down and grew 10 px at its start:
    // u must stay attached, so the new start gets u = -10.
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0), 1, 0.0)}, 2);
    const auto m = state.match({candidate({-10, 3}, {100, 3}, 500)});
    EXPECT_EQ(m[0].id, 1u) << "no shared edge, but it lies close";
    EXPECT_FALSE(m[0].reverse);
    EXPECT_NEAR(m[0].u_offset, -10.0, 1.01);
}

TEST(StrokeCoherence, SplitStrokeKeepsItsIdOnTheLargerPart) {
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0, 10), 5, 0.0)}, 6);
    const auto m = state.match({candidate({0, 0}, {30, 0}, 0, 3), candidate({40, 0}, {100, 0}, 4, 6)});
    EXPECT_EQ(m[1].id, 5u);
    EXPECT_TRUE(m[1].inherited);
    EXPECT_EQ(m[0].id, 6u);
    EXPECT_FALSE(m[0].inherited);
    EXPECT_NEAR(m[1].u_offset, 40.0, 1e-9);
}

TEST(StrokeCoherence, DistantStrokeIsNew) {
    const core::StrokeCoherence state({trace(candidate({0, 0}, {100, 0}, 0), 5, 0.0)}, 6);
    const auto m = state.match({candidate({0, 300}, {100, 300}, 1000)});
    EXPECT_EQ(m[0].id, 6u);
    EXPECT_FALSE(m[0].inherited);
}

TEST(StrokeCoherence, KindsDoNotMix) {
    core::StrokeCandidate c = candidate({0, 0}, {100, 0}, 0);
    const core::StrokeCoherence state({trace(c, 5, 0.0)}, 6);
    c.geometry.kind = core::LineKind::kCrease;
    EXPECT_FALSE(state.match({c})[0].inherited);
    c.geometry.visible = false;
    EXPECT_FALSE(state.match({c})[0].inherited);
}

TEST(StrokeCoherence, HiddenLineComingIntoViewKeepsItsId) {
    // Last frame the line was hidden (written with lines.hidden); now it shows, moved 4 px and
    // on the neighbouring mesh edges, as a silhouette sliding over the mesh does.
    core::StrokeTrace hidden = trace(candidate({0, 0}, {100, 0}, 0), 5, 10.0);
    hidden.visible = false;
    const core::StrokeCoherence state({hidden}, 6);
    const auto m = state.match({candidate({0, 4}, {100, 4}, 500)});
    EXPECT_EQ(m[0].id, 5u);
    EXPECT_TRUE(m[0].inherited);
    EXPECT_NEAR(m[0].u_offset, 10.0, 1e-9);
}

TEST(StrokeCoherence, SameVisibilityComesFirst) {
    // A visible line with a hidden one right behind it, both seen again, moved and on other
    // edges: each keeps its own id, although the hidden stroke of last frame overlaps the
    // visible one now (100 px) more than the visible one (60 px) or the hidden one (80 px) does.
    core::StrokeTrace visible = trace(candidate({0, 0}, {60, 0}, 0), 1, 0.0);
    core::StrokeTrace hidden = trace(candidate({0, 1}, {100, 1}, 100), 2, 0.0);
    hidden.visible = false;
    const core::StrokeCoherence state({visible, hidden}, 3);
    core::StrokeCandidate now_visible = candidate({0, 0}, {100, 0}, 200);
    core::StrokeCandidate now_hidden = candidate({0, 6}, {80, 6}, 300);
    now_hidden.geometry.visible = false;
    const auto m = state.match({now_visible, now_hidden});
    EXPECT_EQ(m[0].id, 1u);
    EXPECT_EQ(m[1].id, 2u);
}

TEST(StrokeCoherence, SameVisibilityComesFirstOverEveryRadius) {
    // A visible line sweeping fast (16 px since last frame: only the wider radius finds it) and
    // a small hidden piece right on last frame's line: the visible line keeps the id.
    const core::StrokeCoherence state({trace(candidate({0, 0}, {200, 0}, 0), 4, 0.0)}, 5);
    core::StrokeCandidate piece = candidate({100, 1}, {110, 1}, 600, 1);
    piece.geometry.visible = false;
    const auto m = state.match({candidate({0, 16}, {200, 16}, 500), piece});
    EXPECT_EQ(m[0].id, 4u);
    EXPECT_EQ(m[1].id, 5u);
}

TEST(StrokeCoherence, SideSamplesPassOverATangleAtTheEnd) {
    // The stroke runs back and forth near its end (a zig-zag tangle), then away along x: its
    // side is sampled where it first gets 2, 4, ... 12 px from the end.
    const std::vector<dvec2> zigzag{{0, 0}, {3, 0}, {1, 0}, {3.5, 0}, {0.5, 0}, {20, 0}};
    const std::vector<dvec2> side = core::side_samples(zigzag, 0);
    ASSERT_EQ(side.size(), 6u);
    for (size_t i = 0; i < side.size(); ++i) EXPECT_NEAR(side[i].x, 2.0 * double(i + 1), 1e-9) << i;
    std::vector<dvec2> reversed(zigzag.rbegin(), zigzag.rend());
    EXPECT_EQ(core::side_samples(reversed, 1), side);
}

TEST(StrokeCoherence, LoopStartStaysPut) {
    // A square loop seen twice: the start stays where it was.
    core::StrokeCandidate loop;
    loop.geometry.closed = true;
    const std::vector<dvec2> corners = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    for (int side = 0; side < 4; ++side) {
        for (int i = 0; i < 50; ++i) {
            loop.samples_px.push_back(corners[size_t(side)] +
                                      (corners[size_t((side + 1) % 4)] - corners[size_t(side)]) * (i / 50.0));
            loop.samples_arc.push_back(100.0 * side + 2.0 * i);
        }
    }
    loop.length_px = 400.0;
    core::StrokeTrace t = trace(loop, 9, 0.0);
    t.closed = true;
    t.start_px = {100, 40};
    const core::StrokeCoherence state({t}, 10);
    const auto m = state.match({loop});
    ASSERT_TRUE(m[0].start_px.has_value());
    EXPECT_LT(glm::length(*m[0].start_px - dvec2(100, 40)), 1e-9);
}

}  // namespace
}  // namespace inkline

namespace inkline {
namespace {

TEST(StrokeCoherence, NearestSampleIsTheNearestOfAllInCrowdedAndSparsePlaces) {
    // Random short strokes, dense in one corner and sparse elsewhere, some hidden and some of
    // another kind, against a search over every sample: the nearest visible one of the kind
    // within kMatchRadiusPx, ties to the lower stroke and sample.
    uint32_t seed = 7;
    auto random = [&] {
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 24);
    };
    std::vector<core::StrokeTrace> traces;
    for (uint32_t s = 0; s < 3000; ++s) {
        const double spread = s % 3 ? 120.0 : 2000.0;
        const dvec2 a(spread * random() - 300.0, spread * random() - 300.0);
        const dvec2 b = a + dvec2(40.0 * random() - 20.0, 40.0 * random() - 20.0);
        core::StrokeTrace t = trace(candidate(a, b, 10 * s), s, 0.0);
        t.visible = s % 5 != 0;
        t.kind = s % 7 == 0 ? core::LineKind::kCrease : core::LineKind::kSilhouette;
        traces.push_back(std::move(t));
    }
    std::vector<dvec2> points;
    for (int i = 0; i < 4000; ++i) {
        const double spread = i % 2 ? 150.0 : 2100.0;
        points.push_back({spread * random() - 320.0, spread * random() - 320.0});
    }
    points.push_back(traces[1].samples_px[0]);  // exactly on a sample
    const core::StrokeCoherence state(traces, 3000);
    const std::vector<core::StrokeCoherence::Nearest> got = state.nearest_visible(points, core::LineKind::kSilhouette);
    ASSERT_EQ(got.size(), points.size());
    size_t found = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        double best = HUGE_VAL;
        int64_t id = -1;
        double u = 0.0;
        for (const core::StrokeTrace& t : traces) {
            if (!t.visible || t.kind != core::LineKind::kSilhouette) continue;
            for (size_t k = 0; k < t.samples_px.size(); ++k) {
                const double d = glm::length(t.samples_px[k] - points[i]);
                if (d <= core::kMatchRadiusPx && d < best) best = d, id = t.id, u = t.samples_u[k];
            }
        }
        found += id >= 0;
        ASSERT_EQ(got[i].id, id) << "point " << i;
        ASSERT_EQ(got[i].u, u) << "point " << i;
    }
    EXPECT_GT(found, points.size() / 3);
    EXPECT_LT(found, points.size());
}

// Straight strokes 100 px long through one point, at angles turning by `step` (rad), each on
// edges of its own (10 a stroke from first_edge); odd ones drawn from the other end.
std::vector<core::StrokeCandidate> star(size_t count, dvec2 center, double first_angle, double step,
                                        uint32_t first_edge) {
    std::vector<core::StrokeCandidate> out;
    for (size_t i = 0; i < count; ++i) {
        const double a = first_angle + step * double(i);
        const dvec2 d = 50.0 * dvec2(std::cos(a), std::sin(a));
        const uint32_t edges = first_edge + 10 * uint32_t(i);
        out.push_back(i % 2 ? candidate(center + d, center - d, edges) : candidate(center - d, center + d, edges));
    }
    return out;
}

// The nearest sample of the traces `use` accepts within radius, by a search over every sample:
// (trace, sample, distance), ties to the lower trace and sample; trace -1 where there is none.
template <typename Use>
std::tuple<int64_t, size_t, double> nearest_of_all(const std::vector<core::StrokeTrace>& traces, dvec2 p, double radius,
                                                   Use use) {
    std::tuple<int64_t, size_t, double> best{-1, 0, HUGE_VAL};
    for (size_t t = 0; t < traces.size(); ++t) {
        for (size_t k = 0; k < traces[t].samples_px.size(); ++k) {
            if (!use(t, k)) continue;
            const double d = glm::length(traces[t].samples_px[k] - p);
            if (d <= radius && d < std::get<2>(best)) best = {int64_t(t), k, d};
        }
    }
    return best;
}

// match as documented, for visible open strokes of one kind, by searches over every sample:
// the largest overlaps first over 12, 24 and 48 px, then fresh ids; direction and u offset from
// the nearest samples of the stroke taken.
std::vector<core::StrokeMatch> match_by_every_sample(const std::vector<core::StrokeCandidate>& candidates,
                                                     const std::vector<core::StrokeTrace>& traces, uint32_t next_id) {
    std::vector<core::StrokeMatch> out(candidates.size());
    std::vector<uint8_t> done(candidates.size(), 0), taken(traces.size(), 0);
    for (int round = 0; round < 3; ++round) {
        const double radius = core::kMatchRadiusPx * double(1 << round);
        struct Pair {
            size_t c, t;
            double score;
        };
        std::vector<Pair> pairs;
        for (size_t c = 0; c < candidates.size(); ++c) {
            if (done[c]) continue;
            const core::StrokeCandidate& cand = candidates[c];
            std::map<size_t, double> score;
            for (size_t s = 0; s < cand.geometry.edges.size(); ++s) {
                for (size_t t = 0; t < traces.size(); ++t) {
                    const std::vector<uint32_t>& e = traces[t].edges;
                    const double length = glm::length(cand.geometry.points_px[s + 1] - cand.geometry.points_px[s]);
                    if (!taken[t] && std::binary_search(e.begin(), e.end(), cand.geometry.edges[s])) score[t] += length;
                }
            }
            const double share = cand.length_px / double(cand.samples_px.size());
            for (const dvec2& p : cand.samples_px) {
                const auto [t, k, d] = nearest_of_all(traces, p, radius, [&](size_t other, size_t) { return !taken[other]; });
                if (t >= 0) score[size_t(t)] += share;
            }
            for (const auto& [t, sc] : score) {
                if (sc >= core::kMinOverlapFraction * std::min(cand.length_px, traces[t].length_px)) pairs.push_back({c, t, sc});
            }
        }
        std::sort(pairs.begin(), pairs.end(),
                  [](const Pair& a, const Pair& b) { return std::tie(b.score, a.c, a.t) < std::tie(a.score, b.c, b.t); });
        for (const Pair& p : pairs) {
            if (done[p.c] || taken[p.t]) continue;
            done[p.c] = taken[p.t] = 1;
            const core::StrokeCandidate& cand = candidates[p.c];
            std::vector<double> s, u;
            for (size_t i = 0; i < cand.samples_px.size(); ++i) {
                const auto [t, k, d] =
                    nearest_of_all(traces, cand.samples_px[i], radius, [&](size_t other, size_t) { return other == p.t; });
                if (t < 0) continue;
                s.push_back(cand.samples_arc[i]);
                u.push_back(traces[p.t].samples_u[k]);
            }
            core::StrokeMatch& m = out[p.c];
            m.id = traces[p.t].id;
            m.inherited = true;
            // Which way u runs, summed step by step as match sums it.
            double flow = 0.0;
            for (size_t i = 1; i < u.size(); ++i) {
                const double du = u[i] - u[i - 1];
                u[i] = u[i - 1] + du;
                flow += du;
            }
            m.reverse = flow < 0.0;
            std::vector<double> offsets;
            for (size_t i = 0; i < u.size(); ++i) offsets.push_back(u[i] - (m.reverse ? cand.length_px - s[i] : s[i]));
            std::nth_element(offsets.begin(), offsets.begin() + std::ptrdiff_t(offsets.size() / 2), offsets.end());
            if (!offsets.empty()) m.u_offset = offsets[offsets.size() / 2];
        }
    }
    for (size_t c = 0; c < candidates.size(); ++c) {
        if (!done[c]) out[c].id = next_id++;
    }
    return out;
}

TEST(StrokeCoherence, StrokesCrowdedThroughOnePointMatchAsASearchOverEverySampleWould) {
    // 400 strokes through one point (as where thousands of faces share an edge). Now every other
    // one is seen again, turned by more than their spacing, on other edges but for every fifth;
    // and short strokes cross near the point, where each sample lies nearest to another of them:
    // which strokes they take depends on every nearest sample there.
    const dvec2 center(300.0, 300.0);
    const double step = std::numbers::pi / 400.0;
    std::vector<core::StrokeTrace> traces;
    for (const core::StrokeCandidate& c : star(400, center, 0.0, step, 0)) {
        traces.push_back(trace(c, 1000 + uint32_t(traces.size()), 3.0 * double(traces.size())));
        std::sort(traces.back().edges.begin(), traces.back().edges.end());
    }
    std::vector<core::StrokeCandidate> now;
    const std::vector<core::StrokeCandidate> turned = star(400, center, 1.7 * step, step, 100000);
    for (size_t i = 0; i < 400; i += 2) {
        now.push_back(turned[i]);
        if (i % 5 == 0) now.back().geometry.edges = traces[i].edges;
    }
    uint32_t seed = 4;
    auto random = [&] {
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 24);
    };
    for (uint32_t i = 0; i < 150; ++i) {
        // Near the way one stroke not seen again ran, within 15 px of the point.
        const double a = step * (2.0 * std::floor(200.0 * random()) + 1.0 + random() - 0.5);
        const dvec2 d(std::cos(a), std::sin(a));
        const dvec2 mid = center + d * (30.0 * random() - 15.0) + dvec2(-d.y, d.x) * (random() - 0.5);
        now.push_back(candidate(mid - 5.0 * d, mid + 5.0 * d, 200000 + 10 * i));
    }
    const core::StrokeCoherence state(traces, 2000);
    const std::vector<core::StrokeMatch> got = state.match(now);
    const std::vector<core::StrokeMatch> want = match_by_every_sample(now, traces, 2000);
    ASSERT_EQ(got.size(), want.size());
    size_t long_kept = 0, short_kept = 0;
    for (size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].id, want[i].id) << "stroke " << i;
        ASSERT_EQ(got[i].inherited, want[i].inherited) << "stroke " << i;
        ASSERT_EQ(got[i].reverse, want[i].reverse) << "stroke " << i;
        ASSERT_EQ(got[i].u_offset, want[i].u_offset) << "stroke " << i;
        (i < 200 ? long_kept : short_kept) += got[i].inherited;
    }
    EXPECT_EQ(long_kept, 200u);
    EXPECT_GT(short_kept, 20u) << "short strokes take ids of strokes not seen again";
    EXPECT_LT(short_kept, 150u);
}

TEST(StrokeCoherence, SideMemoryIsTheSearchOverEverySampleWhereStrokesCross) {
    // 1500 visible strokes through one point and a few hidden ones or of another kind; sides
    // near it in every direction, long enough to have one (only strokes running along them
    // count) or not.
    const dvec2 center(200.0, 200.0);
    std::vector<core::StrokeTrace> traces;
    for (const core::StrokeCandidate& c : star(1500, center, 0.1, std::numbers::pi / 1500.0, 0)) {
        core::StrokeTrace t = trace(c, uint32_t(traces.size()), 5.0);
        t.visible = traces.size() % 11 != 0;
        t.kind = traces.size() % 13 == 0 ? core::LineKind::kCrease : core::LineKind::kSilhouette;
        traces.push_back(std::move(t));
    }
    const core::StrokeCoherence state(traces, 1500);
    uint32_t seed = 9;
    auto random = [&] {
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 24);
    };
    std::vector<std::vector<dvec2>> sides;
    std::vector<core::LineKind> kinds;
    for (int i = 0; i < 400; ++i) {
        const dvec2 end = center + dvec2(40.0 * random() - 20.0, 40.0 * random() - 20.0);
        const double a = 2.0 * std::numbers::pi * random();
        const double length = i % 4 == 0 ? 4.0 : 14.0;
        sides.push_back(core::side_samples({end, end + length * dvec2(std::cos(a), std::sin(a))}, 0));
        kinds.push_back(i % 9 == 0 ? core::LineKind::kCrease : core::LineKind::kSilhouette);
    }
    const std::vector<std::vector<core::SideMemory>> got = state.side_memory(sides, kinds);
    ASSERT_EQ(got.size(), sides.size());
    size_t found = 0;
    for (size_t i = 0; i < sides.size(); ++i) {
        // As stroke_coherence.cpp judges a side: samples of last frame count when they run
        // within 60 degrees of a side of at least 6 px, either way.
        const dvec2 along = sides[i].back() - sides[i].front();
        auto runs_along = [&](size_t t, size_t k) {
            const core::StrokeTrace& trace = traces[t];
            if (!trace.visible || trace.kind != kinds[i]) return false;
            const std::vector<dvec2>& q = trace.samples_px;
            if (glm::length(along) < 6.0) return true;
            const dvec2 tangent = q[std::min(k + 1, q.size() - 1)] - q[k > 0 ? k - 1 : 0];
            return std::abs(glm::dot(along, tangent)) >= 0.5 * glm::length(along) * glm::length(tangent);
        };
        std::vector<std::tuple<int64_t, size_t, double>> hits;
        std::map<int64_t, size_t> votes;
        for (const dvec2& p : sides[i]) {
            hits.push_back(nearest_of_all(traces, p, core::kMatchRadiusPx, runs_along));
            if (std::get<0>(hits.back()) >= 0) ++votes[traces[size_t(std::get<0>(hits.back()))].id];
        }
        std::vector<core::SideMemory> want;
        for (const auto& [id, n] : votes) {
            if (2 * n < hits.size()) continue;
            core::SideMemory m{.id = id};
            size_t seen = 0;
            for (const auto& [t, k, d] : hits) {
                if (t < 0 || traces[size_t(t)].id != id) continue;
                if (seen++ == 0) m.u = traces[size_t(t)].samples_u[k];
                m.u_far = traces[size_t(t)].samples_u[k];
                m.distance += d;
            }
            m.distance /= double(seen);
            want.push_back(m);
        }
        ASSERT_EQ(got[i].size(), want.size()) << "side " << i;
        for (size_t k = 0; k < want.size(); ++k) {
            EXPECT_EQ(got[i][k].id, want[k].id) << "side " << i;
            EXPECT_EQ(got[i][k].u, want[k].u) << "side " << i;
            EXPECT_EQ(got[i][k].u_far, want[k].u_far) << "side " << i;
            EXPECT_EQ(got[i][k].distance, want[k].distance) << "side " << i;
        }
        found += !want.empty();
    }
    EXPECT_GT(found, sides.size() / 3);
    EXPECT_LT(found, sides.size());
}

}  // namespace
}  // namespace inkline
