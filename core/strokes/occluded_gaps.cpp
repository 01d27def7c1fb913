// SPDX-License-Identifier: MIT
#include "core/strokes/occluded_gaps.h"

namespace inkline::core {

GapBridgeOptions gap_bridge_options(double width_max_px) {
    GapBridgeOptions o;
    o.max_gap_px = 2.0 * width_max_px;
    o.new_gap_px = 0.5 * o.max_gap_px;
    o.split_gap_px = 0.25 * o.max_gap_px;
    o.max_fold_px = 3.0 * o.max_gap_px;
    o.max_tee_rest_px = 2.5 * o.max_gap_px;
    return o;
}

std::vector<StrokeGeometry> occluded_parts(const std::vector<Polyline>& occluded) {
    std::vector<StrokeGeometry> out;
    out.reserve(occluded.size());
    for (const Polyline& line : occluded) out.push_back(geometry_of(line));
    return out;
}

std::vector<Polyline> occluded_left(const std::vector<Polyline>& occluded, const OccludedUse& use) {
    std::vector<Polyline> out;
    for (size_t h = 0; h < occluded.size(); ++h) {
        const Polyline& line = occluded[h];
        if (h < use.bridged_whole.size() && use.bridged_whole[h]) continue;
        const auto first = use.segments_taken.lower_bound({h, 0});
        if (first == use.segments_taken.end() || first->first != h) {
            out.push_back(line);
            continue;
        }
        // Runs of untaken segments; a loop cut open starts after its first taken segment.
        const size_t n = line.edges.size();
        auto taken = [&](size_t k) { return use.segments_taken.contains({h, k}); };
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
