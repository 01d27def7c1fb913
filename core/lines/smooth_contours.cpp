// SPDX-License-Identifier: MIT
#include "core/lines/smooth_contours.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace inkline::core {

glm::dvec3 contour_point_on_edge(const glm::dvec3& a, const glm::dvec3& b, double ga, double gb) {
    const double t = ga / (ga - gb);  // ga and gb differ in sign (one may be zero): t in [0, 1]
    return a + (b - a) * std::clamp(t, 0.0, 1.0);
}

SmoothContourTracer::SmoothContourTracer(const Mesh& mesh, const EdgeTable& table)
    : face_edges_(face_edges(mesh, table)) {}

const std::vector<Chain>& SmoothContourTracer::trace(const Mesh& mesh, const EdgeTable& table,
                                                     const glm::dvec3& eye_object) {
    const size_t n_vertices = mesh.positions.size(), n_faces = mesh.triangles.size();
    chains_.clear();
    stats_ = {};

    // g at every vertex, and its sign.
    const std::vector<glm::dvec3> normals = vertex_normals(mesh);
    std::vector<double> g(n_vertices);
    back_.assign(n_vertices, 0);
    for (size_t v = 0; v < n_vertices; ++v) {
        g[v] = glm::dot(normals[v], glm::dvec3(mesh.positions[v]) - eye_object);
        back_[v] = g[v] > 0.0 ? 1 : 0;
    }

    // The edges the contour crosses: those of faces whose corners differ.
    contour_edges_.clear();
    for (size_t f = 0; f < n_faces; ++f) {
        if (!table.face_valid[f]) continue;
        ++stats_.faces_tested;
        const glm::uvec3 t = mesh.triangles[f];
        if (back_[t.x] == back_[t.y] && back_[t.y] == back_[t.z]) continue;
        ++stats_.segments;
        for (int k = 0; k < 3; ++k) {
            if (back_[t[k]] != back_[t[(k + 1) % 3]]) contour_edges_.push_back(face_edges_[f][k]);
        }
    }
    std::sort(contour_edges_.begin(), contour_edges_.end());
    contour_edges_.erase(std::unique(contour_edges_.begin(), contour_edges_.end()), contour_edges_.end());

    auto point_on = [&](uint32_t e) {
        const glm::uvec2 v = table.edge_vertices[e];
        return contour_point_on_edge(glm::dvec3(mesh.positions[v.x]), glm::dvec3(mesh.positions[v.y]), g[v.x], g[v.y]);
    };
    // The other edge the contour crosses in face f, entered through edge e.
    auto exit_of = [&](uint32_t f, uint32_t e) {
        const glm::uvec3 t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k) {
            const uint32_t edge = face_edges_[f][k];
            if (edge != e && back_[t[k]] != back_[t[(k + 1) % 3]]) return edge;
        }
        return e;  // not reached: a face the contour enters has a second crossed edge
    };
    // A chain passes through an edge of exactly two faces; it ends on any other.
    auto passes = [&](uint32_t e) { return table.faces_of(e).size() == 2; };

    face_used_.assign(n_faces, 0);
    // From edge e into face f, on until the chain ends or comes back to where it began.
    auto walk = [&](uint32_t e, uint32_t f) {
        Chain chain;
        chain.kind = LineKind::kSilhouette;
        const uint32_t first = e;
        chain.points.push_back(point_on(e));
        for (;;) {
            face_used_[f] = 1;
            chain.edges.push_back(e);
            chain.faces.push_back(f);
            e = exit_of(f, e);
            chain.points.push_back(point_on(e));
            if (e == first) {
                chain.closed = true;
                break;
            }
            if (!passes(e)) break;
            const std::span<const uint32_t> faces = table.faces_of(e);
            const uint32_t next = faces[0] == f ? faces[1] : faces[0];
            if (face_used_[next]) break;
            f = next;
        }
        chains_.push_back(std::move(chain));
    };
    // Open chains from their ends first, then the loops that are left.
    for (const uint32_t e : contour_edges_) {
        if (passes(e)) continue;
        for (const uint32_t f : table.faces_of(e)) {
            if (!face_used_[f]) walk(e, f);
        }
    }
    for (const uint32_t e : contour_edges_) {
        if (!passes(e)) continue;
        const uint32_t f = table.faces_of(e)[0];
        if (!face_used_[f]) walk(e, f);
    }
    return chains_;
}

}  // namespace inkline::core
