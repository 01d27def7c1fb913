// SPDX-License-Identifier: MIT
// Smooth contours: the contour of the smooth surface that the mesh's vertex normals describe,
// instead of the zig-zag of mesh edges between front and back faces.
//
// g(p) = n(p) . (p - eye) is evaluated at every vertex with the area-weighted vertex normal and
// taken as linear over each face (Hertzmann and Zorin, "Illustrating smooth surfaces", SIGGRAPH
// 2000). A vertex faces away from the eye where g > 0 and towards it where g <= 0. The contour
// crosses each edge whose two vertices differ, at the point where g interpolated along the edge
// is zero, and each face with two such edges as one straight segment. Segments through shared
// edges chain into closed loops, or into open curves that end on an edge of one face (a
// boundary) or of three and more (non-manifold).
#pragma once

#include "core/lines/chaining.h"
#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

struct SmoothContourStats {
    size_t faces_tested = 0;  // faces whose vertex signs were compared
    size_t segments = 0;      // faces the contour crosses
};

// Traces the smooth contours of one frame's mesh seen from eye_object. Chains are silhouettes
// (core/lines/chaining.h says how their points, edges and faces relate); deterministic: the
// same mesh and eye give the same chains, points bit for bit.
class SmoothContourTracer {
  public:
    // Built once per topology: the edges of every face.
    SmoothContourTracer(const Mesh& mesh, const EdgeTable& table);

    const std::vector<Chain>& trace(const Mesh& mesh, const EdgeTable& table, const glm::dvec3& eye_object);
    const SmoothContourStats& stats() const { return stats_; }

  private:
    std::vector<glm::uvec3> face_edges_;
    std::vector<uint8_t> back_;           // per vertex: g > 0
    std::vector<uint32_t> contour_edges_; // edges the contour crosses, ascending
    std::vector<uint8_t> face_used_;
    std::vector<Chain> chains_;
    SmoothContourStats stats_;
};

// The face each segment of a smooth contour line crosses, from the edge each segment starts on
// (what a stroke keeps through the stroke stage): of that edge's faces, the one nearest the
// segment's midpoint. points_object has one point more than edges.
std::vector<uint32_t> faces_crossed(const Mesh& mesh, const EdgeTable& table, std::span<const glm::dvec3> points_object,
                                    std::span<const uint32_t> edges);

}  // namespace inkline::core
