// SPDX-License-Identifier: MIT
// One occlusion query against one face, as the CPU tests make it: the query's own faces, the ray
// that ray-cast visibility traces and a double-precision triangle test that answers as Embree's
// does, the segment that exact visibility tests. Used wherever a face is tested outside Embree or
// the CGAL tree (fans: core/visibility/internal/fan_index.h), and by the tests that check them.
// Based on: S. Woop, C. Benthin, I. Wald. Watertight Ray/Triangle Intersection. JCGT 2(1), 2013.
#pragma once

#include "core/mesh/topology.h"
#include "core/visibility/visibility.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core::internal {

// Up to this many own faces a linear scan is cheapest (an edge has one or two unless it is
// non-manifold); a longer list, thousands of sheets on one edge, is searched by halving.
inline constexpr size_t kLinearOwnFaces = 8;

// Whether `face` is one of the query edge's `own` faces (ascending, as EdgeTable::faces_of).
inline bool is_own_face(std::span<const uint32_t> own, uint32_t face) {
    if (own.size() <= kLinearOwnFaces) return std::find(own.begin(), own.end(), face) != own.end();
    return std::binary_search(own.begin(), own.end(), face);
}

// The faces that never occlude a query (core/visibility/visibility.h): its edge's, and on an
// intersection line the other surface's face.
struct OwnFaces {
    std::span<const uint32_t> edge_faces;  // ascending, as EdgeTable::faces_of
    uint32_t crossing_face = 0xffffffffu;

    bool has(uint32_t face) const { return face == crossing_face || is_own_face(edge_faces, face); }
};

// A query's own faces: a smooth contour point's list, else its edge's faces in `table`.
inline OwnFaces own_faces_of(const OcclusionQuery& query, const EdgeTable& table) {
    return {query.own_faces.empty() ? table.faces_of(query.edge) : query.own_faces, query.crossing_face};
}

// Ray casting. The ray stops this fraction of the eye distance short of the point, exactly as
// exact visibility's segment does, so faces that merely touch the point (around an end vertex of
// its edge) do not count. The ray starts at the point and runs to the eye: Embree intersects
// relative to the ray origin, so float precision is best where the gap is decided. The ray is
// first clipped to kOcclusionReachDiagonals (core/visibility/visibility.h), as the segment is.
inline constexpr float kRayEndGap = 1e-6f;

// Embree sees the mesh and the rays scaled by a power of two (exact in float) that brings the
// largest coordinate to [1, 2): a mesh of extent 1e-30 or 1e18 is traced at unit scale, where
// float products in the triangle tests neither underflow nor leave Embree's ray range. 1 for a
// mesh of zeros or with a non-finite coordinate.
double raycast_scale(const std::vector<glm::vec3>& positions);

// A ray in the scaled frame, in float as Embree takes it: origin + t * direction meets a face
// for tnear < t <= tfar.
struct ScaledRay {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f};  // not normalised
    float tnear = kRayEndGap;
    float tfar = 1.0f;
};

// The ray cast for a point seen from the eye (object space): from the point (t = 0) to the eye,
// or as far towards it as an occluder can be (t = 1, occlusion_segment_end), times `scale`.
ScaledRay occlusion_ray(const glm::dvec3& p_object, const Viewpoint& eye_object, double reach, double scale);

// Ray against triangles, in double precision: Woop et al.'s watertight test, which is what
// Embree's robust mode answers in float. A ray through the edge or corner of a triangle meets
// it, and a ray through an edge shared by two triangles meets at least one of them: the edge
// function of a shared edge is computed from the same numbers in both, only its sign differs.
class RayTriangleTest {
  public:
    explicit RayTriangleTest(const ScaledRay& ray);
    // Whether the ray meets the triangle (a, b, c), given in the ray's frame.
    bool meets(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const;

  private:
    glm::dvec3 origin_;
    int kx_ = 0, ky_ = 1, kz_ = 2;  // the direction's largest component is kz
    double shear_x_ = 0.0, shear_y_ = 0.0, shear_z_ = 1.0;
    double tnear_ = 0.0, tfar_ = 1.0;
};

// Exact visibility. The segment stops this fraction of its length short of the point, so faces
// that merely touch the point (those around an end vertex of its edge) do not count as
// occluders. At a 4-unit viewing distance this is 4e-6 units, far below a pixel at any
// supported image size. The segment is first clipped to kOcclusionReachDiagonals
// (core/visibility/visibility.h), so a far eye does not widen the gap past the mesh.
inline constexpr double kSegmentEndGap = 1e-6;

// The closed segment exact visibility tests for a point seen from the eye (object space).
struct QuerySegment {
    glm::dvec3 far_end;  // the eye, or the point occlusion_segment_end clipped it to
    glm::dvec3 stop;     // kSegmentEndGap of the way from the point to far_end
};

QuerySegment query_segment(const glm::dvec3& p_object, const Viewpoint& eye_object, double reach);

// Whether the segment meets the triangle (a, b, c): CGAL's exact predicates, the test exact
// visibility makes for every face.
bool segment_meets_triangle(const QuerySegment& segment, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

}  // namespace inkline::core::internal
