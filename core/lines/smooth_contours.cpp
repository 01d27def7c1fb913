// SPDX-License-Identifier: MIT
#include "core/lines/smooth_contours.h"

#include "core/error.h"
#include "core/lines/internal/cone_tree.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <glm/geometric.hpp>

#include <algorithm>

namespace inkline::core {

namespace {

// The zero of g on the edge (a, b) with values ga and gb of different signs (one may be zero).
// Called with a the edge's lower-numbered vertex, so that both faces of an edge agree bit for bit.
glm::dvec3 contour_point_on_edge(const glm::dvec3& a, const glm::dvec3& b, double ga, double gb) {
    const double t = ga / (ga - gb);
    return a + (b - a) * std::clamp(t, 0.0, 1.0);
}

}  // namespace

std::vector<uint32_t> faces_crossed(const Mesh& mesh, const EdgeTable& table, std::span<const glm::dvec3> points_object,
                                    std::span<const uint32_t> edges) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    auto point = [](const glm::dvec3& p) { return Kernel::Point_3(p.x, p.y, p.z); };
    std::vector<uint32_t> out;
    out.reserve(edges.size());
    for (size_t i = 0; i < edges.size() && i + 1 < points_object.size(); ++i) {
        const Kernel::Point_3 mid = point(0.5 * (points_object[i] + points_object[i + 1]));
        uint32_t best = kNoIndex;
        double best_d2 = HUGE_VAL;
        for (const uint32_t f : table.faces_of(edges[i])) {
            const glm::uvec3 t = mesh.triangles[f];
            const Kernel::Triangle_3 tri(point(glm::dvec3(mesh.positions[t.x])), point(glm::dvec3(mesh.positions[t.y])),
                                         point(glm::dvec3(mesh.positions[t.z])));
            const double d2 = CGAL::to_double(CGAL::squared_distance(mid, tri));
            if (d2 < best_d2) best_d2 = d2, best = f;
        }
        out.push_back(best);
    }
    return out;
}

SmoothContourTracer::SmoothContourTracer(const Mesh& mesh, const EdgeTable& table, const SmoothContourOptions& options)
    : options_(options), face_edges_(face_edges(mesh, table)), face_used_(mesh.triangles.size(), 0) {}

SmoothContourTracer::~SmoothContourTracer() = default;
SmoothContourTracer::SmoothContourTracer(SmoothContourTracer&&) noexcept = default;
SmoothContourTracer& SmoothContourTracer::operator=(SmoothContourTracer&&) noexcept = default;

const std::vector<Chain>& SmoothContourTracer::trace(const Mesh& mesh, const EdgeTable& table,
                                                     const glm::dvec3& eye_object) {
    INKLINE_CHECK_EQ(mesh.triangles.size(), face_edges_.size());
    chains_.clear();
    contour_faces_.clear();
    stats_ = {};
    if (options_.mode == TrackerMode::kBrute) {
        test_every_face(mesh, table, eye_object);
    } else {
        if (!tree_) {
            normals_ = vertex_normals(mesh);
            tree_ = std::make_unique<internal::ConeTree>(mesh, table, std::max<uint32_t>(1, options_.leaf_faces),
                                                         normals_);
            values_.assign(mesh.positions.size(), {});
        } else if (options_.deforming) {
            normals_ = vertex_normals(mesh);
            tree_->refit(mesh, normals_);
        }
        if (frame_ == 0xffffffffu) {  // stamps would wrap: forget them all
            for (VertexValue& value : values_) value.stamp = 0;
            frame_ = 0;
        }
        ++frame_;
        mesh_ = &mesh;
        eye_ = eye_object;
        if (!tree_->nodes.empty()) search(0);
        mesh_ = nullptr;
    }
    stats_.segments = contour_faces_.size();
    chain(mesh, table);
    for (const uint32_t f : contour_faces_) face_used_[f] = 0;
    return chains_;
}

void SmoothContourTracer::test_every_face(const Mesh& mesh, const EdgeTable& table, const glm::dvec3& eye_object) {
    const std::vector<glm::dvec3> normals = vertex_normals(mesh);
    values_.resize(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        values_[v].g = glm::dot(normals[v], glm::dvec3(mesh.positions[v]) - eye_object);
    }
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (!table.face_valid[f]) continue;
        ++stats_.faces_tested;
        const glm::uvec3 t = mesh.triangles[f];
        const bool b = values_[t.x].back();
        if (values_[t.y].back() != b || values_[t.z].back() != b) contour_faces_.push_back(f);
    }
}

bool SmoothContourTracer::back(uint32_t vertex) {
    VertexValue& value = values_[vertex];
    if (value.stamp != frame_) {
        value.stamp = frame_;
        // The same expression as test_every_face, on the same normals: the same bits.
        value.g = glm::dot(normals_[vertex], glm::dvec3(mesh_->positions[vertex]) - eye_);
    }
    return value.back();
}

void SmoothContourTracer::search(uint32_t index) {
    ++stats_.nodes_visited;
    if (tree_->facing(index, eye_) != internal::ClusterFacing::kUnknown) return;  // all corners alike
    const internal::ConeNode& node = tree_->nodes[index];
    if (!node.is_leaf()) {
        search(index + 1);
        search(node.second_child);
        return;
    }
    for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
        const uint32_t f = tree_->faces[k];
        ++stats_.faces_tested;
        const glm::uvec3 t = mesh_->triangles[f];
        const bool b = back(t.x);
        if (back(t.y) != b || back(t.z) != b) contour_faces_.push_back(f);
    }
}

void SmoothContourTracer::chain(const Mesh& mesh, const EdgeTable& table) {
    // The edges the contour crosses: those of faces whose corners differ.
    contour_edges_.clear();
    for (const uint32_t f : contour_faces_) {
        const glm::uvec3 t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k) {
            if (values_[t[k]].back() != values_[t[(k + 1) % 3]].back()) contour_edges_.push_back(face_edges_[f][k]);
        }
    }
    std::sort(contour_edges_.begin(), contour_edges_.end());
    contour_edges_.erase(std::unique(contour_edges_.begin(), contour_edges_.end()), contour_edges_.end());

    auto point_on = [&](uint32_t e) {
        const glm::uvec2 v = table.edge_vertices[e];
        return contour_point_on_edge(glm::dvec3(mesh.positions[v.x]), glm::dvec3(mesh.positions[v.y]), values_[v.x].g, values_[v.y].g);
    };
    // The other edge the contour crosses in face f, entered through edge e.
    auto exit_of = [&](uint32_t f, uint32_t e) {
        const glm::uvec3 t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k) {
            const uint32_t edge = face_edges_[f][k];
            if (edge != e && values_[t[k]].back() != values_[t[(k + 1) % 3]].back()) return edge;
        }
        return e;  // not reached: a face the contour enters has a second crossed edge
    };
    // A chain passes through an edge of exactly two faces; it ends on any other.
    auto passes = [&](uint32_t e) { return table.faces_of(e).size() == 2; };

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
}

}  // namespace inkline::core
