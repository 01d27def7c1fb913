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
#include <iterator>
#include <span>

namespace inkline::core {

namespace {

// Where along an edge, from its end with value ga, g is zero (ga and gb of different signs, one
// may be zero): a fraction of the edge.
double zero_along(double ga, double gb) { return std::clamp(ga / (ga - gb), 0.0, 1.0); }

// The zero of g on the edge (a, b) with values ga and gb of different signs (one may be zero).
// Called with a the edge's lower-numbered vertex, so that both faces of an edge agree bit for bit.
glm::dvec3 contour_point_on_edge(const glm::dvec3& a, const glm::dvec3& b, double ga, double gb) {
    return a + (b - a) * zero_along(ga, gb);
}

// Orders crease outline stretches, and finds them, by edge.
struct EdgeOrder {
    bool operator()(const CreaseOutline& a, uint32_t edge) const { return a.edge < edge; }
    bool operator()(uint32_t edge, const CreaseOutline& a) const { return edge < a.edge; }
};

// Per face: whether its connected part of the mesh (faces joined through edges of two faces) has
// no edge of one face, nor of three and more, nor an invalid face.
std::vector<uint8_t> closed_parts(const Mesh& mesh, const EdgeTable& table, std::span<const glm::uvec3> face_edges) {
    const auto n = uint32_t(mesh.triangles.size());
    internal::UnionFind<uint32_t> parts(n);
    std::vector<uint8_t> open(n, 0);
    for (uint32_t f = 0; f < n; ++f) {
        if (!table.face_valid[f]) {
            open[f] = 1;
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            const std::span<const uint32_t> faces = table.faces_of(face_edges[f][k]);
            if (faces.size() == 2) {
                parts.unite(faces[0], faces[1]);
            } else {
                open[f] = 1;
            }
        }
    }
    std::vector<uint8_t> open_part(n, 0), closed(n);
    for (uint32_t f = 0; f < n; ++f) open_part[parts.find(f)] |= open[f];
    for (uint32_t f = 0; f < n; ++f) closed[f] = !open_part[parts.find(f)];
    return closed;
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

std::vector<Chain> cut_crease_outline(std::vector<Chain> creases, const std::vector<CreaseOutline>& outline,
                                      const Mesh& mesh, const EdgeTable& table) {
    if (outline.empty()) return creases;
    auto stretches_of = [&](uint32_t edge) {
        const auto [lo, hi] = std::equal_range(outline.begin(), outline.end(), edge, EdgeOrder{});
        return std::span<const CreaseOutline>(lo, hi);
    };
    std::vector<Chain> out;
    out.reserve(creases.size());
    for (Chain& chain : creases) {
        const bool cut = chain.kind == LineKind::kCrease && !chain.vertices.empty() &&
                         std::any_of(chain.edges.begin(), chain.edges.end(),
                                     [&](uint32_t e) { return !stretches_of(e).empty(); });
        if (!cut) {
            out.push_back(std::move(chain));
            continue;
        }
        // The chain's points, with each stretch on the outline left out between two pieces.
        std::vector<Chain> pieces;
        Chain piece;
        piece.kind = LineKind::kCrease;
        piece.points.emplace_back(mesh.positions[chain.vertices.front()]);
        auto end_piece = [&] {
            if (piece.points.size() >= 2) pieces.push_back(std::move(piece));
            piece = Chain{};
            piece.kind = LineKind::kCrease;
        };
        auto reach = [&](const glm::dvec3& p, uint32_t edge) {
            if (p == piece.points.back()) return;
            piece.points.push_back(p);
            piece.edges.push_back(edge);
        };
        for (size_t i = 0; i < chain.edges.size(); ++i) {
            const uint32_t e = chain.edges[i];
            const bool forward = chain.vertices[i] == table.edge_vertices[e].x;
            const std::span<const CreaseOutline> stretches = stretches_of(e);
            for (size_t k = 0; k < stretches.size(); ++k) {
                const CreaseOutline& s = stretches[forward ? k : stretches.size() - 1 - k];
                reach(forward ? s.p0 : s.p1, e);
                end_piece();
                piece.points.push_back(forward ? s.p1 : s.p0);
            }
            reach(glm::dvec3(mesh.positions[chain.vertices[i + 1]]), e);
        }
        end_piece();
        // A loop cut away from its first vertex: its last piece runs on into its first.
        const glm::dvec3 first(mesh.positions[chain.vertices.front()]);
        if (chain.closed && pieces.size() >= 2 && pieces.front().points.front() == first &&
            pieces.back().points.back() == first) {
            Chain& last = pieces.back();
            last.points.insert(last.points.end(), pieces.front().points.begin() + 1, pieces.front().points.end());
            last.edges.insert(last.edges.end(), pieces.front().edges.begin(), pieces.front().edges.end());
            pieces.erase(pieces.begin());
        }
        std::move(pieces.begin(), pieces.end(), std::back_inserter(out));
    }
    return out;
}

SmoothContourTracer::SmoothContourTracer(const Mesh& mesh, const EdgeTable& table, const SmoothContourOptions& options)
    : options_(options),
      face_edges_(face_edges(mesh, table)),
      closed_(closed_parts(mesh, table, face_edges_)),
      face_used_(mesh.triangles.size(), 0) {}

SmoothContourTracer::~SmoothContourTracer() = default;
SmoothContourTracer::SmoothContourTracer(SmoothContourTracer&&) noexcept = default;
SmoothContourTracer& SmoothContourTracer::operator=(SmoothContourTracer&&) noexcept = default;

void SmoothContourTracer::smooth_pieces(const Mesh& mesh, const EdgeTable& table) {
    core::smooth_pieces(mesh, table, face_edges_, options_.crease_angle_deg, pieces_);
    // The crease edges between two faces: the sides of two faces that are not joined.
    creases_.clear();
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (!table.face_valid[f]) continue;
        for (uint8_t k = 0; k < 3; ++k) {
            if (pieces_.joined[f] & (1u << k)) continue;
            const uint32_t e = face_edges_[f][k];
            const std::span<const uint32_t> faces = table.faces_of(e);
            if (faces.size() != 2) continue;
            const uint32_t other = faces[0] == f ? faces[1] : faces[0];
            if (other < f) continue;
            uint8_t j = 0;
            while (face_edges_[other][j] != e) ++j;
            creases_.push_back({e, {f, other}, {k, j}});
        }
    }
    std::sort(creases_.begin(), creases_.end(), [](const CreaseEdge& a, const CreaseEdge& b) { return a.edge < b.edge; });
}

const std::vector<Chain>& SmoothContourTracer::trace(const Mesh& mesh, const EdgeTable& table,
                                                     const Viewpoint& eye_object) {
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
                                                         pieces_.normals, pieces_.face_groups);
            values_.assign(pieces_.normals.size(), {});
        } else if (options_.deforming) {
            smooth_pieces(mesh, table);
            tree_->refit(mesh, pieces_.normals, pieces_.face_groups);
            values_.resize(pieces_.normals.size());
        }
        if (frame_ == 0xffffffffu) {  // stamps would wrap: forget them all
            for (VertexValue& value : values_) value.stamp = 0;
            frame_ = 0;
        }
        ++frame_;
        mesh_ = &mesh;
        eye_ = eye_object;
        if (!tree_->nodes.empty()) search(0);
    }
    stats_.segments = contour_faces_.size();
    chain(mesh, table);
    for (const uint32_t f : contour_faces_) face_used_[f] = 0;
    mesh_ = &mesh;
    eye_ = eye_object;
    trace_crease_outline(mesh, table);
    mesh_ = nullptr;
    return chains_;
}

double SmoothContourTracer::value(uint32_t group) {
    if (options_.mode != TrackerMode::kBrute) back(group);  // computed once a trace
    return values_[group].g;
}

void SmoothContourTracer::trace_crease_outline(const Mesh& mesh, const EdgeTable& table) {
    crease_outline_.clear();
    for (const CreaseEdge& crease : creases_) {
        const glm::uvec2 ends = table.edge_vertices[crease.edge];  // ends.x < ends.y
        // g at the edge's two vertices on either side, from the corners of that side's face.
        double g0[2], g1[2];
        for (int s = 0; s < 2; ++s) {
            const uint32_t f = crease.face[s], k = crease.side[s];
            const glm::uvec3 groups = pieces_.face_groups[f];
            const bool forward = mesh.triangles[f][k] == ends.x;
            g0[s] = value(groups[forward ? k : (k + 1) % 3]);
            g1[s] = value(groups[forward ? (k + 1) % 3 : k]);
        }
        // Where each side's g changes sign along the edge: the point its contour ends on, bit
        // for bit (the same function and values as chain()'s).
        const glm::dvec3 a(mesh.positions[ends.x]), b(mesh.positions[ends.y]);
        struct Zero {
            double t;
            glm::dvec3 p;
            int side;
        };
        Zero zeros[2];
        int count = 0;
        for (int s = 0; s < 2; ++s) {
            if ((g0[s] > 0.0) == (g1[s] > 0.0)) continue;
            zeros[count++] = {zero_along(g0[s], g1[s]), contour_point_on_edge(a, b, g0[s], g1[s]), s};
        }
        if (count == 2 && zeros[1].t < zeros[0].t) std::swap(zeros[0], zeros[1]);
        // From a to b: a stretch wherever the two sides face opposite ways.
        bool back[2] = {g0[0] > 0.0, g0[1] > 0.0};
        double t_from = 0.0;
        glm::dvec3 p_from = a;
        bool from_vertex = true;
        auto stretch_to = [&](double t, const glm::dvec3& p, bool to_vertex) {
            if (back[0] == back[1] || !(t > t_from) || p == p_from) return;
            crease_outline_.push_back({.edge = crease.edge,
                                       .p0 = p_from,
                                       .p1 = p,
                                       .vertex0 = from_vertex,
                                       .vertex1 = to_vertex,
                                       .face = crease.face[back[0] ? 1 : 0]});
        };
        for (int i = 0; i < count;) {
            const Zero& zero = zeros[i];
            stretch_to(zero.t, zero.p, false);
            for (; i < count && zeros[i].t == zero.t; ++i) back[zeros[i].side] = !back[zeros[i].side];
            t_from = zero.t, p_from = zero.p, from_vertex = false;
        }
        stretch_to(1.0, b, true);
    }

    // Stretches chained through the vertices where exactly two of them meet; a chain ends at a
    // contour's end (a zero) or at a vertex of one stretch or of three and more.
    const size_t n = crease_outline_.size();
    std::vector<std::pair<uint32_t, uint32_t>> at_vertex;  // (vertex, 2 * stretch + end)
    for (uint32_t i = 0; i < n; ++i) {
        const glm::uvec2 ends = table.edge_vertices[crease_outline_[i].edge];
        if (crease_outline_[i].vertex0) at_vertex.emplace_back(ends.x, 2 * i);
        if (crease_outline_[i].vertex1) at_vertex.emplace_back(ends.y, 2 * i + 1);
    }
    std::sort(at_vertex.begin(), at_vertex.end());
    std::vector<uint32_t> partner(2 * n, kNoIndex);
    for (size_t i = 0; i < at_vertex.size();) {
        size_t j = i;
        while (j < at_vertex.size() && at_vertex[j].first == at_vertex[i].first) ++j;
        if (j - i == 2) partner[at_vertex[i].second] = at_vertex[i + 1].second, partner[at_vertex[i + 1].second] = at_vertex[i].second;
        i = j;
    }
    std::vector<uint8_t> used(n, 0);
    auto point = [&](uint32_t end) { return end % 2 ? crease_outline_[end / 2].p1 : crease_outline_[end / 2].p0; };
    // From stretch end `start` along its stretch, on through the vertices.
    auto walk = [&](uint32_t start) {
        Chain chain;
        chain.kind = LineKind::kSilhouette;
        chain.points.push_back(point(start));
        for (uint32_t from = start;;) {
            const CreaseOutline& stretch = crease_outline_[from / 2];
            used[from / 2] = 1;
            chain.edges.push_back(stretch.edge);
            chain.faces.push_back(stretch.face);
            const uint32_t to = from ^ 1u;
            chain.points.push_back(point(to));
            const uint32_t next = partner[to];
            if (next == start) {
                chain.closed = true;
                break;
            }
            if (next == kNoIndex || used[next / 2]) break;
            from = next;
        }
        chains_.push_back(std::move(chain));
    };
    for (uint32_t end = 0; end < 2 * n; ++end) {
        if (!used[end / 2] && partner[end] == kNoIndex) walk(end);
    }
    for (uint32_t i = 0; i < n; ++i) {
        if (!used[i]) walk(2 * i);
    }
}

void SmoothContourTracer::test_every_face(const Mesh& mesh, const EdgeTable& table, const Viewpoint& eye_object) {
    eye_ = eye_object;
    smooth_pieces(mesh, table);
    values_.resize(pieces_.normals.size());
    for (size_t group = 0; group < pieces_.normals.size(); ++group) {
        values_[group].g = corner_value(mesh, uint32_t(group));
    }
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (!table.face_valid[f]) continue;
        ++stats_.faces_tested;
        const glm::uvec3 t = pieces_.face_groups[f];
        const bool b = values_[t.x].back();
        if (values_[t.y].back() != b || values_[t.z].back() != b) contour_faces_.push_back(f);
    }
}

double SmoothContourTracer::facing(const Mesh& mesh, uint32_t face, const glm::dvec3& p) const {
    if (face >= pieces_.face_groups.size() || !closed_[face]) return NAN;  // before a trace, or not closed
    const glm::uvec3 t = mesh.triangles[face], groups = pieces_.face_groups[face];
    // Barycentric coordinates of p (on the face's plane) from the normal equations.
    const glm::dvec3 a(mesh.positions[t.x]), v0 = glm::dvec3(mesh.positions[t.y]) - a,
        v1 = glm::dvec3(mesh.positions[t.z]) - a, v2 = p - a;
    const double d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
    const double d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1);
    const double det = d00 * d11 - d01 * d01;
    if (!(det > 0.0)) return NAN;
    const double u = (d11 * d20 - d01 * d21) / det, v = (d00 * d21 - d01 * d20) / det;
    return (1.0 - u - v) * corner_value(mesh, groups.x) + u * corner_value(mesh, groups.y) +
           v * corner_value(mesh, groups.z);
}

void SmoothContourTracer::set_facing(const Mesh& mesh, Chain& r_chain) const {
    r_chain.facing.clear();
    for (size_t i = 0; i < r_chain.edges.size(); ++i) {
        const glm::dvec3 &p0 = r_chain.points[i], &p1 = r_chain.points[i + 1];
        const uint32_t a = r_chain.first_faces[i], b = r_chain.crossing_faces[i];
        r_chain.facing.push_back(
            {{facing(mesh, a, p0), facing(mesh, a, p1)}, {facing(mesh, b, p0), facing(mesh, b, p1)}});
    }
}

double SmoothContourTracer::corner_value(const Mesh& mesh, uint32_t group) const {
    return -glm::dot(pieces_.normals[group], eye_.toward(glm::dvec3(mesh.positions[pieces_.group_vertex[group]])));
}

bool SmoothContourTracer::back(uint32_t group) {
    VertexValue& value = values_[group];
    if (value.stamp != frame_) {
        value.stamp = frame_;
        value.g = corner_value(*mesh_, group);
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
        const glm::uvec3 t = pieces_.face_groups[f];
        // All three evaluated: chain() reads the values of every corner of a contour face.
        const bool x = back(t.x), y = back(t.y), z = back(t.z);
        if (x != y || y != z) contour_faces_.push_back(f);
    }
}

void SmoothContourTracer::chain(const Mesh& mesh, const EdgeTable& table) {
    // Where the contour crosses the faces' edges: between corners of different signs.
    auto crossed = [&](uint32_t f, uint32_t k) {
        const glm::uvec3 t = pieces_.face_groups[f];
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
        uint32_t ga = pieces_.face_groups[f][k], gb = pieces_.face_groups[f][(k + 1) % 3];
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
            if (!(pieces_.joined[f] >> k & 1u)) break;
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
        if (!(pieces_.joined[c.face] >> c.side & 1u) && !face_used_[c.face]) walk(c.face, c.side);
    }
    for (const Crossing& c : crossings_) {
        if (!face_used_[c.face]) walk(c.face, c.side);
    }
}

}  // namespace inkline::core
