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
    uint32_t span_begin = 0;         // ConeTree::spans[span_begin + j] bounds the j-th kSpanEdges edges
    uint32_t second_child = kNoIndex;  // the first child is the next node; kNoIndex: a leaf

    bool is_leaf() const { return second_child == kNoIndex; }
};

// An interior edge by the indices of its two faces in ConeTree::faces, the lower first (the
// faces themselves are faces[position[k]]; 12 bytes an edge, 18 MB at 1.5M edges).
struct ListedEdge {
    uint32_t edge;
    uint32_t position[2];
};

// Bounds of the face positions of a run of kSpanEdges consecutive listed edges of one node: a
// run whose two sides each lie inside one proven cluster can be skipped without reading it.
inline constexpr uint32_t kSpanEdges = 16;
struct EdgeSpan {
    uint32_t first_min, first_max;    // of position[0]
    uint32_t second_min, second_max;  // of position[1]
};

// Nodes are in depth-first order: node 0 is the root (absent when the mesh has no valid face) and
// an inner node i has children i + 1 and second_child.
// Every interior edge (two faces) is listed once, at the deepest node holding both its faces:
// a leaf's edges lie inside it, an inner node's edges join its two children and are sorted by
// the position of their face in the first child, so that runs of them stay close on the mesh.
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

    // False when is_crease(mesh, edge faces, cos_crease) is certainly false for the mesh last
    // given to refit (valid only after refit).
    bool maybe_crease(const ListedEdge& edge, double cos_crease) const;

    std::vector<ConeNode> nodes;
    std::vector<uint32_t> faces;          // valid faces; a node holds faces[face_begin, face_end)
    std::vector<uint32_t> face_position;  // #F, index of each face in `faces`; kNoIndex if invalid
    std::vector<ListedEdge> edges;        // interior edges; a node lists edges[edge_begin, edge_end)
    std::vector<EdgeSpan> spans;

  private:
    struct FaceCone {
        glm::dvec3 centroid;
        glm::dvec3 normal;  // unit
        double error;
        uint32_t face;      // the mesh face
    };
    static FaceCone face_cone(const Mesh& mesh, uint32_t face);
    void fit_node(ConeNode& node) const;
    static void set_spread(ConeNode& node, double spread);

    std::vector<FaceCone> cones_;  // parallel to faces: split in place by the build, then kept by refit for maybe_crease
};

}  // namespace inkline::core::internal
