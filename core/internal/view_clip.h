// SPDX-License-Identifier: MIT
// The part of a face, or of a segment, that a frame can draw on: in front of the near plane and
// inside the image's sides, clipped in clip space (where both are planes) with each point's
// object-space position carried along. Stippling and hatching read a face's magnification there
// instead of at corners behind the camera or far outside the image; the frame pipeline tells a
// mesh wholly out of view by its bounds' corners.
#pragma once

#include "core/scene/camera.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>

namespace inkline::core::internal {

struct ViewVertex {
    glm::dvec4 clip{0.0};
    glm::dvec3 p{0.0};  // object space
};

// How far inside plane k (0: the near plane, 1-4: the image's sides) a clip-space point lies;
// inside where positive.
inline double inside_view_by(const Projection& projection, int plane, const glm::dvec4& c) {
    switch (plane) {
        case 0: return projection.depth(c) - projection.near();
        case 1: return c.w + c.x;
        case 2: return c.w - c.x;
        case 3: return c.w + c.y;
        default: return c.w - c.y;
    }
}

// A convex polygon of up to 9 corners (a triangle clipped by a box) clipped by the five planes:
// at most 9 + 5 vertices.
struct ViewPolygon {
    std::array<ViewVertex, 14> vertices;
    size_t count = 0;
};

inline ViewPolygon part_in_view(const Projection& projection, std::span<const glm::dvec3> corners) {
    ViewPolygon polygon;
    polygon.count = std::min<size_t>(corners.size(), 9);
    for (size_t k = 0; k < polygon.count; ++k) polygon.vertices[k] = {projection.clip(corners[k]), corners[k]};
    for (int plane = 0; plane < 5 && polygon.count > 0; ++plane) {
        ViewPolygon clipped;
        for (size_t i = 0; i < polygon.count; ++i) {
            const ViewVertex& u = polygon.vertices[i];
            const ViewVertex& v = polygon.vertices[(i + 1) % polygon.count];
            const double du = inside_view_by(projection, plane, u.clip), dv = inside_view_by(projection, plane, v.clip);
            // (A polygon made slightly concave by rounding could cross a plane more than twice:
            // the array bounds it.)
            if (du >= 0.0 && clipped.count < clipped.vertices.size()) clipped.vertices[clipped.count++] = u;
            if ((du >= 0.0) != (dv >= 0.0) && clipped.count < clipped.vertices.size()) {
                const double s = du / (du - dv);
                clipped.vertices[clipped.count++] = {u.clip + s * (v.clip - u.clip), u.p + s * (v.p - u.p)};
            }
        }
        polygon = clipped;
    }
    return polygon;
}

inline ViewPolygon part_in_view(const Projection& projection, const glm::dvec3& a, const glm::dvec3& b,
                                const glm::dvec3& c) {
    const glm::dvec3 corners[3] = {a, b, c};
    return part_in_view(projection, corners);
}

// The stretch [r_from, r_to] of the segment a -> b (0 at a, 1 at b) in view; false when none.
inline bool segment_in_view(const Projection& projection, const glm::dvec3& a, const glm::dvec3& b, double& r_from,
                            double& r_to) {
    const glm::dvec4 ca = projection.clip(a), cb = projection.clip(b);
    r_from = 0.0;
    r_to = 1.0;
    for (int plane = 0; plane < 5; ++plane) {
        const double da = inside_view_by(projection, plane, ca), db = inside_view_by(projection, plane, cb);
        if (da < 0.0 && db < 0.0) return false;
        if (da < 0.0) r_from = std::max(r_from, da / (da - db));
        if (db < 0.0) r_to = std::min(r_to, da / (da - db));
    }
    return r_from < r_to;
}

}  // namespace inkline::core::internal
