// SPDX-License-Identifier: MIT
#include "core/lines/internal/cone_tree.h"

#include "core/lines/features.h"
#include "core/mesh/topology.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace inkline {
namespace {

using core::internal::ClusterFacing;
using core::internal::ConeTree;

// Every face under every node the tree proves has the proven sign of facing_value.
size_t check_proofs(const ConeTree& tree, const core::Mesh& mesh, const glm::dvec3& eye) {
    size_t proven = 0;
    for (uint32_t n = 0; n < tree.nodes.size(); ++n) {
        const ClusterFacing facing = tree.facing(n, eye);
        if (facing == ClusterFacing::kUnknown) continue;
        ++proven;
        for (uint32_t k = tree.nodes[n].face_begin; k < tree.nodes[n].face_end; ++k) {
            const double value = core::facing_value(mesh, tree.faces[k], eye);
            EXPECT_EQ(value > 0.0, facing == ClusterFacing::kFront) << "node " << n << " face " << tree.faces[k];
        }
    }
    return proven;
}

TEST(ConeTree, ProvenFacingHoldsForEveryFace) {
    const core::Mesh torus = test::torus(1.0, 0.4, 64, 24);
    const core::EdgeTable table = core::build_edge_table(torus);
    const ConeTree tree(torus, table, 8);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> coord(-3.0, 3.0);
    size_t proven = 0;
    for (int i = 0; i < 40; ++i) proven += check_proofs(tree, torus, {coord(rng), coord(rng), coord(rng)});
    EXPECT_GT(proven, tree.nodes.size()) << "most nodes should be proven from most eyes";
}

TEST(ConeTree, EyeInThePlaneOfFlatFacesProvesNothingWrong) {
    // facing_value is exactly zero there (back-facing); the cone test must not call it front.
    const core::Mesh grid = test::grid(16, 1.0);
    const core::EdgeTable table = core::build_edge_table(grid);
    const ConeTree tree(grid, table, 4);
    check_proofs(tree, grid, {3.0, 0.5, 0.0});
    check_proofs(tree, grid, {0.25, 0.25, 0.0});
    EXPECT_EQ(tree.facing(0, glm::dvec3{0.0, 0.0, 2.0}), ClusterFacing::kFront);
    EXPECT_EQ(tree.facing(0, glm::dvec3{0.0, 0.0, -2.0}), ClusterFacing::kBack);
}

TEST(ConeTree, RefitKeepsProofsValidAfterDeformation) {
    core::Mesh sphere = test::uv_sphere(48, 24, 1.0);
    const core::EdgeTable table = core::build_edge_table(sphere);
    ConeTree tree(sphere, table, 8);
    for (glm::vec3& p : sphere.positions) p = glm::vec3(p.x * 1.5f, p.y * (0.7f + 0.2f * p.x), p.z + 0.3f * p.y * p.y);
    tree.refit(sphere);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> coord(-4.0, 4.0);
    size_t proven = 0;
    for (int i = 0; i < 30; ++i) proven += check_proofs(tree, sphere, {coord(rng), coord(rng), coord(rng)});
    EXPECT_GT(proven, 0u);
    // The crease prefilter only rules out edges that is_crease rejects too.
    for (const double degrees : {1.0, 5.0, 30.0}) {
        const double cos_crease = std::cos(degrees * M_PI / 180.0);
        size_t ruled_out = 0;
        for (const core::internal::ListedEdge& le : tree.edges) {
            if (tree.maybe_crease(le, cos_crease)) continue;
            ++ruled_out;
            EXPECT_FALSE(core::is_crease(sphere, tree.faces[le.position[0]], tree.faces[le.position[1]], cos_crease))
                << "edge " << le.edge;
        }
        if (degrees > 10.0) {
            EXPECT_GT(ruled_out, 0u);
        }
    }
}

TEST(ConeTree, EveryInteriorEdgeListedOnceAtItsFacesCommonNode) {
    const core::Mesh sphere = test::hemisphere(40, 20, 1.0);
    const core::EdgeTable table = core::build_edge_table(sphere);
    const ConeTree tree(sphere, table, 6);
    std::vector<int> seen(table.edge_count(), 0);
    std::vector<uint32_t> position(sphere.triangles.size());
    for (uint32_t k = 0; k < tree.faces.size(); ++k) position[tree.faces[k]] = k;
    for (uint32_t n = 0; n < tree.nodes.size(); ++n) {
        const core::internal::ConeNode& node = tree.nodes[n];
        for (uint32_t k = node.edge_begin; k < node.edge_end; ++k) {
            const uint32_t e = tree.edges[k].edge;
            ++seen[e];
            for (uint32_t f : table.faces_of(e)) {
                EXPECT_GE(position[f], node.face_begin);
                EXPECT_LT(position[f], node.face_end);
            }
            if (!node.is_leaf()) {
                const uint32_t split = tree.nodes[n + 1].face_end;
                EXPECT_EQ(split, tree.nodes[node.second_child].face_begin);
                const auto faces = table.faces_of(e);
                EXPECT_NE(position[faces[0]] < split, position[faces[1]] < split) << "edge " << e;
            }
        }
    }
    for (uint32_t e = 0; e < table.edge_count(); ++e) EXPECT_EQ(seen[e], table.is_interior(e) ? 1 : 0) << "edge " << e;
}

// Every leaf but the last is full, so a position's leaf is position / leaf_faces: the leaves in
// depth-first order tile the faces, and each node's leaves are the ones its face range covers.
TEST(ConeTree, LeavesAreFullAndFoundByPosition) {
    const core::Mesh sphere = test::hemisphere(40, 21, 1.0);
    const core::EdgeTable table = core::build_edge_table(sphere);
    for (const uint32_t leaf_faces : {1u, 5u, 16u}) {
        const ConeTree tree(sphere, table, leaf_faces);
        ASSERT_EQ(tree.faces.size(), sphere.triangles.size());
        uint32_t leaf = 0;
        for (uint32_t n = 0; n < tree.nodes.size(); ++n) {
            const core::internal::ConeNode& node = tree.nodes[n];
            const auto [first, last] = tree.leaves_of(node);
            EXPECT_EQ(first, leaf) << "node " << n;  // depth first: a node's leaves come next
            if (!node.is_leaf()) {
                EXPECT_EQ(tree.leaves_of(tree.nodes[n + 1]).second, tree.leaves_of(tree.nodes[node.second_child]).first);
                EXPECT_EQ(last, tree.leaves_of(tree.nodes[node.second_child]).second);
                continue;
            }
            EXPECT_EQ(last, leaf + 1);
            EXPECT_EQ(node.face_begin, leaf * leaf_faces);
            if (node.face_end != tree.faces.size()) {
                EXPECT_EQ(node.face_end - node.face_begin, leaf_faces);
            }
            for (uint32_t k = node.face_begin; k < node.face_end; ++k) EXPECT_EQ(tree.leaf_of(k), leaf);
            ++leaf;
        }
        EXPECT_EQ(leaf, tree.leaf_count());
    }
}

TEST(ConeTree, CreaseFreeNodesHoldNoCrease) {
    const core::Mesh sphere = test::uv_sphere(20, 10, 1.0);
    const core::EdgeTable table = core::build_edge_table(sphere);
    const ConeTree tree(sphere, table, 4);
    for (const double degrees : {5.0, 20.0, 40.0}) {
        const double angle = degrees * M_PI / 180.0;
        size_t free_nodes = 0;
        for (uint32_t n = 0; n < tree.nodes.size(); ++n) {
            if (!tree.crease_free(n, angle)) continue;
            ++free_nodes;
            const core::internal::ConeNode& node = tree.nodes[n];
            for (uint32_t i = node.face_begin; i < node.face_end; ++i) {
                for (uint32_t j = i + 1; j < node.face_end; ++j) {
                    EXPECT_FALSE(core::is_crease(sphere, tree.faces[i], tree.faces[j], std::cos(angle)));
                }
            }
        }
        if (degrees > 30.0) {
            EXPECT_GT(free_nodes, 0u);
        }
    }
}

}  // namespace
}  // namespace inkline
