// SPDX-License-Identifier: MIT
// Hierarchy of face clusters, each bounded by a normal cone anchored at the box of its face
// centroids: proves whole clusters front- or back-facing from an eye, or free of creases.
// Based on: P. Sander, X. Gu, S. Gortler, H. Hoppe, J. Snyder. Silhouette Clipping. SIGGRAPH 2000.
//           A. Johannsen, M. Carter. Clustered Backface Culling. Journal of Graphics Tools, 1998.
#pragma once

#include "core/mesh.h"
#include "core/topology.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace inkline::core::internal {

// What a cluster's cone proves about every face in it, for facing_value's sign.
enum class ClusterFacing : uint8_t { kUnknown = 0, kFront = 1, kBack = 2 };

struct ConeNode {
    glm::dvec3 box_min{0.0};         // bounds of the face centroids, computed as facing_value does
    glm::dvec3 box_max{0.0};
    glm::dvec3 axis{0.0, 0.0, 1.0};  // unit cone axis
    double spread = 2.0;             // max |unit normal - axis| over the faces; 2 bounds nothing
    double error = 1.0;              // largest relative error of facing_value's normal (see .cpp)
    uint32_t face_begin = 0;         // range in ConeTree::faces
    uint32_t face_end = 0;
    uint32_t edge_begin = 0;         // range in ConeTree::edges
    uint32_t edge_end = 0;
    uint32_t first_child = kNoIndex;  // children are first_child and first_child + 1; kNoIndex: leaf
    uint32_t parent = kNoIndex;

    bool is_leaf() const { return first_child == kNoIndex; }
};

// Node 0 is the root (absent when the mesh has no valid face); a parent precedes its children.
// Every interior edge (two faces) is listed once, at the deepest node holding both its faces:
// a leaf's edges lie inside it, an inner node's edges join its two children.
class ConeTree {
  public:
    // Splits the valid faces at the median of their widest position or normal spread, down to
    // leaves of at most leaf_faces faces, and fits every cone exactly.
    ConeTree(const Mesh& mesh, const EdgeTable& table, uint32_t leaf_faces);

    // New positions, same topology: refits leaves exactly and inner nodes from their children
    // (looser than a fresh build, but linear time).
    void refit(const Mesh& mesh);

    // kFront (kBack) when facing_value(mesh, f, eye) > 0 (<= 0) is certain for every face f of
    // the node, including floating-point error; kUnknown otherwise.
    ClusterFacing facing(uint32_t node, const glm::dvec3& eye) const;

    // True when no two faces of the node are further apart than crease_angle_rad, so is_crease
    // holds for none of its edges.
    bool crease_free(uint32_t node, double crease_angle_rad) const;

    std::vector<ConeNode> nodes;
    std::vector<uint32_t> faces;      // valid faces, grouped by node
    std::vector<uint32_t> face_leaf;  // #F, leaf of each face; kNoIndex for invalid faces
    std::vector<uint32_t> edges;      // interior edges, grouped by node, ascending within one

  private:
    struct FaceCone {
        glm::dvec3 centroid;
        glm::dvec3 normal;  // unit
        double error;
    };
    void fit_faces(const Mesh& mesh);
    void fit_leaf(ConeNode& node) const;

    std::vector<FaceCone> face_cones_;  // #F, scratch for build and refit
};

}  // namespace inkline::core::internal
