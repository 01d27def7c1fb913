// SPDX-License-Identifier: MIT
#include "core/lines/smooth_pieces.h"

#include "core/internal/union_find.h"
#include "core/lines/features.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace inkline::core {

void smooth_pieces(const Mesh& mesh, const EdgeTable& table, std::span<const glm::uvec3> face_edges,
                   double crease_angle_deg, SmoothPieces& r_pieces) {
    const size_t n_faces = mesh.triangles.size();
    const double cos_crease = std::cos(glm::radians(crease_angle_deg));
    // Corner 3f + c joins the corners of the same vertex in each face across a smooth edge.
    internal::UnionFind<uint32_t> corners(3 * n_faces);
    r_pieces.joined.assign(n_faces, 0);
    for (uint32_t f = 0; f < n_faces; ++f) {
        if (!table.face_valid[f]) continue;
        const glm::uvec3 t = mesh.triangles[f];
        for (uint32_t k = 0; k < 3; ++k) {
            const std::span<const uint32_t> faces = table.faces_of(face_edges[f][k]);
            if (faces.size() != 2) continue;
            const uint32_t other = faces[0] == f ? faces[1] : faces[0];
            if (is_crease(mesh, f, other, cos_crease)) continue;
            r_pieces.joined[f] |= uint8_t(1u << k);
            if (other < f) continue;  // joined from the lower face
            const glm::uvec3 o = mesh.triangles[other];
            for (const uint32_t c : {k, (k + 1) % 3}) {
                for (uint32_t d = 0; d < 3; ++d) {
                    if (o[d] == t[c]) corners.unite(3 * f + c, 3 * other + d);
                }
            }
        }
    }
    // Groups numbered in order of their first corner; each group's normal sums its faces' normals
    // (area weighted) in face order, as vertex_normals does.
    r_pieces.face_groups.resize(n_faces);
    r_pieces.group_vertex.clear();
    r_pieces.normals.clear();
    std::vector<uint32_t> group_of_root(3 * n_faces, kNoIndex);
    for (uint32_t f = 0; f < n_faces; ++f) {
        const glm::uvec3 t = mesh.triangles[f];
        const glm::dvec3 n = table.face_valid[f] ? face_normal(mesh.positions, t) : glm::dvec3(0.0);
        for (uint32_t c = 0; c < 3; ++c) {
            uint32_t& group = group_of_root[corners.find(3 * f + c)];
            if (group == kNoIndex) {
                group = uint32_t(r_pieces.group_vertex.size());
                r_pieces.group_vertex.push_back(t[c]);
                r_pieces.normals.emplace_back(0.0);
            }
            r_pieces.face_groups[f][c] = group;
            r_pieces.normals[group] += n;
        }
    }
    for (glm::dvec3& n : r_pieces.normals) {
        const double len = glm::length(n);
        n = len > 0.0 ? n / len : glm::dvec3(0.0);
    }
}

}  // namespace inkline::core
