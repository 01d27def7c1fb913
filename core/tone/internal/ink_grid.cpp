// SPDX-License-Identifier: MIT
#include "core/tone/internal/ink_grid.h"

#include "core/strokes/strokes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace inkline::core::internal {

InkGrid::InkGrid(std::span<const Stroke> strokes, ImageSize image, double reach_px) : reach_(reach_px) {
    cols_ = std::max(1, int(std::ceil(image.width / kCell)));
    rows_ = std::max(1, int(std::ceil(image.height / kCell)));
    cells_.resize(size_t(cols_) * size_t(rows_));
    for (const Stroke& stroke : strokes) {
        if (!stroke.drawn || !stroke.geometry.visible) continue;
        const auto& c = stroke.centerline_px;
        const auto& w = stroke.centerline_width;
        const size_t n = c.size();
        if (n == 0) continue;
        const size_t segments = stroke.geometry.closed ? n : n - 1;
        for (size_t i = 0; i < std::max<size_t>(segments, 1); ++i) {
            const size_t j = n == 1 ? 0 : (i + 1) % n;
            const double half = 0.5 * std::max(w[i], w[j]);
            add({c[i], c[j], half}, half + reach_px);
        }
    }
}

bool InkGrid::touches(const glm::dvec2& p, double radius_px) const {
    if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < cols_ * kCell && p.y < rows_ * kCell)) return false;
    const int col = int(p.x / kCell);
    const int row = int(p.y / kCell);
    for (uint32_t s : cells_[size_t(row) * size_t(cols_) + size_t(col)]) {
        const Segment& seg = segments_[s];
        const glm::dvec2 d = seg.b - seg.a;
        const double len2 = glm::dot(d, d);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(p - seg.a, d) / len2, 0.0, 1.0) : 0.0;
        const glm::dvec2 q = seg.a + t * d - p;
        const double reach = seg.half_width + radius_px;
        if (glm::dot(q, q) < reach * reach) return true;
    }
    return false;
}

double InkGrid::clearance(const glm::dvec2& p) const {
    double least = reach_;
    if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < cols_ * kCell && p.y < rows_ * kCell)) return least;
    for (uint32_t s : cells_[size_t(int(p.y / kCell)) * size_t(cols_) + size_t(int(p.x / kCell))]) {
        const Segment& seg = segments_[s];
        const glm::dvec2 d = seg.b - seg.a;
        const double len2 = glm::dot(d, d);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(p - seg.a, d) / len2, 0.0, 1.0) : 0.0;
        least = std::min(least, std::max(0.0, glm::length(seg.a + t * d - p) - seg.half_width));
    }
    return least;
}

void InkGrid::add(const Segment& seg, double reach) {
    const glm::dvec2 lo = glm::min(seg.a, seg.b) - reach;
    const glm::dvec2 hi = glm::max(seg.a, seg.b) + reach;
    // Cells clamped in double first: a centerline far outside the image must not overflow int.
    const auto cell = [](double v, int count) { return int(std::clamp(std::floor(v / kCell), -1.0, double(count))); };
    const int c0 = std::max(0, cell(lo.x, cols_)), c1 = std::min(cols_ - 1, cell(hi.x, cols_));
    const int r0 = std::max(0, cell(lo.y, rows_)), r1 = std::min(rows_ - 1, cell(hi.y, rows_));
    if (c0 > c1 || r0 > r1) return;
    const auto index = uint32_t(segments_.size());
    segments_.push_back(seg);
    for (int r = r0; r <= r1; ++r) {
        for (int c = c0; c <= c1; ++c) cells_[size_t(r) * size_t(cols_) + size_t(c)].push_back(index);
    }
}

}  // namespace inkline::core::internal
