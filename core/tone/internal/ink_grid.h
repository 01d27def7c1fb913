// SPDX-License-Identifier: MIT
// The ink of a frame's visible strokes, for the tone to keep its marks off: each drawn
// centerline cut into segments with their half width, binned on a pixel grid.
#pragma once

#include "core/scene/camera.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {
struct Stroke;
}

namespace inkline::core::internal {

class InkGrid {
  public:
    // The visible, drawn strokes' centerlines; a query reaches at most reach_px past the ink.
    InkGrid(std::span<const Stroke> strokes, ImageSize image, double reach_px);

    // True when a disc of radius_px (at most the reach) at p touches the ink.
    bool touches(const glm::dvec2& p, double radius_px) const;
    // How far p is from the ink (0 inside it), up to the reach (then the reach).
    double clearance(const glm::dvec2& p) const;

  private:
    static constexpr double kCell = 16.0;
    struct Segment {
        glm::dvec2 a, b;
        double half_width;
    };
    void add(const Segment& seg, double reach);

    double reach_ = 0.0;
    int cols_ = 1, rows_ = 1;
    std::vector<Segment> segments_;
    std::vector<std::vector<uint32_t>> cells_;
};

}  // namespace inkline::core::internal
