// SPDX-License-Identifier: MIT
#include "core/strokes/t_junctions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "core/internal/point_grid.h"
#include "core/strokes/internal/splice.h"

namespace inkline::core {
namespace {

// A stroke that ends this close (px) to another's interior point ends on it: a T-junction. More
// than kSideSpacingPx, as an end on a line may fall between points of it spaced a few px apart.
constexpr double kTeeReachPx = 3.0;

// Interior points of open visible strokes on a grid of kTeeReachPx cells.
class InteriorGrid {
  public:
    explicit InteriorGrid(const std::vector<StrokeGeometry>& strokes) : strokes_(strokes), grid_(kTeeReachPx) {
        for (size_t s = 0; s < strokes.size(); ++s) {
            const StrokeGeometry& g = strokes[s];
            if (!internal::is_open_visible(g)) continue;
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
            if (d <= kTeeReachPx) hits.push_back({stroke, point, d});
        });
        // Each stroke's nearest point, the lower one of a tie; sorted, not searched for, as
        // thousands of strokes may pass by one point.
        std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
            return std::tie(a.stroke, a.distance, a.point) < std::tie(b.stroke, b.distance, b.point);
        });
        hits.erase(std::unique(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.stroke == b.stroke; }),
                   hits.end());
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
            if (!internal::is_open_visible(g)) continue;
            for (int e = 0; e < 2; ++e) {
                if (g.ends[size_t(e)] != StrokeEnd::kJunction) continue;
                for (const InteriorGrid::Hit& hit : grid.near(g.end_px(e), s, g.kind))
                    tees.push_back({s, e, hit.stroke, hit.point, hit.distance});
            }
        }
    }
    if (tees.empty()) return 0;

    // Last frame's strokes along the three sides of each: the ending stroke (once for all its
    // end's candidates), and the crossing stroke toward its first and toward its last point
    // (once for each point: where thousands of strokes cross, every end near there finds the
    // same points of them).
    std::vector<std::vector<glm::dvec2>> sides;
    std::vector<LineKind> kinds;
    std::vector<std::array<size_t, 3>> side_of(tees.size());
    std::map<std::pair<size_t, size_t>, size_t> crossing_sides;  // (other, at) -> its first side
    for (size_t i = 0; i < tees.size(); ++i) {
        const Tee& t = tees[i];
        const std::vector<glm::dvec2>& x = r_strokes[t.other].points_px;
        const bool same_end = i > 0 && tees[i - 1].stroke == t.stroke && tees[i - 1].end == t.end;
        if (!same_end) sides.push_back(side_samples(r_strokes[t.stroke].points_px, t.end));
        side_of[i][0] = same_end ? side_of[i - 1][0] : sides.size() - 1;
        const auto [it, added] = crossing_sides.try_emplace({t.other, t.at}, sides.size());
        if (added) {
            sides.push_back(side_samples({x.begin(), x.begin() + std::ptrdiff_t(t.at) + 1}, 1));
            sides.push_back(side_samples({x.begin() + std::ptrdiff_t(t.at), x.end()}, 0));
        }
        side_of[i][1] = it->second;
        side_of[i][2] = it->second + 1;
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
        const glm::dvec2 p = g.end_px(t.end);
        if (g.ends[size_t(t.end)] != StrokeEnd::kJunction || glm::length(x.points_px[t.at] - p) != t.jump) continue;

        const size_t last = x.points_px.size() - 1;
        StrokeGeometry kept = keep_before ? internal::part_of(x, 0, t.at) : internal::part_of(x, t.at, last);
        StrokeGeometry rest = keep_before ? internal::part_of(x, t.at, last) : internal::part_of(x, 0, t.at);
        if (rest.unbridged_length_px() > options.max_tee_rest_px) continue;
        // Where last frame's stroke ran on through the crossing stroke more closely, the crossing
        // stroke stays whole; unless the rest leads on from the junction beside the ending stroke,
        // along last frame's stroke, and stops sooner: a stub beside the branch it took.
        if (fit_through && *fit_through <= (keep_before ? *fit_before : *fit_after)) {
            const bool stub = continuation_fit(ends_side, keep_before ? after : before, t.jump, SideHeadings::kSame) &&
                              rest.unbridged_length_px() < g.unbridged_length_px();
            if (!stub) continue;
        }
        if (!keep_before) kept.reverse();  // now it ends at the cut
        StrokeGeometry ending = std::move(g);
        if (t.end == 1) ending.reverse();  // now it starts at the junction

        // kept -> the jump, drawn across like an occluded segment -> ending.
        internal::splice_bridged_segment(kept, ending.points_px.front(), ending.points_world.front(),
                                         ending.edges.front());
        internal::splice(kept, ending);
        x = std::move(kept);
        g = StrokeGeometry{};
        r_strokes.push_back(std::move(rest));
        ++joined;
    }
    return joined;
}

}  // namespace inkline::core
