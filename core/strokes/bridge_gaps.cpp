// SPDX-License-Identifier: MIT
#include "core/strokes/bridge_gaps.h"

#include <array>
#include <glm/geometric.hpp>
#include <map>
#include <optional>
#include <unordered_map>

#include "core/internal/union_find.h"
#include "core/strokes/internal/splice.h"

namespace inkline::core {
namespace {

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

}  // namespace

size_t bridge_hidden_gaps(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                          const StrokeCoherence& coherence, const GapBridgeOptions& options,
                          std::vector<uint8_t>& r_bridged_whole) {
    r_bridged_whole.assign(occluded.size(), 0);
    // Open ends of visible strokes by their exact point: a gap's ends are the same cut points.
    std::unordered_map<internal::PointKey, std::vector<EndRef>, internal::PointKeyHash> ends;
    for (size_t s = 0; s < r_strokes.size(); ++s) {
        const StrokeGeometry& g = r_strokes[s];
        if (!internal::is_open_visible(g)) continue;
        ends[internal::point_key(g.points_px.front())].push_back({s, 0});
        ends[internal::point_key(g.points_px.back())].push_back({s, 1});
    }
    auto only_end = [&](const glm::dvec2& p, LineKind kind) -> std::optional<EndRef> {
        auto it = ends.find(internal::point_key(p));
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
        const int64_t id_a =
            majority({near_id.begin() + std::ptrdiff_t(spans[i][0]), near_id.begin() + std::ptrdiff_t(spans[i][1])});
        const int64_t id_b =
            majority({near_id.begin() + std::ptrdiff_t(spans[i][1]), near_id.begin() + std::ptrdiff_t(spans[i][2])});
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
        if (!internal::orient_for_splice(a, p0, b, p1)) continue;
        internal::splice_bridged(a, occluded[gap.occluded]);
        internal::splice(a, b);
        owner.merge_into(sa, sb);
        b = StrokeGeometry{};  // merged into a
        r_bridged_whole[gap.occluded] = 1;
        ++bridged;
    }
    return bridged;
}

}  // namespace inkline::core
