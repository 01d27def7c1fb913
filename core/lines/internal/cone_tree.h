// SPDX-License-Identifier: MIT
// Hierarchy of face clusters, each bounded by a normal cone anchored at the box of its face
// centroids: proves whole clusters front- or back-facing from an eye, or free of creases. Built
// over corner normals instead, it bounds the normals at the faces' corners and is anchored at the
// box of the corners: it proves the sign of n . eye.toward(corner) at every corner of a cluster,
// the sign smooth contours follow.
// Based on: P. Sander, X. Gu, S. Gortler, H. Hoppe, J. Snyder. Silhouette Clipping. SIGGRAPH 2000.
//           A. Johannsen, M. Carter. Clustered Backface Culling. Journal of Graphics Tools, 1998.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/scene/camera.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace inkline::core::internal {

// What a cluster's cone proves about every face in it, for facing_value's sign.
enum class ClusterFacing : uint8_t { kUnknown = 0, kFront = 1, kBack = 2 };

struct ConeNode {
    glm::dvec3 box_min{0.0};         // bounds of the face centroids, computed as facing_value does
    glm::dvec3 box_max{0.0};         // (over corner normals: of the faces' corners)
    glm::dvec3 axis{0.0, 0.0, 1.0};  // unit cone axis
    double spread = 2.0;             // max |unit normal - axis| over the faces; 2 bounds nothing
    double error = 1.0;              // largest relative error of facing_value's normal (see .cpp)
    uint32_t face_begin = 0;         // range in ConeTree::faces
    uint32_t face_end = 0;
    uint32_t edge_begin = 0;         // range in ConeTree::edges
    uint32_t edge_end = 0;
    uint32_t second_child = kNoIndex;  // the first child is the next node; kNoIndex: a leaf

    bool is_leaf() const { return second_child == kNoIndex; }
};

// An interior edge by the indices of its two faces in ConeTree::faces, the lower first (the
// faces themselves are faces[position[k]]; 12 bytes an edge, 18 MB at 1.5M edges).
struct ListedEdge {
    uint32_t edge;
    uint32_t position[2];
};

// Nodes are in depth-first order: node 0 is the root (absent when the mesh has no valid face) and
// an inner node i has children i + 1 and second_child. Leaves hold leaf_faces faces each (the last
// one possibly fewer), so the leaf holding position p is the (p / leaf_faces)-th leaf in tree
// order, and a node's leaves are the consecutive range leaves_of(node).
// Every interior edge (two faces) is listed once, at the deepest node holding both its faces:
// a leaf's edges lie inside it, an inner node's edges join its two children and are sorted by
// the position of their face in the first child, so that runs of them stay close on the mesh.
class ConeTree {
  public:
    // Splits the valid faces near the median of their widest position or normal spread (the
    // first half gets a whole number of leaves), down to leaves of leaf_faces faces, and fits
    // every cone exactly.
    // With corner normals (unit or zero), the cones bound those at each face's corners instead of
    // the face normals: corner c of face f has normals[face_corners[f][c]].
    ConeTree(const Mesh& mesh, const EdgeTable& table, uint32_t leaf_faces, std::span<const glm::dvec3> normals = {},
             std::span<const glm::uvec3> face_corners = {});

    // New positions, same topology: refits leaves exactly and inner nodes from their children
    // (looser than a fresh build, but linear time). A tree over corner normals takes the new ones.
    void refit(const Mesh& mesh, std::span<const glm::dvec3> normals = {},
               std::span<const glm::uvec3> face_corners = {});

    // kFront (kBack) when facing_value(mesh, f, eye) > 0 (<= 0) is certain for every face f of
    // the node, including floating-point error; kUnknown otherwise. Over corner normals: kFront
    // (kBack) when glm::dot(n, eye.toward(corner)) > 0 (< 0) is certain for every corner of
    // every face of the node, n the corner's normal.
    ClusterFacing facing(uint32_t node, const Viewpoint& eye) const;

    uint32_t leaf_faces() const { return leaf_faces_; }
    uint32_t leaf_count() const { return (uint32_t(faces.size()) + leaf_faces_ - 1) / leaf_faces_; }
    // The leaf (in tree order, not a node index) that holds a position in `faces`.
    uint32_t leaf_of(uint32_t position) const { return position / leaf_faces_; }
    // The leaves under a node: [first, second).
    std::pair<uint32_t, uint32_t> leaves_of(const ConeNode& node) const {
        return {node.face_begin / leaf_faces_, (node.face_end + leaf_faces_ - 1) / leaf_faces_};
    }

    // Creases (a tree over face normals only): true when no two faces of the node are further
    // apart than crease_angle_rad, so is_crease holds for none of its edges.
    bool crease_free(uint32_t node, double crease_angle_rad) const;

    // False when is_crease(mesh, edge faces, cos_crease) is certainly false for the mesh last
    // given to refit (valid only after refit).
    bool maybe_crease(const ListedEdge& edge, double cos_crease) const;

    std::vector<ConeNode> nodes;
    std::vector<uint32_t> faces;          // valid faces; a node holds faces[face_begin, face_end)
    std::vector<ListedEdge> edges;        // interior edges; a node lists edges[edge_begin, edge_end)

  private:
    uint32_t leaf_faces_;
    // Single precision, 32 bytes a face (the build's scratch: 32 MB at 1M faces, moved by every
    // split): the values are computed in double and rounded to float, the error upwards; a node's
    // box and spread are widened by what that rounding can move them (fit_node).
    struct FaceCone {
        glm::vec3 centroid;  // over corner normals: the centre of the corners' box
        glm::vec3 normal;    // unit before rounding
        float error;
        uint32_t face;       // the mesh face
    };
    static_assert(sizeof(FaceCone) == 32);
    // Over corner normals, what a face's cone adds to its centroid and normal.
    // Single precision, 28 bytes a face: the corners are floats, so their box is exact; the
    // spread is rounded up.
    struct CornerBounds {
        glm::vec3 box_min;  // of the corners
        glm::vec3 box_max;
        float spread;       // at least max |corner normal - the face's unit normal|; 2 bounds nothing
    };
    static FaceCone face_cone(const Mesh& mesh, uint32_t face);
    // Corner normals: normals[face_corners[f][c]] at corner c of face f.
    struct CornerNormals {
        std::span<const glm::dvec3> normals;
        std::span<const glm::uvec3> face_corners;
    };
    FaceCone corner_cone(const Mesh& mesh, const CornerNormals& corners, uint32_t face);
    FaceCone cone_of(const Mesh& mesh, const CornerNormals& corners, uint32_t face);
    void fit_node(ConeNode& node) const;
    static void set_spread(ConeNode& node, double spread);

    std::vector<FaceCone> cones_;  // parallel to faces: split in place by the build, then kept by refit for maybe_crease
    bool over_corner_normals_ = false;
    std::vector<CornerBounds> corners_;  // over corner normals, per mesh face, while cones_ is held
};

}  // namespace inkline::core::internal
