// SPDX-License-Identifier: MIT
// Visibility of feature chains: sample each chain, classify samples as visible, occluded or
// outside the view, find each change by bisection and split the chain there.
// The occlusion test itself is pluggable: exact (CGAL, core/visibility/exact_visibility.h), GL depth map,
// ray casting. All share the definition below.
#pragma once

#include "core/lines/chaining.h"
#include "core/mesh/mesh.h"
#include "core/scene/camera.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

inline constexpr uint32_t kNoCrossingFace = 0xffffffffu;

struct OcclusionQuery {
    glm::dvec3 p_object;  // a point on a feature edge, object space
    uint32_t edge;        // that edge: its own faces never occlude it
    // On an intersection line, the other surface's face the point lies on (edge is then an edge of
    // the first surface's face, core/lines/chaining.h); it never occludes the point either.
    uint32_t crossing_face = kNoCrossingFace;
    // On a smooth contour, the faces that never occlude the point instead of its edge's (ascending):
    // the face it crosses and every face sharing a corner with it (core/lines/smooth_contours.h).
    std::span<const uint32_t> own_faces = {};
};

// A point is occluded when the open segment from the eye to it meets a valid face other than
// the faces of its own edge (and its crossing face), or other than its own faces when it has them.
class Occlusion {
  public:
    virtual ~Occlusion() = default;
    // r_occluded[i] = 1 when queries[i] is occluded seen from eye_object; sizes must match.
    virtual void occluded(const Viewpoint& eye_object, std::span<const OcclusionQuery> queries,
                          std::span<uint8_t> r_occluded) const = 0;
};

// Occluders lie inside the mesh's bounding box, so only the part of the segment from a point
// towards the eye that lies within this many box diagonals of the point can meet one. The
// occlusion tests clip the segment there before they apply their end gap: an eye at any distance
// answers as one at this distance does, and Embree's float rays stay far inside the range it
// accepts (about 1.8e18 per component) whatever the coordinates.
inline constexpr double kOcclusionReachDiagonals = 4.0;

// kOcclusionReachDiagonals diagonals of the bounding box of `positions` (1 for a single point).
double occlusion_reach(const std::vector<glm::vec3>& positions);

// The end of the segment from p towards the eye that the occlusion tests use: the eye when it
// is within `reach` of p, else the point `reach` away from p towards it (always, for an eye at
// infinity).
glm::dvec3 occlusion_segment_end(const glm::dvec3& p, const Viewpoint& eye, double reach);

struct VisibilityOptions {
    double sample_spacing_px = 2.0;  // coarse samples at most this far apart along a chain
    double bisection_px = 0.125;     // transitions located to this precision
    bool keep_hidden = false;        // also return occluded parts, as visible == false
};

// One output polyline: a visible (or hidden) part of a chain, in pixels and world space.
struct Polyline {
    uint32_t id = 0;
    LineKind kind = LineKind::kSilhouette;
    bool closed = false;
    bool visible = true;
    std::vector<glm::dvec2> points_px;     // exact projected feature geometry, px
    std::vector<glm::dvec3> points_world;  // the same points in world space
    std::vector<uint32_t> edges;           // mesh edge of each segment (points - 1)
    // Intersection lines: the other surface's face of each segment; edges then name an edge of
    // the first surface's face (core/lines/chaining.h). Empty for the other kinds.
    std::vector<uint32_t> crossing_faces;
    // Smooth contours: the face each segment crosses; edges then name the edge each segment starts
    // on (core/lines/chaining.h). Empty for the other lines.
    std::vector<uint32_t> faces;
    int32_t object = -1;                   // index into the frame's objects; -1 without objects

    double length_px() const;
    bool operator==(const Polyline&) const = default;
};

// Splits every chain by visibility. Parts outside the image or behind the near plane are
// dropped; occluded parts are kept only with keep_hidden. Ids are assigned in output order.
// Smooth contour chains need the mesh's edge table (their points' own faces come from it).
std::vector<Polyline> split_by_visibility(const std::vector<Chain>& chains, const Mesh& mesh, const EdgeTable& table,
                                          const Projection& projection, const Occlusion& occlusion,
                                          const VisibilityOptions& options);
// The same for chains without smooth contours.
std::vector<Polyline> split_by_visibility(const std::vector<Chain>& chains, const Mesh& mesh,
                                          const Projection& projection, const Occlusion& occlusion,
                                          const VisibilityOptions& options);

}  // namespace inkline::core
