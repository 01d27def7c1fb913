// SPDX-License-Identifier: MIT
#include "core/strokes/rejoin_strokes.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <optional>
#include <queue>
#include <set>
#include <tuple>
#include <unordered_map>

#include "core/internal/point_grid.h"
#include "core/internal/union_find.h"
#include "core/strokes/internal/splice.h"
#include "core/strokes/stroke_path.h"

namespace inkline::core {
namespace {

// A path that joins two parts of last frame's stroke again may run this many times max_gap_px
// (hidden folds of a zig-zag silhouette run back and forth; the chord is bounded on its own).
constexpr double kRejoinPathFactor = 4.0;
// Two sides that come this close (px) within kSideReachPx of their ends run over each other: a
// fold, not two lines that merely end near each other.
constexpr double kFoldTouchPx = 1.0;
// Grid cells for "all ends within d px" are d times this, so that rounding in the cell index
// never leaves out a point exactly d away; and never smaller than kMinCellPx (px), so that a tiny
// d does not make the cell index (an int, over coordinates clamped to 1e8 px) overflow.
constexpr double kCellSlack = 1.0 + 1e-6;
constexpr double kMinCellPx = 1.0;

// The least distance (px) between a's side at end_a and b's side at end_b: from a's side samples
// to b's segments within kSideReachPx of its end.
double side_distance(const StrokeGeometry& a, int end_a, const StrokeGeometry& b, int end_b) {
    const std::vector<glm::dvec2> samples = side_samples(a.points_px, end_a);
    const size_t n = b.points_px.size();
    auto at = [&](size_t k) { return b.points_px[end_b == 0 ? k : n - 1 - k]; };
    double least = HUGE_VAL, arc = 0.0;
    for (size_t k = 0; k + 1 < n && arc <= kSideReachPx; ++k) {
        for (const glm::dvec2& q : samples) least = std::min(least, distance_to_segment(q, at(k), at(k + 1)));
        arc += glm::length(at(k + 1) - at(k));
    }
    return least;
}

// One step of a path between stroke ends: a segment of an occluded part, or a whole short
// visible stroke.
struct Arc {
    size_t to = 0;          // node reached
    double length = 0.0;    // px
    size_t source = 0;      // occluded part, or stroke for a fragment
    size_t segment = 0;     // of the occluded part
    bool fragment = false;  // a whole visible stroke
    bool forward = true;    // runs the source in its own direction
};

// Exact points where paths meet, and the arcs between them.
class JoinGraph {
  public:
    size_t node(const glm::dvec2& p) {
        const auto [it, added] = nodes_.try_emplace(internal::point_key(p), arcs_.size());
        if (added) arcs_.emplace_back();
        return it->second;
    }
    std::optional<size_t> find(const glm::dvec2& p) const {
        const auto it = nodes_.find(internal::point_key(p));
        if (it == nodes_.end()) return std::nullopt;
        return it->second;
    }
    void link(const glm::dvec2& a, const glm::dvec2& b, double length, Arc arc) {
        const size_t na = node(a), nb = node(b);
        arc.length = length;
        arc.to = nb;
        arc.forward = true;
        arcs_[na].push_back(arc);
        arc.to = na;
        arc.forward = false;
        arcs_[nb].push_back(arc);
    }
    const std::vector<Arc>& arcs(size_t n) const { return arcs_[n]; }
    size_t size() const { return arcs_.size(); }

  private:
    std::unordered_map<internal::PointKey, size_t, internal::PointKeyHash> nodes_;
    std::vector<std::vector<Arc>> arcs_;
};

// A stroke end with what last frame drew next to it: every stroke of last frame nearest to at
// least half of the side's samples (near a junction, the side may lie as near to a neighbour as
// to its own stroke, so there may be two).
struct MemoryEnd {
    size_t stroke;
    int end;
    glm::dvec2 p;
    std::vector<SideMemory> memory;  // by id
};

// Appends the points that `arc` reaches to path (its last point is where the arc starts).
void follow(StrokeGeometry& path, const Arc& arc, const std::vector<StrokeGeometry>& strokes,
            const std::vector<StrokeGeometry>& occluded) {
    if (arc.fragment) {
        internal::splice(path, strokes[arc.source], !arc.forward);
        return;
    }
    const StrokeGeometry& o = occluded[arc.source];
    const size_t k = arc.forward ? arc.segment + 1 : arc.segment;
    internal::splice_bridged_segment(path, o.points_px[k], o.points_world[k], o.edges[arc.segment]);
}

}  // namespace

size_t rejoin_split_strokes(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                            OccludedUse& r_use, const StrokeCoherence& coherence, const GapBridgeOptions& options) {
    if (coherence.traces().empty()) return 0;
    const double max_path = kRejoinPathFactor * options.max_gap_px;

    // Open ends of visible strokes and the strokes of last frame along each.
    std::vector<MemoryEnd> ends;
    std::vector<std::vector<glm::dvec2>> sides;
    std::vector<LineKind> kinds;
    for (size_t s = 0; s < r_strokes.size(); ++s) {
        const StrokeGeometry& g = r_strokes[s];
        if (!internal::is_open_visible(g)) continue;
        for (int e = 0; e < 2; ++e) {
            ends.push_back({s, e, g.end_px(e), {}});
            sides.push_back(side_samples(g.points_px, e));
            kinds.push_back(g.kind);
        }
    }
    std::vector<std::vector<SideMemory>> memory = coherence.side_memory(sides, kinds);
    for (size_t i = 0; i < ends.size(); ++i) ends[i].memory = std::move(memory[i]);

    // Paths run along occluded parts and short visible strokes, between exact points.
    JoinGraph graph;
    for (size_t h = 0; h < occluded.size(); ++h) {
        const StrokeGeometry& o = occluded[h];
        if (o.visible || (h < r_use.bridged_whole.size() && r_use.bridged_whole[h])) continue;
        for (size_t k = 0; k + 1 < o.points_px.size(); ++k) {
            graph.link(o.points_px[k], o.points_px[k + 1], glm::length(o.points_px[k + 1] - o.points_px[k]),
                       {.source = h, .segment = k});
        }
    }
    for (size_t s = 0; s < r_strokes.size(); ++s) {
        const StrokeGeometry& g = r_strokes[s];
        if (!internal::is_open_visible(g)) continue;
        const double length = g.length_px();
        if (length <= options.max_gap_px)
            graph.link(g.points_px.front(), g.points_px.back(), length, {.source = s, .fragment = true});
    }
    std::vector<std::vector<size_t>> ends_at(graph.size());
    for (size_t i = 0; i < ends.size(); ++i) {
        if (ends[i].memory.empty()) continue;
        const size_t n = graph.node(ends[i].p);
        if (n >= ends_at.size()) ends_at.resize(n + 1);
        ends_at[n].push_back(i);
    }

    // Every pair of ends joinable by memory, with the shortest path between them.
    struct Join {
        double length;
        size_t a, b;
        std::vector<Arc> path;
        bool fold = false;  // straight across a fold, no exact path
    };
    std::vector<Join> joins;
    for (size_t i = 0; i < ends.size(); ++i) {
        const MemoryEnd& from = ends[i];
        if (from.memory.empty()) continue;
        const size_t start = *graph.find(from.p);
        std::map<size_t, double> dist{{start, 0.0}};
        std::map<size_t, std::pair<size_t, Arc>> came;  // node -> (previous node, arc taken)
        using Item = std::pair<double, size_t>;
        std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
        open.push({0.0, start});
        while (!open.empty()) {
            const auto [d, n] = open.top();
            open.pop();
            if (d > dist[n]) continue;
            for (size_t k = 0; n < ends_at.size() && k < ends_at[n].size(); ++k) {
                const size_t j = ends_at[n][k];
                const MemoryEnd& to = ends[j];
                if (j <= i || to.stroke == from.stroke) continue;
                if (r_strokes[to.stroke].kind != r_strokes[from.stroke].kind) continue;
                if (glm::length(to.p - from.p) > options.max_gap_px ||
                    !continuation_fit(from.memory, to.memory, d, SideHeadings::kAny))
                    continue;
                std::vector<Arc> path;
                for (size_t m = n; m != start; m = came.at(m).first) path.push_back(came.at(m).second);
                std::reverse(path.begin(), path.end());
                joins.push_back({d, i, j, std::move(path)});
            }
            for (const Arc& arc : graph.arcs(n)) {
                if (arc.fragment && arc.source == from.stroke) continue;
                const double nd = d + arc.length;
                if (nd > max_path) continue;
                const auto it = dist.find(arc.to);
                if (it != dist.end() && it->second <= nd) continue;
                dist[arc.to] = nd;
                came[arc.to] = {n, arc};
                open.push({nd, arc.to});
            }
        }
    }
    // Folds: ends whose sides run back over each other, as where a zig-zag silhouette folds back
    // along itself for longer than an exact path is searched, joined straight across. Only ends
    // within max_fold_px of each other can join: each end is compared with those in its grid cell
    // and the eight around it, not with every other end (tens of thousands on a noisy scan).
    internal::PointGrid<size_t> end_grid(std::max(options.max_fold_px * kCellSlack, kMinCellPx));
    for (size_t i = 0; i < ends.size(); ++i) end_grid.add(ends[i].p, i);
    end_grid.sort();
    std::vector<size_t> near;
    for (size_t i = 0; i < ends.size(); ++i) {
        near.clear();
        end_grid.around(ends[i].p, [&](size_t j) {
            if (j > i) near.push_back(j);
        });
        for (size_t j : near) {
            const MemoryEnd &a = ends[i], &b = ends[j];
            const double chord = glm::length(a.p - b.p);
            if (chord > options.max_fold_px || a.stroke == b.stroke) continue;
            if (r_strokes[a.stroke].kind != r_strokes[b.stroke].kind) continue;
            if (!continuation_fit(a.memory, b.memory, chord, SideHeadings::kOpposite)) continue;
            if (side_distance(r_strokes[a.stroke], a.end, r_strokes[b.stroke], b.end) > kFoldTouchPx) continue;
            joins.push_back({chord, i, j, {}, true});
        }
    }
    std::sort(joins.begin(), joins.end(), [](const Join& x, const Join& y) {
        return std::tie(x.fold, x.length, x.a, x.b) < std::tie(y.fold, y.length, y.a, y.b);
    });

    // Exact paths first, then folds; shortest first; each end, fragment and occluded segment is
    // used once.
    internal::UnionFind<size_t> owner(r_strokes.size());  // which stroke each was merged into
    std::vector<uint8_t> consumed(r_strokes.size(), 0);
    std::set<std::pair<size_t, size_t>>& segment_taken = r_use.segments_taken;
    size_t joined = 0;
    for (const Join& join : joins) {
        const MemoryEnd &ea = ends[join.a], &eb = ends[join.b];
        if (consumed[ea.stroke] || consumed[eb.stroke]) continue;
        const size_t sa = owner.find(ea.stroke), sb = owner.find(eb.stroke);
        if (sa == sb) continue;
        bool free = true;
        for (const Arc& arc : join.path) {
            if (arc.fragment) {
                // Still a stroke of its own, and not one of the two being joined.
                free =
                    free && !consumed[arc.source] && owner.is_root(arc.source) && arc.source != sa && arc.source != sb;
            } else {
                free = free && !segment_taken.contains({arc.source, arc.segment});
            }
        }
        StrokeGeometry& a = r_strokes[sa];
        StrokeGeometry& b = r_strokes[sb];
        if (!free || !internal::orient_for_splice(a, ea.p, b, eb.p)) continue;
        StrokeGeometry path;  // from a's end to b's
        path.pure_stroke_count = 0;
        path.points_px.push_back(ea.p);
        path.points_world.push_back(a.points_world.back());
        for (const Arc& arc : join.path) {
            follow(path, arc, r_strokes, occluded);
            if (arc.fragment) {
                consumed[arc.source] = 1;
                owner.merge_into(sa, arc.source);
                r_strokes[arc.source] = StrokeGeometry{};
            } else {
                segment_taken.insert({arc.source, arc.segment});
            }
        }
        if (join.fold) {
            // One segment, drawn across like an occluded one; it lies along the stroke's last edge.
            internal::splice_bridged_segment(path, eb.p, b.points_world.front(), a.edges.back());
        }
        if (path.edges.size() > 0) internal::splice(a, path);
        internal::splice(a, b);
        owner.merge_into(sa, sb);
        b = StrokeGeometry{};
        ++joined;
    }
    return joined;
}

}  // namespace inkline::core
