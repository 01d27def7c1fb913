// SPDX-License-Identifier: MIT
#include "core/strokes/stroke_geometry.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <utility>

namespace inkline::core {

const char* stroke_end_name(StrokeEnd end) {
    switch (end) {
        case StrokeEnd::kFree:
            return "S";
        case StrokeEnd::kCorner:
            return "A";
        case StrokeEnd::kJunction:
            return "C";
        case StrokeEnd::kLoop:
            return "L";
    }
    return "?";
}

double StrokeGeometry::length_px() const {
    double len = 0.0;
    for (size_t i = 1; i < points_px.size(); ++i) len += glm::length(points_px[i] - points_px[i - 1]);
    return len;
}

double StrokeGeometry::unbridged_length_px() const {
    double len = 0.0;
    for (size_t i = 1; i < points_px.size(); ++i) {
        if (i - 1 >= bridged.size() || !bridged[i - 1]) len += glm::length(points_px[i] - points_px[i - 1]);
    }
    return len;
}

std::vector<size_t> StrokeGeometry::drawn_indices() const {
    std::vector<size_t> out;
    for (size_t k = 0; k < points_px.size(); ++k) {
        const bool bridged_before = k > 0 && k - 1 < bridged.size() && bridged[k - 1];
        const bool bridged_after = k < bridged.size() && bridged[k];
        if (!bridged_before || !bridged_after) out.push_back(k);
    }
    return out;
}

void StrokeGeometry::reverse() {
    std::reverse(points_px.begin(), points_px.end());
    std::reverse(points_world.begin(), points_world.end());
    std::reverse(edges.begin(), edges.end());
    std::reverse(bridged.begin(), bridged.end());
    std::swap(ends[0], ends[1]);
}

StrokeGeometry geometry_of(const Polyline& line) {
    StrokeGeometry g;
    g.kind = line.kind;
    g.visible = line.visible;
    g.closed = line.closed;
    g.points_px = line.points_px;
    g.points_world = line.points_world;
    g.edges = line.edges;
    return g;
}

}  // namespace inkline::core
