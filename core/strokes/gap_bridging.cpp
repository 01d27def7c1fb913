// SPDX-License-Identifier: MIT
#include "core/strokes/gap_bridging.h"

#include <algorithm>
#include <array>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <set>
#include <tuple>

#include "core/internal/point_grid.h"
#include "core/internal/union_find.h"
#include "core/strokes/stroke_path.h"

namespace inkline::core {
namespace {

// A path that joins two parts of last frame's stroke again may run this many times max_gap_px
// (hidden folds of a zig-zag silhouette run back and forth; the chord is bounded on its own).
constexpr double kRejoinPathFactor = 4.0;
// Two sides that come this close (px) within kSideReachPx of their ends run over each other: a
// fold, not two lines that merely end near each other.
constexpr double kFoldTouchPx = 1.0;
// A stroke that ends this close (px) to another's interior point ends on it: a T-junction. More
// than kSideSpacingPx, as an end on a line may fall between points of it spaced a few px apart.
constexpr double kTeeReachPx = 3.0;
// Grid cells for "all ends within d px" are d times this, so that rounding in the cell index
// never leaves out a point exactly d away; and never smaller than kMinCellPx (px), so that a tiny
// d does not make the cell index (an int, over coordinates clamped to 1e8 px) overflow.
constexpr double kCellSlack = 1.0 + 1e-6;
constexpr double kMinCellPx = 1.0;

using Key = std::pair<double, double>;
Key key_of(const glm::dvec2& p) { return {p.x, p.y}; }

struct EndRef {
    size_t stroke;
    int end;  // 0: first point, 1: last point
};

// The id most of the side's samples lie nearest to (-1 when none lies near any); ties go to the
// lower id.
int64_t majority(const std::vector<int64_t>& ids) {
    std::map<int64_t, size_t> votes;
    for (int64_t id : ids) {
        if (id >= 0) ++votes[id];
    }
    int64_t best = -1;
    size_t most = 0;
    for (const auto& [id, n] : votes) {
        if (n > most) best = id, most = n;
    }
    return best;
}

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

// Appends `piece` (its first point equal to out's last) to out; hidden marks every segment of
// the piece as occluded.
void append(StrokeGeometry& out, const StrokeGeometry& piece, bool hidden) {
    out.hidden.resize(out.edges.size(), 0);
    out.points_px.insert(out.points_px.end(), piece.points_px.begin() + 1, piece.points_px.end());
    out.points_world.insert(out.points_world.end(), piece.points_world.begin() + 1, piece.points_world.end());
    out.edges.insert(out.edges.end(), piece.edges.begin(), piece.edges.end());
    if (hidden) {
        out.hidden.resize(out.edges.size(), 1);
    } else {
        std::vector<uint8_t> h = piece.hidden;
        h.resize(piece.edges.size(), 0);
        out.hidden.insert(out.hidden.end(), h.begin(), h.end());
    }
    out.pure_strokes += piece.pure_strokes;
}

}  // namespace

std::vector<StrokeGeometry> occluded_runs(const std::vector<Polyline>& occluded) {
    std::vector<StrokeGeometry> out;
    out.reserve(occluded.size());
    for (const Polyline& line : occluded) {
        StrokeGeometry g;
        g.kind = line.kind;
        g.visible = line.visible;
        g.closed = line.closed;
        g.points_px = line.points_px;
        g.points_world = line.points_world;
        g.edges = line.edges;
        out.push_back(std::move(g));
    }
    return out;
}

GapBridgeOptions gap_bridge_options(double width_max_px) {
    GapBridgeOptions o;
    o.max_gap_px = 2.0 * width_max_px;
    o.new_gap_px = 0.5 * o.max_gap_px;
    o.split_gap_px = 0.25 * o.max_gap_px;
    o.max_fold_px = 3.0 * o.max_gap_px;
    o.max_tee_rest_px = 2.5 * o.max_gap_px;
    return o;
}

size_t bridge_hidden_gaps(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                          const StrokeCoherence& coherence, const GapBridgeOptions& options,
                          std::vector<uint8_t>& r_used) {
    r_used.assign(occluded.size(), 0);
    // Open ends of visible strokes by their exact point: a gap's ends are the same cut points.
    std::map<Key, std::vector<EndRef>> ends;
    for (size_t s = 0; s < r_strokes.size(); ++s) {
        const StrokeGeometry& g = r_strokes[s];
        if (!g.visible || g.closed || g.points_px.size() < 2) continue;
        ends[key_of(g.points_px.front())].push_back({s, 0});
        ends[key_of(g.points_px.back())].push_back({s, 1});
    }
    auto only_end = [&](const glm::dvec2& p, LineKind kind) -> std::optional<EndRef> {
        auto it = ends.find(key_of(p));
        if (it == ends.end() || it->second.size() != 1) return std::nullopt;  // none, or a junction
        const EndRef e = it->second.front();
        if (r_strokes[e.stroke].kind != kind) return std::nullopt;
        return e;
    };

    // Candidate gaps: short occluded strokes between two visible ends of their kind.
    struct Gap {
        size_t occluded;
        EndRef a, b;  // the visible end at the gap's first point, and at its last
        double chord;
    };
    std::vector<Gap> gaps;
    std::vector<glm::dvec2> queries;
    std::vector<std::array<size_t, 3>> spans;  // per gap: first query of side a, of side b, end
    for (size_t h = 0; h < occluded.size(); ++h) {
        const StrokeGeometry& g = occluded[h];
        if (g.visible || g.closed || g.points_px.size() < 2) continue;
        const double chord = glm::length(g.points_px.back() - g.points_px.front());
        if (chord > options.max_gap_px || g.length_px() > 2.0 * options.max_gap_px) continue;
        const std::optional<EndRef> a = only_end(g.points_px.front(), g.kind);
        const std::optional<EndRef> b = only_end(g.points_px.back(), g.kind);
        if (!a || !b || (a->stroke == b->stroke && a->end == b->end)) continue;
        gaps.push_back({h, *a, *b, chord});
        const size_t first = queries.size();
        for (const glm::dvec2& p : side_samples(r_strokes[a->stroke].points_px, a->end)) queries.push_back(p);
        const size_t mid = queries.size();
        for (const glm::dvec2& p : side_samples(r_strokes[b->stroke].points_px, b->end)) queries.push_back(p);
        spans.push_back({first, mid, queries.size()});
    }
    if (gaps.empty()) return 0;
    // Only one kind of line per gap matters, but the lookup is per kind: ask per kind once.
    std::vector<int64_t> near_id(queries.size(), -1);
    for (size_t k = 0; k < kLineKindCount; ++k) {
        std::vector<glm::dvec2> pts;
        std::vector<size_t> where;
        for (size_t i = 0; i < gaps.size(); ++i) {
            if (size_t(occluded[gaps[i].occluded].kind) != k) continue;
            for (size_t q = spans[i][0]; q < spans[i][2]; ++q) pts.push_back(queries[q]), where.push_back(q);
        }
        if (pts.empty()) continue;
        const std::vector<int64_t> ids = coherence.nearest_visible_ids(pts, LineKind(k));
        for (size_t j = 0; j < ids.size(); ++j) near_id[where[j]] = ids[j];
    }

    // Which stroke each original stroke has been merged into, as strokes merge in gap order.
    internal::UnionFind<size_t> owner(r_strokes.size());
    size_t bridged = 0;
    for (size_t i = 0; i < gaps.size(); ++i) {
        const Gap& gap = gaps[i];
        // Hysteresis: how last frame drew this place decides how wide a gap is bridged.
        const int64_t id_a = majority({near_id.begin() + std::ptrdiff_t(spans[i][0]),
                                       near_id.begin() + std::ptrdiff_t(spans[i][1])});
        const int64_t id_b = majority({near_id.begin() + std::ptrdiff_t(spans[i][1]),
                                       near_id.begin() + std::ptrdiff_t(spans[i][2])});
        double limit = options.new_gap_px;
        if (id_a >= 0 && id_a == id_b) limit = options.max_gap_px;
        if (id_a >= 0 && id_b >= 0 && id_a != id_b) limit = options.split_gap_px;
        if (gap.chord > limit) continue;

        // The strokes now holding each side, oriented a -> gap -> b. A gap between a stroke's
        // own two ends stays open: a loop closed only through a flickering dip would gain and
        // lose its start point (and loop-ness) from frame to frame.
        const size_t sa = owner.find(gap.a.stroke), sb = owner.find(gap.b.stroke);
        if (sa == sb) continue;
        StrokeGeometry& a = r_strokes[sa];
        StrokeGeometry& b = r_strokes[sb];
        const glm::dvec2 p0 = occluded[gap.occluded].points_px.front();
        const glm::dvec2 p1 = occluded[gap.occluded].points_px.back();
        // An end taken by an earlier gap (two occluded parts leaving one point) is gone.
        const bool a_back = a.points_px.back() == p0, b_front = b.points_px.front() == p1;
        if ((!a_back && a.points_px.front() != p0) || (!b_front && b.points_px.back() != p1)) continue;
        if (!a_back) a.reverse();
        if (!b_front) b.reverse();
        append(a, occluded[gap.occluded], true);
        a.ends[1] = b.ends[1];
        append(a, b, false);
        owner.merge_into(sa, sb);
        b = StrokeGeometry{};  // merged into a
        r_used[gap.occluded] = 1;
        ++bridged;
    }
    return bridged;
}

namespace {

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
        const auto [it, added] = nodes_.try_emplace(key_of(p), arcs_.size());
        if (added) arcs_.emplace_back();
        return it->second;
    }
    std::optional<size_t> find(const glm::dvec2& p) const {
        const auto it = nodes_.find(key_of(p));
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
    std::map<Key, size_t> nodes_;
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
    if (!arc.fragment) {
        const StrokeGeometry& o = occluded[arc.source];
        const size_t k = arc.forward ? arc.segment + 1 : arc.segment;
        path.points_px.push_back(o.points_px[k]);
        path.points_world.push_back(o.points_world[k]);
        path.edges.push_back(o.edges[arc.segment]);
        path.hidden.push_back(1);
        return;
    }
    StrokeGeometry f = strokes[arc.source];
    if (!arc.forward) f.reverse();
    f.hidden.resize(f.edges.size(), 0);
    path.points_px.insert(path.points_px.end(), f.points_px.begin() + 1, f.points_px.end());
    path.points_world.insert(path.points_world.end(), f.points_world.begin() + 1, f.points_world.end());
    path.edges.insert(path.edges.end(), f.edges.begin(), f.edges.end());
    path.hidden.insert(path.hidden.end(), f.hidden.begin(), f.hidden.end());
    path.pure_strokes += f.pure_strokes;
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
        if (!g.visible || g.closed || g.points_px.size() < 2) continue;
        for (int e = 0; e < 2; ++e) {
            ends.push_back({s, e, e == 0 ? g.points_px.front() : g.points_px.back(), {}});
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
        if (o.visible || (h < r_use.runs.size() && r_use.runs[h])) continue;
        for (size_t k = 0; k + 1 < o.points_px.size(); ++k) {
            graph.link(o.points_px[k], o.points_px[k + 1], glm::length(o.points_px[k + 1] - o.points_px[k]),
                       {.source = h, .segment = k});
        }
    }
    for (size_t s = 0; s < r_strokes.size(); ++s) {
        const StrokeGeometry& g = r_strokes[s];
        if (!g.visible || g.closed || g.points_px.size() < 2) continue;
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
                if (glm::length(to.p - from.p) > options.max_gap_px || !continuation_fit(from.memory, to.memory, d, SideHeadings::kAny)) continue;
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
    std::set<std::pair<size_t, size_t>>& segment_taken = r_use.segments;
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
                free = free && !consumed[arc.source] && owner.is_root(arc.source) && arc.source != sa &&
                       arc.source != sb;
            } else {
                free = free && !segment_taken.contains({arc.source, arc.segment});
            }
        }
        StrokeGeometry& a = r_strokes[sa];
        StrokeGeometry& b = r_strokes[sb];
        const bool a_back = a.points_px.back() == ea.p, b_front = b.points_px.front() == eb.p;
        if (!free || (!a_back && a.points_px.front() != ea.p) || (!b_front && b.points_px.back() != eb.p)) continue;
        if (!a_back) a.reverse();
        if (!b_front) b.reverse();
        StrokeGeometry path;
        path.pure_strokes = 0;
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
            path.points_px.push_back(eb.p);
            path.points_world.push_back(b.points_world.front());
            path.edges.push_back(a.edges.back());
            path.hidden.push_back(1);
        }
        if (path.edges.size() > 0) append(a, path, false);
        a.ends[1] = b.ends[1];
        append(a, b, false);
        owner.merge_into(sa, sb);
        b = StrokeGeometry{};
        ++joined;
    }
    return joined;
}

namespace {

// Points [begin, end] of a stroke as a stroke of their own: cut ends are junctions.
StrokeGeometry part_of(const StrokeGeometry& g, size_t begin, size_t end) {
    StrokeGeometry out;
    out.kind = g.kind;
    out.visible = g.visible;
    out.points_px.assign(g.points_px.begin() + std::ptrdiff_t(begin), g.points_px.begin() + std::ptrdiff_t(end) + 1);
    out.points_world.assign(g.points_world.begin() + std::ptrdiff_t(begin),
                            g.points_world.begin() + std::ptrdiff_t(end) + 1);
    out.edges.assign(g.edges.begin() + std::ptrdiff_t(begin), g.edges.begin() + std::ptrdiff_t(end));
    if (!g.hidden.empty()) {
        std::vector<uint8_t> h = g.hidden;
        h.resize(g.edges.size(), 0);
        out.hidden.assign(h.begin() + std::ptrdiff_t(begin), h.begin() + std::ptrdiff_t(end));
    }
    out.ends = {begin == 0 ? g.ends[0] : StrokeEnd::kJunction,
                end + 1 == g.points_px.size() ? g.ends[1] : StrokeEnd::kJunction};
    return out;
}

// Interior points of open visible strokes on a grid of kTeeReachPx cells.
class InteriorGrid {
  public:
    explicit InteriorGrid(const std::vector<StrokeGeometry>& strokes) : strokes_(strokes), grid_(kTeeReachPx) {
        for (size_t s = 0; s < strokes.size(); ++s) {
            const StrokeGeometry& g = strokes[s];
            if (!g.visible || g.closed) continue;
            for (size_t k = 1; k + 1 < g.points_px.size(); ++k) grid_.add(g.points_px[k], {s, k});
        }
        grid_.sort();
    }

    struct Hit {
        size_t stroke = size_t(-1), point = 0;
        double distance = HUGE_VAL;
    };
    // For each stroke other than `self`, of the kind, with an interior point within kTeeReachPx
    // of p: the nearest such point. Nearest first.
    std::vector<Hit> near(const glm::dvec2& p, size_t self, LineKind kind) const {
        std::vector<Hit> hits;
        grid_.around(p, [&](const std::pair<size_t, size_t>& sk) {
            const auto [stroke, point] = sk;
            if (stroke == self || strokes_[stroke].kind != kind) return;
            const double d = glm::length(strokes_[stroke].points_px[point] - p);
            if (d > kTeeReachPx) return;
            const auto same = std::find_if(hits.begin(), hits.end(), [&, wanted = stroke](const Hit& h) { return h.stroke == wanted; });
            if (same == hits.end()) {
                hits.push_back({stroke, point, d});
            } else if (std::tie(d, point) < std::tie(same->distance, same->point)) {
                *same = {stroke, point, d};
            }
        });
        std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
            return std::tie(a.distance, a.stroke) < std::tie(b.distance, b.stroke);
        });
        return hits;
    }

  private:
    const std::vector<StrokeGeometry>& strokes_;
    internal::PointGrid<std::pair<size_t, size_t>> grid_;  // (stroke, point)
};

}  // namespace

size_t join_at_t_junctions(std::vector<StrokeGeometry>& r_strokes, const StrokeCoherence& coherence,
                           const GapBridgeOptions& options) {
    if (coherence.traces().empty()) return 0;
    // Candidate T-junctions: an open end typed C, and for each other visible stroke of its kind
    // that passes by, its nearest interior point (in a tangle, the nearest stroke may be a
    // fragment, and the line the end meets one a little farther).
    struct Tee {
        size_t stroke;  // the ending stroke
        int end;
        size_t other;  // the stroke it ends on
        size_t at;     // the interior point of `other` where that is cut
        double jump;   // px from the end to that point
    };
    std::vector<Tee> tees;
    {
        const InteriorGrid grid(r_strokes);
        for (size_t s = 0; s < r_strokes.size(); ++s) {
            const StrokeGeometry& g = r_strokes[s];
            if (!g.visible || g.closed || g.points_px.size() < 2) continue;
            for (int e = 0; e < 2; ++e) {
                if (g.ends[size_t(e)] != StrokeEnd::kJunction) continue;
                for (const InteriorGrid::Hit& hit : grid.near(e == 0 ? g.points_px.front() : g.points_px.back(), s, g.kind))
                    tees.push_back({s, e, hit.stroke, hit.point, hit.distance});
            }
        }
    }
    if (tees.empty()) return 0;

    // Last frame's strokes along the three sides of each: the ending stroke (once for all its
    // end's candidates), and the crossing stroke toward its first and toward its last point.
    std::vector<std::vector<glm::dvec2>> sides;
    std::vector<LineKind> kinds;
    std::vector<std::array<size_t, 3>> side_of(tees.size());
    for (size_t i = 0; i < tees.size(); ++i) {
        const Tee& t = tees[i];
        const std::vector<glm::dvec2>& x = r_strokes[t.other].points_px;
        const bool same_end = i > 0 && tees[i - 1].stroke == t.stroke && tees[i - 1].end == t.end;
        if (!same_end) sides.push_back(side_samples(r_strokes[t.stroke].points_px, t.end));
        side_of[i][0] = same_end ? side_of[i - 1][0] : sides.size() - 1;
        sides.push_back(side_samples({x.begin(), x.begin() + std::ptrdiff_t(t.at) + 1}, 1));
        side_of[i][1] = sides.size() - 1;
        sides.push_back(side_samples({x.begin() + std::ptrdiff_t(t.at), x.end()}, 0));
        side_of[i][2] = sides.size() - 1;
        kinds.resize(sides.size(), r_strokes[t.stroke].kind);
    }
    const std::vector<std::vector<SideMemory>> memory = coherence.side_memory(sides, kinds);

    size_t joined = 0;
    for (size_t i = 0; i < tees.size(); ++i) {
        const Tee& t = tees[i];
        // The part of the crossing stroke that last frame's stroke continued into from the
        // ending one, more closely than the crossing stroke continued through itself.
        const std::vector<SideMemory>& ends_side = memory[side_of[i][0]];
        const std::vector<SideMemory>& before = memory[side_of[i][1]];
        const std::vector<SideMemory>& after = memory[side_of[i][2]];
        const std::optional<double> fit_before = continuation_fit(ends_side, before, t.jump, SideHeadings::kOpposite);
        const std::optional<double> fit_after = continuation_fit(ends_side, after, t.jump, SideHeadings::kOpposite);
        const std::optional<double> fit_through = continuation_fit(before, after, 0.0, SideHeadings::kOpposite);
        if (!fit_before && !fit_after) continue;
        const bool keep_before = fit_before && (!fit_after || *fit_before <= *fit_after);

        // Strokes change as tees are joined: this one only while both are still as found.
        StrokeGeometry& g = r_strokes[t.stroke];
        StrokeGeometry& x = r_strokes[t.other];
        if (g.points_px.size() < 2 || x.closed || t.at + 1 >= x.points_px.size()) continue;
        const glm::dvec2 p = t.end == 0 ? g.points_px.front() : g.points_px.back();
        if (g.ends[size_t(t.end)] != StrokeEnd::kJunction || glm::length(x.points_px[t.at] - p) != t.jump) continue;

        StrokeGeometry kept = keep_before ? part_of(x, 0, t.at) : part_of(x, t.at, x.points_px.size() - 1);
        StrokeGeometry rest = keep_before ? part_of(x, t.at, x.points_px.size() - 1) : part_of(x, 0, t.at);
        if (rest.visible_length_px() > options.max_tee_rest_px) continue;
        // Where last frame's stroke ran on through the crossing stroke more closely, the crossing
        // stroke stays whole; unless the rest leads on from the junction beside the ending stroke,
        // along last frame's stroke, and stops sooner: a stub beside the branch it took.
        if (fit_through && *fit_through <= (keep_before ? *fit_before : *fit_after)) {
            const bool stub = continuation_fit(ends_side, keep_before ? after : before, t.jump, SideHeadings::kSame) &&
                              rest.visible_length_px() < g.visible_length_px();
            if (!stub) continue;
        }
        if (!keep_before) kept.reverse();  // now it ends at the cut
        StrokeGeometry ending = std::move(g);
        if (t.end == 1) ending.reverse();  // now it starts at the junction

        // kept -> the jump, drawn across like an occluded segment -> ending.
        StrokeGeometry jump;
        jump.pure_strokes = 0;
        jump.points_px = {kept.points_px.back(), ending.points_px.front()};
        jump.points_world = {kept.points_world.back(), ending.points_world.front()};
        jump.edges = {ending.edges.front()};
        append(kept, jump, true);
        kept.ends[1] = ending.ends[1];
        append(kept, ending, false);
        x = std::move(kept);
        g = StrokeGeometry{};
        r_strokes.push_back(std::move(rest));
        ++joined;
    }
    return joined;
}

namespace {

// Rounding of a sum of n segment lengths, relative to the whole, is below n ulp; this many ulp
// per point cover that and the rounding of the distances compared with it.
constexpr double kArcUlpsPerPoint = 4.0;

// The turn (deg) at point k of pts: between the chords to the nearest points at least `scale_px`
// away before and after it; nullopt where either side is shorter. Every point after b and before
// k, and after k and before f, lies nearer than scale_px to point k (the search starts there).
std::optional<double> coarse_turn_deg(const std::vector<glm::dvec2>& pts, size_t k, double scale_px, size_t b,
                                      size_t f) {
    while (b > 0 && glm::length(pts[b] - pts[k]) < scale_px) --b;
    while (f + 1 < pts.size() && glm::length(pts[f] - pts[k]) < scale_px) ++f;
    const glm::dvec2 in = pts[k] - pts[b], out = pts[f] - pts[k];
    if (glm::length(in) < scale_px || glm::length(out) < scale_px) return std::nullopt;
    const double c = glm::dot(in, out) / (glm::length(in) * glm::length(out));
    return glm::degrees(std::acos(std::clamp(c, -1.0, 1.0)));
}

}  // namespace

size_t split_at_reversals(std::vector<StrokeGeometry>& r_strokes, double scale_px, double angle_deg) {
    size_t cuts = 0;
    const size_t count = r_strokes.size();
    for (size_t s = 0; s < count; ++s) {
        if (r_strokes[s].closed || r_strokes[s].points_px.size() < 3) continue;
        // The points the stroke is drawn through (a bridged gap's inner points left out).
        const StrokeGeometry& g = r_strokes[s];
        const std::vector<size_t> drawn = g.drawn_indices();
        std::vector<glm::dvec2> pts;
        for (size_t k : drawn) pts.push_back(g.points_px[k]);
        if (pts.size() < 3) continue;
        // Where the search for the points scale_px away starts: points less than scale_px along
        // the stroke from k are nearer than that, so they are passed over at once (a stroke of
        // densely spaced points would otherwise be walked scale_px both ways from every point).
        // The margin covers the rounding of the arc-length sums.
        std::vector<double> arc(pts.size(), 0.0);
        for (size_t i = 1; i < pts.size(); ++i) arc[i] = arc[i - 1] + glm::length(pts[i] - pts[i - 1]);
        const double within = scale_px - kArcUlpsPerPoint * std::numeric_limits<double>::epsilon() *
                                             double(pts.size() + 8) * (arc.back() + scale_px);
        size_t lo = 0, hi = 0;  // first point, and last point, less than `within` along from k
        // The sharpest point of each run of points turning more than angle_deg.
        std::vector<size_t> at;
        double best = 0.0;
        size_t best_k = 0;
        for (size_t i = 0; i <= pts.size(); ++i) {
            std::optional<double> turn;
            if (i < pts.size()) {
                size_t b = i, f = i;
                if (within > 0.0) {
                    while (arc[i] - arc[lo] >= within) ++lo;
                    hi = std::max(hi, i);
                    while (hi + 1 < pts.size() && arc[hi + 1] - arc[i] < within) ++hi;
                    b = lo > 0 ? lo - 1 : 0;
                    f = std::min(hi + 1, pts.size() - 1);
                }
                turn = coarse_turn_deg(pts, i, scale_px, b, f);
            }
            if (turn && *turn > angle_deg) {
                if (*turn > best) best = *turn, best_k = drawn[i];
            } else if (best > 0.0) {
                at.push_back(best_k);
                best = 0.0;
            }
        }
        if (at.empty()) continue;
        StrokeGeometry whole = std::move(r_strokes[s]);
        size_t begin = 0;
        for (size_t i = 0; i <= at.size(); ++i) {
            const size_t end = i < at.size() ? at[i] : whole.points_px.size() - 1;
            StrokeGeometry piece = part_of(whole, begin, end);
            if (begin > 0) piece.ends[0] = StrokeEnd::kCorner;
            if (i < at.size()) piece.ends[1] = StrokeEnd::kCorner;
            if (i == 0) {
                r_strokes[s] = std::move(piece);
            } else {
                r_strokes.push_back(std::move(piece));
            }
            begin = end;
        }
        cuts += at.size();
    }
    return cuts;
}

std::vector<Polyline> occluded_left(const std::vector<Polyline>& occluded, const OccludedUse& use) {
    std::vector<Polyline> out;
    for (size_t h = 0; h < occluded.size(); ++h) {
        const Polyline& line = occluded[h];
        if (h < use.runs.size() && use.runs[h]) continue;
        const auto first = use.segments.lower_bound({h, 0});
        if (first == use.segments.end() || first->first != h) {
            out.push_back(line);
            continue;
        }
        // Runs of untaken segments; a loop cut open starts after its first taken segment.
        const size_t n = line.edges.size();
        auto taken = [&](size_t k) { return use.segments.contains({h, k}); };
        Polyline piece;
        auto flush = [&] {
            if (!piece.edges.empty()) out.push_back(std::move(piece));
            piece = Polyline{};
        };
        const size_t start = line.closed ? first->second + 1 : 0;
        for (size_t i = 0; i < n; ++i) {
            const size_t k = (start + i) % n;
            if (taken(k)) {
                flush();
                continue;
            }
            if (piece.edges.empty()) {
                piece.id = line.id;
                piece.kind = line.kind;
                piece.visible = line.visible;
                piece.points_px.push_back(line.points_px[k]);
                piece.points_world.push_back(line.points_world[k]);
            }
            piece.points_px.push_back(line.points_px[k + 1]);
            piece.points_world.push_back(line.points_world[k + 1]);
            piece.edges.push_back(line.edges[k]);
        }
        flush();
    }
    return out;
}

}  // namespace inkline::core
