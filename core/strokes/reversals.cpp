// SPDX-License-Identifier: MIT
#include "core/strokes/reversals.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <optional>
#include <utility>

#include "core/strokes/internal/splice.h"

namespace inkline::core {
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
            StrokeGeometry piece = internal::part_of(whole, begin, end);
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

}  // namespace inkline::core
