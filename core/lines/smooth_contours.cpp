// SPDX-License-Identifier: MIT
#include "core/lines/smooth_contours.h"

#include "core/error.h"
#include "core/internal/union_find.h"
#include "core/lines/features.h"
#include "core/lines/internal/cone_tree.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

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

void SmoothContourTracer::smooth_pieces(const Mesh& mesh, const EdgeTable& table) {
    const size_t n_faces = mesh.triangles.size();
    const double cos_crease = std::cos(glm::radians(options_.crease_angle_deg));
    // Corner 3f + c joins the corners of the same vertex in each face across a smooth edge.
    internal::UnionFind<uint32_t> corners(3 * n_faces);
    joined_.assign(n_faces, 0);
    for (uint32_t f = 0; f < n_faces; ++f) {
        if (!table.face_valid[f]) continue;
        const glm::uvec3 t = mesh.triangles[f];
        for (uint32_t k = 0; k < 3; ++k) {
            const std::span<const uint32_t> faces = table.faces_of(face_edges_[f][k]);
            if (faces.size() != 2) continue;
            const uint32_t other = faces[0] == f ? faces[1] : faces[0];
            if (is_crease(mesh, f, other, cos_crease)) continue;
            joined_[f] |= uint8_t(1u << k);
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
    // (area weighted) in face order.
    face_groups_.resize(n_faces);
    group_vertex_.clear();
    std::vector<uint32_t> group_of_root(3 * n_faces, kNoIndex);
    normals_.clear();
    for (uint32_t f = 0; f < n_faces; ++f) {
        const glm::uvec3 t = mesh.triangles[f];
        const glm::dvec3 n = table.face_valid[f] ? face_normal(mesh.positions, t) : glm::dvec3(0.0);
        for (uint32_t c = 0; c < 3; ++c) {
            uint32_t& group = group_of_root[corners.find(3 * f + c)];
            if (group == kNoIndex) {
                group = uint32_t(group_vertex_.size());
                group_vertex_.push_back(t[c]);
                normals_.emplace_back(0.0);
            }
            face_groups_[f][c] = group;
            normals_[group] += n;
        }
    }
    for (glm::dvec3& n : normals_) {
        const double len = glm::length(n);
        n = len > 0.0 ? n / len : glm::dvec3(0.0);
    }
}

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
            smooth_pieces(mesh, table);
            tree_ = std::make_unique<internal::ConeTree>(mesh, table, std::max<uint32_t>(1, options_.leaf_faces),
                                                         normals_, face_groups_);
            values_.assign(normals_.size(), {});
        } else if (options_.deforming) {
            smooth_pieces(mesh, table);
            tree_->refit(mesh, normals_, face_groups_);
            values_.resize(normals_.size());
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
    smooth_pieces(mesh, table);
    values_.resize(normals_.size());
    for (size_t group = 0; group < normals_.size(); ++group) {
        values_[group].g = glm::dot(normals_[group], glm::dvec3(mesh.positions[group_vertex_[group]]) - eye_object);
    }
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (!table.face_valid[f]) continue;
        ++stats_.faces_tested;
        const glm::uvec3 t = face_groups_[f];
        const bool b = values_[t.x].back();
        if (values_[t.y].back() != b || values_[t.z].back() != b) contour_faces_.push_back(f);
    }
}

bool SmoothContourTracer::back(uint32_t group) {
    VertexValue& value = values_[group];
    if (value.stamp != frame_) {
        value.stamp = frame_;
        // The same expression as test_every_face, on the same normals: the same bits.
        value.g = glm::dot(normals_[group], glm::dvec3(mesh_->positions[group_vertex_[group]]) - eye_);
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
        const glm::uvec3 t = face_groups_[f];
        // All three evaluated: chain() reads the values of every corner of a contour face.
        const bool x = back(t.x), y = back(t.y), z = back(t.z);
        if (x != y || y != z) contour_faces_.push_back(f);
    }
}

void SmoothContourTracer::chain(const Mesh& mesh, const EdgeTable& table) {
    // Where the contour crosses the faces' edges: between corners of different signs.
    auto crossed = [&](uint32_t f, uint32_t k) {
        const glm::uvec3 t = face_groups_[f];
        return values_[t[k]].back() != values_[t[(k + 1) % 3]].back();
    };
    crossings_.clear();
    for (const uint32_t f : contour_faces_) {
        for (uint32_t k = 0; k < 3; ++k) {
            if (crossed(f, k)) crossings_.push_back({face_edges_[f][k], f, k});
        }
    }
    std::sort(crossings_.begin(), crossings_.end(), [](const Crossing& a, const Crossing& b) {
        return a.edge != b.edge ? a.edge < b.edge : a.face < b.face;
    });

    // The contour's point on side k of face f, computed from the edge's lower-numbered vertex so
    // that two faces of the same groups agree bit for bit.
    auto point_on = [&](uint32_t f, uint32_t k) {
        uint32_t a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
        uint32_t ga = face_groups_[f][k], gb = face_groups_[f][(k + 1) % 3];
        if (a > b) std::swap(a, b), std::swap(ga, gb);
        return contour_point_on_edge(glm::dvec3(mesh.positions[a]), glm::dvec3(mesh.positions[b]), values_[ga].g,
                                     values_[gb].g);
    };
    // The other side the contour crosses in face f, entered through side k.
    auto exit_of = [&](uint32_t f, uint32_t k) {
        for (uint32_t j = 1; j < 3; ++j) {
            if (crossed(f, (k + j) % 3)) return (k + j) % 3;
        }
        return k;  // not reached: a face the contour enters has a second crossed side
    };

    // From side k into face f, on until the chain ends or comes back to where it began. A chain
    // passes through an edge of two faces of the same groups; it ends on any other.
    auto walk = [&](uint32_t f, uint32_t k) {
        Chain chain;
        chain.kind = LineKind::kSilhouette;
        const uint32_t first = face_edges_[f][k];
        chain.points.push_back(point_on(f, k));
        for (;;) {
            face_used_[f] = 1;
            chain.edges.push_back(face_edges_[f][k]);
            chain.faces.push_back(f);
            k = exit_of(f, k);
            const uint32_t e = face_edges_[f][k];
            chain.points.push_back(point_on(f, k));
            if (e == first) {
                chain.closed = true;
                break;
            }
            if (!(joined_[f] >> k & 1u)) break;
            const std::span<const uint32_t> faces = table.faces_of(e);
            const uint32_t next = faces[0] == f ? faces[1] : faces[0];
            if (face_used_[next]) break;
            f = next;
            k = 0;
            while (face_edges_[f][k] != e) ++k;
        }
        chains_.push_back(std::move(chain));
    };
    // Open chains from their ends first, then the loops that are left.
    for (const Crossing& c : crossings_) {
        if (!(joined_[c.face] >> c.side & 1u) && !face_used_[c.face]) walk(c.face, c.side);
    }
    for (const Crossing& c : crossings_) {
        if (!face_used_[c.face]) walk(c.face, c.side);
    }
}

}  // namespace inkline::core
