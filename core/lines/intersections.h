// SPDX-License-Identifier: MIT
// Intersection lines: where the surfaces of two objects cross (and, when asked, where one object's
// surface crosses itself), traced as chains of the points where an edge of one surface pierces a
// face of the other.
//
// Whether an edge pierces a face is decided with exact orientation predicates (CGAL), and ties
// (a vertex exactly on a face's plane: a box standing on a ground plane) as if the surface of the
// object with the higher index were moved by an infinitesimal step along a fixed direction, and
// within one object each vertex by a smaller step of its own (a symbolic perturbation). The
// answer for an edge and a face is the same in every pair of faces that asks it, and every pair
// of faces then crosses in no segment or in exactly one: the segments link into chains through
// their shared pierce points, by index, with no distance tolerance. Objects are the mesh's own
// (a glTF shot's mesh instances, an OBJ file's groups); a mesh without objects has one.
#pragma once

#include "core/lines/chaining.h"
#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

struct IntersectionOptions {
    bool between_objects = true;  // faces of different objects
    bool self = false;            // faces of one object that share no vertex
};

struct IntersectionStats {
    size_t candidate_pairs = 0;  // face pairs whose boxes overlap
    size_t segments = 0;         // face pairs that cross
};

// The intersection chains of `mesh` (kind kIntersection, core/lines/chaining.h). face_objects
// holds each face's object (empty: one object). Each chain's first surface is the face of the
// object with the lower index (self intersections: the lower face index). Deterministic: chains
// come in the order of their segments (face pairs, ascending): open chains first, each from its
// free end, then closed ones.
std::vector<Chain> trace_intersections(const Mesh& mesh, const EdgeTable& table,
                                       std::span<const uint32_t> face_objects, const IntersectionOptions& options,
                                       IntersectionStats* r_stats = nullptr);

// trace_intersections over a run's frames: the face edges are found once per topology, and a
// frame whose positions did not change gets the last frame's chains.
class IntersectionTracer {
  public:
    explicit IntersectionTracer(IntersectionOptions options) : options_(options) {}

    // `positions_changed` false: the mesh is last call's, unmoved (only the camera may differ).
    // `table` must be the same object for the same topology.
    const std::vector<Chain>& trace(const Mesh& mesh, const EdgeTable& table, std::span<const uint32_t> face_objects,
                                    bool positions_changed);
    const IntersectionStats& stats() const { return stats_; }

  private:
    IntersectionOptions options_;
    bool traced_ = false;
    const EdgeTable* table_ = nullptr;
    std::vector<glm::uvec3> face_edges_;
    std::vector<Chain> chains_;
    IntersectionStats stats_;
};

}  // namespace inkline::core
