// SPDX-License-Identifier: MIT
// The depth map read back from the GL pass, and the test of one point against it.
// Every texel holds the nearest surface's inverse view depth q = 1 / w_clip (in orthographic
// projection, where w_clip is 1, q = 2 - z_clip: larger nearer, too) with its slope, so
// the surface can be extended exactly to a point between texel centres, and the id of the face
// seen there. Why the test looks at the texels around a point the way it does:
// docs/visibility.md.
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace inkline::gl::internal {

// One texel, as the fragment shader writes it (RGBA32F). q is affine in window space on a
// planar triangle, so (dq_dx, dq_dy) describe the seen triangle's plane exactly.
struct DepthTexel {
    float q = 0.0f;      // q of the nearest surface at the texel centre
    float dq_dx = 0.0f;  // change of q per texel along window x (right)
    float dq_dy = 0.0f;  // change of q per texel along window y (up)
    float face = 0.0f;   // index of the face seen + 1, exact below kMaxFaceId; 0: none
};

// Face ids are stored as floats, exact up to 2^24; larger meshes skip the exact edge test.
inline constexpr uint32_t kMaxFaceId = 1u << 24;

// A width x height grid of texels in GL window order: row 0 at the bottom, texel (i, j)
// covering [i, i+1] x [j, j+1] in window coordinates.
struct DepthMap {
    int width = 0;
    int height = 0;
    std::vector<DepthTexel> texels;  // #width*height, row-major

    const DepthTexel& at(int i, int j) const { return texels[size_t(j) * size_t(width) + size_t(i)]; }
};

// A query point seen through the depth pass's projection.
struct DepthSample {
    glm::dvec2 p_window;  // texels, x right, y up, origin at the bottom-left corner
    double q = 0.0;       // the point's q: 1 / w_clip, its inverse view depth (or 2 - z_clip)
};

enum class DepthVerdict : uint8_t {
    kVisible,  // every texel around the point sees a surface level with or behind it
    kHidden,   // every texel around the point sees a surface in front of it
    kEdge,     // both: the point lies on a depth discontinuity (a silhouette, an occluder's edge)
};

// Compares the point with the surface seen at each of the four texel centres around it (the
// bilinear footprint), each surface extended to the point along its own plane, with a tolerance
// that grows with the surface's slope.
DepthVerdict classify_in_depth_map(const DepthMap& map, const DepthSample& sample);

// Appends to r_faces, without repeats, the faces seen at the texels around the point: its
// bilinear footprint widened by `rings` texels on every side, clipped to the map.
void faces_around(const DepthMap& map, const glm::dvec2& p_window, int rings, std::vector<uint32_t>& r_faces);

}  // namespace inkline::gl::internal
