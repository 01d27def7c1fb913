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

// Chord between two unit vectors at 90 degrees: a cone this wide proves no facing.
const double kMaxSpread = std::sqrt(2.0);

// Weight of a node's centroid spread (relative to the whole mesh's diagonal) against its spread
// of unit normals when choosing the split: both widen the cone test's uncertain band by about
// that angle for an eye a mesh diagonal away.
constexpr double kPositionWeight = 1.0;

double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

}  // namespace

ConeTree::ConeTree(const Mesh& mesh, const EdgeTable& table, uint32_t leaf_faces) {
    INKLINE_CHECK(leaf_faces >= 1);
    fit_faces(mesh);
    const size_t n_faces = mesh.triangles.size();
    face_leaf.assign(n_faces, kNoIndex);
    for (uint32_t f = 0; f < n_faces; ++f) {
        if (table.face_valid[f]) faces.push_back(f);
    }
    if (faces.empty()) return;

    // Top-down median splits, breadth first so that a parent always precedes its children.
    Bounds all;
    for (uint32_t f : faces) all.add(face_cones_[f].centroid);
    const double diagonal = std::max(2.0 * all.radius(), std::numeric_limits<double>::min());
    nodes.push_back({.face_begin = 0, .face_end = uint32_t(faces.size())});
    for (uint32_t i = 0; i < nodes.size(); ++i) {
        fit_leaf(nodes[i]);
        const uint32_t begin = nodes[i].face_begin, end = nodes[i].face_end;
        if (end - begin <= leaf_faces) {
            for (uint32_t k = begin; k < end; ++k) face_leaf[faces[k]] = i;
            continue;
        }
        // Split along the widest of three centroid axes and three normal components.
        glm::dvec3 n_min(2.0), n_max(-2.0);
        for (uint32_t k = begin; k < end; ++k) {
            n_min = glm::min(n_min, face_cones_[faces[k]].normal);
            n_max = glm::max(n_max, face_cones_[faces[k]].normal);
        }
        const glm::dvec3 p_spread = kPositionWeight * (nodes[i].box_max - nodes[i].box_min) / diagonal;
        const glm::dvec3 n_spread = n_max - n_min;
        int key = 0;
        double widest = -1.0;
        for (int k = 0; k < 6; ++k) {
            const double s = k < 3 ? p_spread[k] : n_spread[k - 3];
            if (s > widest) widest = s, key = k;
        }
        auto value = [&](uint32_t f) {
            return key < 3 ? face_cones_[f].centroid[key] : face_cones_[f].normal[key - 3];
        };
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(faces.begin() + begin, faces.begin() + mid, faces.begin() + end,
                         [&](uint32_t a, uint32_t b) { return value(a) < value(b); });
        nodes[i].first_child = uint32_t(nodes.size());
        nodes.push_back({.face_begin = begin, .face_end = mid, .parent = i});
        nodes.push_back({.face_begin = mid, .face_end = end, .parent = i});
    }

    // Each interior edge goes to the deepest node holding both its faces (counting sort).
    std::vector<uint32_t> depth(nodes.size(), 0);
    for (uint32_t i = 1; i < nodes.size(); ++i) depth[i] = depth[nodes[i].parent] + 1;
    std::vector<uint32_t> edge_node(table.edge_count(), kNoIndex);
    std::vector<uint32_t> offsets(nodes.size() + 1, 0);
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        if (!table.is_interior(e)) continue;
        const auto pair = table.faces_of(e);
        uint32_t a = face_leaf[pair[0]], b = face_leaf[pair[1]];
        while (a != b) {
            if (depth[a] >= depth[b]) {
                a = nodes[a].parent;
            } else {
                b = nodes[b].parent;
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
        if (edge_node[e] != kNoIndex) edges[offsets[edge_node[e]]++] = e;
    }
    face_cones_ = {};  // a static mesh never needs it again; refit rebuilds it
}

void ConeTree::fit_faces(const Mesh& mesh) {
    face_cones_.resize(mesh.triangles.size());
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
        // The same expressions as facing_value, so the cones bound the values it computes.
        const glm::uvec3 t = mesh.triangles[f];
        const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double len = glm::length(n);
        FaceCone& fc = face_cones_[f];
        fc.centroid = (a + b + c) / 3.0;
        if (!(len > 0.0)) {
            fc.normal = glm::dvec3(0.0, 0.0, 1.0);
            fc.error = 1.0;
            continue;
        }
        fc.normal = n / len;
        // Relative error of facing_value's normal against this one, were they rounded
        // differently (about 12 ulp of |b-a||c-a| per cross product, large for slivers), plus
        // the rounding of eye - centroid and of the dot product.
        fc.error = std::min(1.0, 8.0 * kEpsilon * (glm::length(b - a) * glm::length(c - a) / len + 1.0));
    }
}

void ConeTree::fit_leaf(ConeNode& node) const {
    glm::dvec3 sum(0.0);
    Bounds box;
    node.error = 0.0;
    for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
        const FaceCone& fc = face_cones_[faces[k]];
        sum += fc.normal;
        box.add(fc.centroid);
        node.error = std::max(node.error, fc.error);
    }
    node.box_min = box.min;
    node.box_max = box.max;
    const double len = glm::length(sum);
    if (!(len > 1e-6 * double(node.face_end - node.face_begin))) {
        node.axis = glm::dvec3(0.0, 0.0, 1.0);
        node.spread = 2.0;
        return;
    }
    node.axis = sum / len;
    node.spread = 0.0;
    for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
        node.spread = std::max(node.spread, glm::length(face_cones_[faces[k]].normal - node.axis));
    }
}

void ConeTree::refit(const Mesh& mesh) {
    fit_faces(mesh);
    for (size_t i = nodes.size(); i-- > 0;) {
        ConeNode& node = nodes[i];
        if (node.is_leaf()) {
            fit_leaf(node);
            continue;
        }
        const ConeNode& l = nodes[node.first_child];
        const ConeNode& r = nodes[node.first_child + 1];
        node.box_min = glm::min(l.box_min, r.box_min);
        node.box_max = glm::max(l.box_max, r.box_max);
        node.error = std::max(l.error, r.error);
        const glm::dvec3 sum = double(l.face_end - l.face_begin) * l.axis + double(r.face_end - r.face_begin) * r.axis;
        const double len = glm::length(sum);
        if (!(len > 1e-6 * double(node.face_end - node.face_begin)) || l.spread >= 2.0 || r.spread >= 2.0) {
            node.spread = 2.0;
            continue;
        }
        // Every normal lies within the child's spread of the child's axis (triangle inequality).
        node.axis = sum / len;
        node.spread = std::min(2.0, std::max(glm::length(l.axis - node.axis) + l.spread,
                                             glm::length(r.axis - node.axis) + r.spread));
    }
}

ClusterFacing ConeTree::facing(uint32_t index, const glm::dvec3& eye) const {
    const ConeNode& node = nodes[index];
    if (!(node.spread < kMaxSpread)) return ClusterFacing::kUnknown;
    // A unit normal n with |n - axis| <= r makes an angle of at most alpha with the axis.
    const double r = node.spread;
    const double cos_alpha = 1.0 - 0.5 * r * r;
    const double sin_alpha = r * std::sqrt(1.0 - 0.25 * r * r);

    // Over the box, v = eye - centroid has axis . v within along +- reach and |v| <= farthest.
    const double pad = kBoxPad * std::max({max_abs(eye), max_abs(node.box_min), max_abs(node.box_max)});
    const glm::dvec3 center = 0.5 * (node.box_min + node.box_max);
    const glm::dvec3 half = 0.5 * (node.box_max - node.box_min) + pad;
    const glm::dvec3 to_eye = eye - center;
    const double along = glm::dot(node.axis, to_eye);
    const double reach = glm::dot(glm::abs(node.axis), half);
    const double farthest = glm::length(glm::abs(to_eye) + half);
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
    // v makes at most theta = acos(c0) with +-axis and n at most alpha with it, so
    // +-n . v >= |v| cos(theta + alpha), which must beat facing_value's relative error.
    const double c0 = std::min(1.0, nearest / farthest);
    const double s0 = std::sqrt(std::max(0.0, 1.0 - c0 * c0));
    const double cos_sum = c0 * cos_alpha - s0 * sin_alpha;
    return cos_sum > node.error + kConeMargin ? side : ClusterFacing::kUnknown;
}

bool ConeTree::crease_free(uint32_t index, double crease_angle_rad) const {
    const ConeNode& node = nodes[index];
    if (!(node.spread < 2.0)) return false;
    // Two normals within alpha of the axis are within 2 alpha of each other.
    const double alpha = 2.0 * std::asin(0.5 * node.spread);
    return 2.0 * alpha + 2.0 * node.error + kCreaseMargin < crease_angle_rad;
}

}  // namespace inkline::core::internal
