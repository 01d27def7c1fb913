// SPDX-License-Identifier: MIT
// Edge table of a triangle soup: every undirected edge with its faces and its neighbours, built
// once per topology. Non-manifold edges (3+ faces) are kept, which OpenMesh's kernel cannot hold.
#pragma once

#include "core/mesh/mesh.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace inkline::core {

inline constexpr uint32_t kNoIndex = 0xffffffffu;

// Edges are numbered in lexicographic order of their (smaller, larger) vertex pair, so an edge
// index can be recomputed from the mesh file alone.
struct EdgeTable {
    std::vector<glm::uvec2> edge_vertices;     // #E, (v0, v1) with v0 < v1
    // 2 per edge: its two faces, ascending; (face, kNoIndex) for an edge of one face; (kNoIndex,
    // k) for an edge of three or more, whose faces are the k-th run of many_faces. Every edge has
    // a face; no offsets are kept for the common cases (6 MB at 1.5M edges).
    std::vector<uint32_t> edge_faces;
    std::vector<uint32_t> many_face_offsets;   // CSR offsets into many_faces, one run per edge of 3+ faces
    std::vector<uint32_t> many_faces;          // faces of those edges, ascending within a run
    std::vector<uint8_t> face_valid;           // #F, 0 for degenerate and duplicate faces (ignored everywhere)
    size_t duplicate_faces = 0;                // faces repeating an earlier face's three vertices
    std::vector<uint32_t> vertex_edge_offsets; // #V+1, CSR offsets into vertex_edges
    std::vector<uint32_t> vertex_edges;        // edges around each vertex, ascending

    size_t edge_count() const { return edge_vertices.size(); }
    std::span<const uint32_t> faces_of(uint32_t edge) const {
        const uint32_t* pair = edge_faces.data() + 2 * size_t(edge);
        if (pair[0] != kNoIndex) return {pair, pair[1] == kNoIndex ? 1u : 2u};
        const uint32_t run = pair[1];
        return {many_faces.data() + many_face_offsets[run], many_face_offsets[run + 1] - many_face_offsets[run]};
    }
    std::span<const uint32_t> edges_around(uint32_t vertex) const {
        return {vertex_edges.data() + vertex_edge_offsets[vertex],
                vertex_edge_offsets[vertex + 1] - vertex_edge_offsets[vertex]};
    }
    // An interior edge has exactly two faces; one or three and more count as boundary.
    bool is_interior(uint32_t edge) const {
        const uint32_t* pair = edge_faces.data() + 2 * size_t(edge);
        return pair[0] != kNoIndex && pair[1] != kNoIndex;
    }
    uint32_t other_vertex(uint32_t edge, uint32_t vertex) const {
        const glm::uvec2 v = edge_vertices[edge];
        return v.x == vertex ? v.y : v.x;
    }
};

// Builds the table; faces with a repeated vertex or zero area, and later copies of a face with
// the same three vertices, are marked invalid and left out.
EdgeTable build_edge_table(const Mesh& mesh);

// The index of the edge (a, b) in either order, or kNoIndex if no valid face has it.
uint32_t find_edge(const EdgeTable& table, uint32_t a, uint32_t b);

// The edges (c0c1, c1c2, c2c0) of each face; kNoIndex for the ignored faces (degenerate, copies).
std::vector<glm::uvec3> face_edges(const Mesh& mesh, const EdgeTable& table);

// The valid faces that share a corner with `face` (itself included), ascending, into r_faces.
void faces_around_corners(const Mesh& mesh, const EdgeTable& table, uint32_t face, std::vector<uint32_t>& r_faces);

// What `inkline info` prints about a mesh.
struct MeshReport {
    size_t vertices = 0;
    size_t faces = 0;
    size_t edges = 0;
    size_t boundary_edges = 0;        // exactly one face
    size_t non_manifold_edges = 0;    // three or more faces
    size_t non_manifold_vertices = 0; // faces around the vertex form more than one fan
    size_t degenerate_faces = 0;
    size_t duplicate_faces = 0;       // same three vertices as an earlier face
    size_t inconsistent_edges = 0;    // interior edges whose two faces disagree in orientation
    size_t connected_components = 0;  // of valid faces joined by edges
};

// kWarnings leaves connected_components at 0: mesh_warnings does not need them, and counting them
// is a serial pass over every face.
enum class MeshReportScope { kAll, kWarnings };
MeshReport describe_mesh(const Mesh& mesh, const EdgeTable& table, MeshReportScope scope = MeshReportScope::kAll);

// Warnings for drawable oddities (degenerate faces, non-manifold edges and vertices, inconsistent
// orientation).
std::vector<std::string> mesh_warnings(const MeshReport& report);

}  // namespace inkline::core
