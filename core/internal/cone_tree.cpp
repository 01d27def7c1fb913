// SPDX-License-Identifier: MIT
#include "core/internal/cone_tree.h"

#include "core/error.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace inkline::core::internal {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// The cone test must only skip faces whose facing sign is certain. Its own arithmetic is exact
// to about 1e-15 relative; demanding this much more keeps every rounding step far inside.
constexpr double kConeMargin = 1e-9;

// The anchor box is grown by this fraction of the coordinates' magnitude, which covers the
// rounding of eye - centroid (about 1e-16 of it) in both facing_value and the test.
constexpr double kBoxPad = 1e-12;

// is_crease compares cosines, which resolve angles near zero only to about 1.5e-8 rad; a node
// counts as crease-free only this far below the crease angle.
constexpr double kCreaseMargin = 1e-6;

// Chord between two unit vectors at 90 degrees (sqrt 2): a cone this wide proves no facing.
constexpr double kMaxSpread = 1.4142135623730951;

// Weight of a node's centroid spread (relative to the whole mesh's diagonal) against its spread
// of unit normals when choosing the split: both widen the cone test's uncertain band by about
// that angle for an eye a mesh diagonal away.
constexpr double kPositionWeight = 1.0;

double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

}  // namespace

ConeTree::ConeTree(const Mesh& mesh, const EdgeTable& table, uint32_t leaf_faces) {
    INKLINE_CHECK(leaf_faces >= 1);
    const size_t n_faces = mesh.triangles.size();
    struct Item {
        FaceCone cone;
        uint32_t face;
    };
    std::vector<Item> items;
    for (uint32_t f = 0; f < n_faces; ++f) {
        if (table.face_valid[f]) items.push_back({face_cone(mesh, f), f});
    }
    face_position.assign(n_faces, kNoIndex);
    if (items.empty()) return;

    // Top-down median splits, depth first so that a traversal reads the nodes in order.
    Bounds all;
    for (const Item& item : items) all.add(item.cone.centroid);
    const double diagonal = std::max(2.0 * all.radius(), std::numeric_limits<double>::min());
    std::vector<uint32_t> face_leaf(n_faces, kNoIndex);
    std::vector<uint32_t> parent, depth;
    auto split = [&](auto& self, uint32_t begin, uint32_t end, uint32_t up) -> uint32_t {
        const uint32_t index = uint32_t(nodes.size());
        nodes.push_back({.face_begin = begin, .face_end = end});
        parent.push_back(up);
        depth.push_back(up == kNoIndex ? 0 : depth[up] + 1);
        if (end - begin <= leaf_faces) {
            for (uint32_t k = begin; k < end; ++k) face_leaf[items[k].face] = index;
            return index;
        }
        // Split along the widest of three centroid axes and three normal components.
        glm::dvec3 p_min(std::numeric_limits<double>::max()), p_max(-std::numeric_limits<double>::max());
        glm::dvec3 n_min(2.0), n_max(-2.0);
        for (uint32_t k = begin; k < end; ++k) {
            p_min = glm::min(p_min, items[k].cone.centroid);
            p_max = glm::max(p_max, items[k].cone.centroid);
            n_min = glm::min(n_min, items[k].cone.normal);
            n_max = glm::max(n_max, items[k].cone.normal);
        }
        const glm::dvec3 p_spread = kPositionWeight * (p_max - p_min) / diagonal;
        const glm::dvec3 n_spread = n_max - n_min;
        int key = 0;
        double widest = -1.0;
        for (int k = 0; k < 6; ++k) {
            const double spread = k < 3 ? p_spread[k] : n_spread[k - 3];
            if (spread > widest) widest = spread, key = k;
        }
        auto value = [key](const Item& item) {
            return key < 3 ? item.cone.centroid[key] : item.cone.normal[key - 3];
        };
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                         [&](const Item& a, const Item& b) { return value(a) < value(b); });
        self(self, begin, mid, index);
        const uint32_t second = self(self, mid, end, index);
        nodes[index].second_child = second;
        return index;
    };
    split(split, 0, uint32_t(items.size()), kNoIndex);
    faces.resize(items.size());
    cones_.resize(items.size());
    for (uint32_t k = 0; k < items.size(); ++k) {
        faces[k] = items[k].face;
        cones_[k] = items[k].cone;
        face_position[faces[k]] = k;
    }
    items = {};
    for (ConeNode& node : nodes) fit_node(node);

    // Each interior edge goes to the deepest node holding both its faces (counting sort).
    std::vector<uint32_t> edge_node(table.edge_count(), kNoIndex);
    std::vector<uint32_t> offsets(nodes.size() + 1, 0);
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        if (!table.is_interior(e)) continue;
        const auto pair = table.faces_of(e);
        uint32_t a = face_leaf[pair[0]], b = face_leaf[pair[1]];
        while (a != b) {
            if (depth[a] >= depth[b]) {
                a = parent[a];
            } else {
                b = parent[b];
            }
        }
        edge_node[e] = a;
        ++offsets[a + 1];
    }
    for (size_t i = 0; i < nodes.size(); ++i) offsets[i + 1] += offsets[i];
    edges.resize(offsets.back());
    for (uint32_t i = 0; i < nodes.size(); ++i) {
        nodes[i].edge_begin = offsets[i];
        nodes[i].edge_end = offsets[i + 1];
    }
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        if (edge_node[e] == kNoIndex) continue;
        uint32_t f0 = table.faces_of(e)[0], f1 = table.faces_of(e)[1];
        if (face_position[f0] > face_position[f1]) std::swap(f0, f1);
        edges[offsets[edge_node[e]]++] = {e, {f0, f1}, {face_position[f0], face_position[f1]}};
    }
    for (ConeNode& node : nodes) {
        if (!node.is_leaf()) {
            std::sort(edges.begin() + node.edge_begin, edges.begin() + node.edge_end,
                      [](const ListedEdge& a, const ListedEdge& b) { return a.position[0] < b.position[0]; });
        }
        node.span_begin = uint32_t(spans.size());
        for (uint32_t k = node.edge_begin; k < node.edge_end; k += kSpanEdges) {
            EdgeSpan span{kNoIndex, 0, kNoIndex, 0};
            for (uint32_t i = k; i < std::min(k + kSpanEdges, node.edge_end); ++i) {
                span.first_min = std::min(span.first_min, edges[i].position[0]);
                span.first_max = std::max(span.first_max, edges[i].position[0]);
                span.second_min = std::min(span.second_min, edges[i].position[1]);
                span.second_max = std::max(span.second_max, edges[i].position[1]);
            }
            spans.push_back(span);
        }
    }
    cones_ = {};  // a static mesh never needs them again; refit recomputes them
}

ConeTree::FaceCone ConeTree::face_cone(const Mesh& mesh, uint32_t face) {
    // The same expressions as facing_value, so that the cones bound the values it computes.
    const glm::uvec3 t = mesh.triangles[face];
    const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    FaceCone fc{.centroid = (a + b + c) / 3.0, .normal = glm::dvec3(0.0, 0.0, 1.0), .error = 1.0};
    if (!(len > 0.0)) return fc;
    fc.normal = n / len;
    // Relative error of facing_value's normal against this one, were they rounded differently
    // (about 12 ulp of |b-a||c-a| per cross product, large for slivers), plus the rounding of
    // eye - centroid and of the dot product.
    const double edges2 = glm::dot(b - a, b - a) * glm::dot(c - a, c - a);
    fc.error = std::min(1.0, 8.0 * kEpsilon * (std::sqrt(edges2) / len + 1.0));
    return fc;
}

void ConeTree::fit_node(ConeNode& node) const {
    glm::dvec3 sum(0.0);
    node.box_min = glm::dvec3(std::numeric_limits<double>::max());
    node.box_max = glm::dvec3(-std::numeric_limits<double>::max());
    node.error = 0.0;
    for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
        const FaceCone& fc = cones_[k];
        sum += fc.normal;
        node.box_min = glm::min(node.box_min, fc.centroid);
        node.box_max = glm::max(node.box_max, fc.centroid);
        node.error = std::max(node.error, fc.error);
    }
    const double len = glm::length(sum);
    if (!(len > 1e-6 * double(node.face_end - node.face_begin))) {
        node.axis = glm::dvec3(0.0, 0.0, 1.0);
        set_spread(node, 2.0);
        return;
    }
    node.axis = sum / len;
    double spread2 = 0.0;
    for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
        const glm::dvec3 d = cones_[k].normal - node.axis;
        spread2 = std::max(spread2, glm::dot(d, d));
    }
    set_spread(node, std::sqrt(spread2));
}

void ConeTree::set_spread(ConeNode& node, double spread) {
    // A unit normal n with |n - axis| <= r makes an angle of at most alpha with the axis,
    // where r = 2 sin(alpha / 2).
    node.spread = std::min(2.0, spread);
    const double r = node.spread;
    node.cos_alpha = 1.0 - 0.5 * r * r;
    node.sin_alpha = r * std::sqrt(std::max(0.0, 1.0 - 0.25 * r * r));
}

void ConeTree::refit(const Mesh& mesh) {
    cones_.resize(faces.size());
    for (size_t i = nodes.size(); i-- > 0;) {
        ConeNode& node = nodes[i];
        if (node.is_leaf()) {
            // Each face belongs to one leaf: fit it while its cones are in cache.
            for (uint32_t k = node.face_begin; k < node.face_end; ++k) cones_[k] = face_cone(mesh, faces[k]);
            fit_node(node);
            continue;
        }
        const ConeNode& l = nodes[i + 1];
        const ConeNode& r = nodes[node.second_child];
        node.box_min = glm::min(l.box_min, r.box_min);
        node.box_max = glm::max(l.box_max, r.box_max);
        node.error = std::max(l.error, r.error);
        const glm::dvec3 sum = double(l.face_end - l.face_begin) * l.axis + double(r.face_end - r.face_begin) * r.axis;
        const double len = glm::length(sum);
        if (!(len > 1e-6 * double(node.face_end - node.face_begin)) || l.spread >= 2.0 || r.spread >= 2.0) {
            set_spread(node, 2.0);
            continue;
        }
        // Every normal lies within the child's spread of the child's axis (triangle inequality).
        node.axis = sum / len;
        set_spread(node, std::max(glm::length(l.axis - node.axis) + l.spread, glm::length(r.axis - node.axis) + r.spread));
    }
}

ClusterFacing ConeTree::facing(uint32_t index, const glm::dvec3& eye) const {
    const ConeNode& node = nodes[index];
    if (!(node.spread < kMaxSpread)) return ClusterFacing::kUnknown;

    // Over the box, v = eye - centroid has axis . v within along +- reach and |v| <= farthest.
    const double pad = kBoxPad * std::max({max_abs(eye), max_abs(node.box_min), max_abs(node.box_max)});
    const glm::dvec3 center = 0.5 * (node.box_min + node.box_max);
    const glm::dvec3 half = 0.5 * (node.box_max - node.box_min) + pad;
    const glm::dvec3 to_eye = eye - center;
    const double along = glm::dot(node.axis, to_eye);
    const double reach = glm::dot(glm::abs(node.axis), half);
    double nearest;  // least |axis . v| over the box, on the side the box lies
    ClusterFacing side;
    if (along - reach > 0.0) {
        nearest = along - reach;
        side = ClusterFacing::kFront;
    } else if (along + reach < 0.0) {
        nearest = -(along + reach);
        side = ClusterFacing::kBack;
    } else {
        return ClusterFacing::kUnknown;
    }
    // v makes at most theta with +-axis, cos theta >= c0 = nearest / farthest, and n at most
    // alpha, so +-n . v >= |v| cos(theta + alpha), which must beat facing_value's relative error
    // m: c0 cos alpha - sqrt(1 - c0^2) sin alpha > m, here multiplied by farthest and squared.
    const glm::dvec3 far_corner = glm::abs(to_eye) + half;
    const double farthest2 = glm::dot(far_corner, far_corner);
    const double m = node.error + kConeMargin;
    const double lhs = nearest * node.cos_alpha - m * std::sqrt(farthest2);
    if (!(lhs > 0.0)) return ClusterFacing::kUnknown;
    const double rest2 = std::max(0.0, farthest2 - nearest * nearest) * node.sin_alpha * node.sin_alpha;
    return lhs * lhs > rest2 ? side : ClusterFacing::kUnknown;
}

bool ConeTree::maybe_crease(const ListedEdge& edge, double cos_crease) const {
    INKLINE_CHECK_EQ(cones_.size(), faces.size());
    // Unit normals within error of is_crease's own directions: their cosine is within the sum.
    const FaceCone& a = cones_[edge.position[0]];
    const FaceCone& b = cones_[edge.position[1]];
    return glm::dot(a.normal, b.normal) - (a.error + b.error + kConeMargin) < cos_crease;
}

bool ConeTree::crease_free(uint32_t index, double crease_angle_rad) const {
    const ConeNode& node = nodes[index];
    if (!(node.spread < 2.0)) return false;
    // Two normals within alpha of the axis are within 2 alpha of each other.
    const double alpha = 2.0 * std::asin(0.5 * node.spread);
    return 2.0 * alpha + 2.0 * node.error + kCreaseMargin < crease_angle_rad;
}

}  // namespace inkline::core::internal
