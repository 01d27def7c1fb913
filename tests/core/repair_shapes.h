// SPDX-License-Identifier: MIT
// Strokes and last frame's memory of them, drawn along straight lines, for the tests of the
// stroke repairs (bridge_gaps, rejoin_strokes, t_junctions, reversals).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <vector>

#include "core/strokes/stroke_coherence.h"
#include "core/strokes/stroke_geometry.h"

namespace inkline::repair_shapes {

using glm::dvec2;

// A straight stroke from a to b with a point every px, on edges first_edge...
inline core::StrokeGeometry line(dvec2 a, dvec2 b, bool visible, uint32_t first_edge) {
    core::StrokeGeometry g;
    g.visible = visible;
    const int n = std::max(1, int(std::ceil(glm::length(b - a))));
    for (int i = 0; i <= n; ++i) {
        const dvec2 p = i == n ? b : a + (b - a) * (double(i) / n);
        g.points_px.push_back(p);
        g.points_world.push_back(glm::dvec3(p, 0.0));
        if (i < n) g.edges.push_back(first_edge + uint32_t(i));
    }
    return g;
}

// Last frame remembered visible strokes from a to b with these ids.
inline core::StrokeTrace trace(dvec2 a, dvec2 b, uint32_t id) {
    core::StrokeTrace t;
    t.id = id;
    t.length_px = glm::length(b - a);
    for (double s = 0.0; s <= t.length_px + 1e-9; s += core::kTraceSpacingPx) {
        t.samples_px.push_back(a + (b - a) * (s / t.length_px));
        t.samples_u.push_back(s);
    }
    return t;
}

// Last frame remembered a stroke along this path, with these ids, u running from its start.
inline core::StrokeTrace trace_along(const std::vector<dvec2>& path, uint32_t id) {
    core::StrokeTrace t;
    t.id = id;
    double u = 0.0;
    for (size_t i = 0; i + 1 < path.size(); ++i) {
        const double len = glm::length(path[i + 1] - path[i]);
        for (double s = 0.0; s < len; s += core::kTraceSpacingPx) {
            t.samples_px.push_back(path[i] + (path[i + 1] - path[i]) * (s / len));
            t.samples_u.push_back(u + s);
        }
        u += len;
    }
    t.length_px = u;
    return t;
}

// A visible stroke through these points, a point every px, on edges first_edge...
inline core::StrokeGeometry through(const std::vector<dvec2>& path, uint32_t first_edge) {
    core::StrokeGeometry g = line(path[0], path[1], true, first_edge);
    for (size_t i = 1; i + 1 < path.size(); ++i) {
        const core::StrokeGeometry next = line(path[i], path[i + 1], true, first_edge + uint32_t(g.edges.size()));
        g.points_px.insert(g.points_px.end(), next.points_px.begin() + 1, next.points_px.end());
        g.points_world.insert(g.points_world.end(), next.points_world.begin() + 1, next.points_world.end());
        g.edges.insert(g.edges.end(), next.edges.begin(), next.edges.end());
    }
    return g;
}

}  // namespace inkline::repair_shapes
