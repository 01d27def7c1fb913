// SPDX-License-Identifier: MIT
// Cubic Bezier fitting of closed outlines within a tolerance, for compact smooth vector output.
// Based on: P. J. Schneider. An Algorithm for Automatically Fitting Digitized Curves.
// Graphics Gems, 1990 (least squares with Newton reparameterization, split at the worst point).
#pragma once

#include <glm/vec2.hpp>
#include <vector>

#include "core/strokes/outline.h"

namespace inkline::core {

struct CubicBezier {
    glm::dvec2 p0, p1, p2, p3;  // p3 of one segment is p0 of the next

    glm::dvec2 at(double t) const;
};

// Segments that run once around the ring, each point of the ring (and of its edges, checked
// every 1 px) within tolerance_px of the curve. Sharp corners of the ring (pointed stroke tips)
// stay corners. An empty result for rings of fewer than three points.
std::vector<CubicBezier> fit_cubics(const Ring& ring, double tolerance_px);

// Largest distance (px) from the ring's points and edges (every 1 px) to the curves.
double fit_error_px(const Ring& ring, const std::vector<CubicBezier>& curves);

}  // namespace inkline::core
