// SPDX-License-Identifier: MIT
#include "gl/internal/depth_map.h"

#include <algorithm>
#include <cmath>

namespace inkline::gl::internal {
namespace {

// Surfaces within this fraction of the point's inverse depth count as level with it. Stored q is
// a float (relative error 6e-8) computed from float vertex transforms (about 1e-6); 1e-5 leaves
// a margin and is still only 4e-5 units at a 4-unit viewing distance, a sixtieth of a pixel at
// 1024 px and 35 degrees. It also absorbs the curvature error when a texel sees a sub-texel
// neighbour of the point's own face and extends that neighbour's plane to the point.
constexpr double kRelativeDepthTolerance = 1e-5;

// The point's window position and the rasteriser's disagree by float rounding of the vertex
// transform and by sub-pixel snapping (8 bits in llvmpipe), together well under this many
// texels; a surface extended to the point may be off by its slope times that distance.
constexpr double kPositionToleranceTexels = 1.0 / 16.0;

}  // namespace

DepthVerdict classify_in_depth_map(const DepthMap& map, const DepthSample& sample) {
    // The four texel centres around the point; at the map's border the nearest row or column
    // stands in for the missing one.
    const int i0 = int(std::floor(sample.p_window.x - 0.5));
    const int j0 = int(std::floor(sample.p_window.y - 0.5));
    int in_front = 0;
    for (int dj = 0; dj < 2; ++dj) {
        for (int di = 0; di < 2; ++di) {
            const int i = std::clamp(i0 + di, 0, map.width - 1);
            const int j = std::clamp(j0 + dj, 0, map.height - 1);
            const DepthTexel& t = map.at(i, j);
            if (t.face == 0.0f) continue;  // nothing drawn: seen past it
            // Extend the texel's plane from its centre to the point.
            const double dx = sample.p_window.x - (double(i) + 0.5);
            const double dy = sample.p_window.y - (double(j) + 0.5);
            const double q_surface = double(t.q) + double(t.dq_dx) * dx + double(t.dq_dy) * dy;
            const double tolerance = kRelativeDepthTolerance * sample.q +
                                     kPositionToleranceTexels * (std::abs(double(t.dq_dx)) + std::abs(double(t.dq_dy)));
            // Larger q is nearer the eye.
            if (q_surface > sample.q + tolerance) ++in_front;
        }
    }
    if (in_front == 0) return DepthVerdict::kVisible;
    return in_front == 4 ? DepthVerdict::kHidden : DepthVerdict::kEdge;
}

void faces_around(const DepthMap& map, const glm::dvec2& p_window, int rings, std::vector<uint32_t>& r_faces) {
    const int i0 = int(std::floor(p_window.x - 0.5)) - rings;
    const int j0 = int(std::floor(p_window.y - 0.5)) - rings;
    const int side = 2 + 2 * rings;
    for (int j = std::max(j0, 0); j < std::min(j0 + side, map.height); ++j) {
        for (int i = std::max(i0, 0); i < std::min(i0 + side, map.width); ++i) {
            const float id = map.at(i, j).face;
            if (id == 0.0f) continue;
            const auto face = uint32_t(id) - 1;
            if (std::find(r_faces.begin(), r_faces.end(), face) == r_faces.end()) r_faces.push_back(face);
        }
    }
}

}  // namespace inkline::gl::internal
