// SPDX-License-Identifier: MIT
#include "tests/support/segment_occlusion.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace inkline::test {
namespace {

constexpr double kEndGap = 1e-6;
constexpr uint32_t kLeafFaces = 4;

// Whether the segment o + t d, t in [t0, t1], meets the box.
bool meets_box(const glm::dvec3& o, const glm::dvec3& inv_d, double t0, double t1, const glm::dvec3& lo,
               const glm::dvec3& hi) {
    for (int a = 0; a < 3; ++a) {
        double ta = (lo[a] - o[a]) * inv_d[a];
        double tb = (hi[a] - o[a]) * inv_d[a];
        if (std::isnan(ta) || std::isnan(tb)) {
            // Parallel to the slab (0 * inf): inside it or not.
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

// Moller-Trumbore: whether o + t d meets the triangle (edges included) for t in [0, t_max].
bool meets_triangle(const glm::dvec3& o, const glm::dvec3& d, double t_max, const glm::dvec3& a,
                    const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return false;  // parallel to the face's plane
    const double inv = 1.0 / det;
    const glm::dvec3 s = o - a;
    const double u = glm::dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    const double t = glm::dot(e2, q) * inv;
    return t >= 0.0 && t <= t_max;
}

}  // namespace

SegmentOcclusion::SegmentOcclusion(const core::Mesh& mesh) {
    corners_.reserve(mesh.triangles.size() * 3);
    for (const glm::uvec3& t : mesh.triangles) {
        corners_.emplace_back(mesh.positions[t.x]);
        corners_.emplace_back(mesh.positions[t.y]);
        corners_.emplace_back(mesh.positions[t.z]);
    }
    if (!corners_.empty()) {
        glm::dvec3 lo = corners_.front(), hi = lo;
        for (const glm::dvec3& c : corners_) lo = glm::min(lo, c), hi = glm::max(hi, c);
        reach_ = std::max(4.0 * glm::length(hi - lo), 1.0);
    }
    order_.resize(mesh.triangles.size());
    for (uint32_t f = 0; f < order_.size(); ++f) order_[f] = f;
    nodes_.reserve(2 * order_.size() / kLeafFaces + 2);
    if (!order_.empty()) build(0, uint32_t(order_.size()));
}

uint32_t SegmentOcclusion::build(uint32_t first, uint32_t count) {
    const auto index = uint32_t(nodes_.size());
    nodes_.push_back({});
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    glm::dvec3 clo = lo, chi = hi;  // bounds of the centroids
    for (uint32_t k = first; k < first + count; ++k) {
        const glm::dvec3* c = &corners_[size_t(order_[k]) * 3];
        for (int i = 0; i < 3; ++i) {
            lo = glm::min(lo, c[i]);
            hi = glm::max(hi, c[i]);
        }
        const glm::dvec3 centroid = (c[0] + c[1] + c[2]) / 3.0;
        clo = glm::min(clo, centroid);
        chi = glm::max(chi, centroid);
    }
    nodes_[index].lo = lo;
    nodes_[index].hi = hi;
    if (count <= kLeafFaces) {
        nodes_[index].first = first;
        nodes_[index].count = count;
        return index;
    }
    const glm::dvec3 extent = chi - clo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const uint32_t half = count / 2;
    const auto centroid = [&](uint32_t f) {
        const glm::dvec3* c = &corners_[size_t(f) * 3];
        return c[0][axis] + c[1][axis] + c[2][axis];
    };
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](uint32_t a, uint32_t b) { return centroid(a) < centroid(b); });
    const uint32_t left = build(first, half);
    const uint32_t right = build(first + half, count - half);
    nodes_[index].first = left;
    nodes_[index].count = 0;
    nodes_[index].right = right;
    return index;
}

bool SegmentOcclusion::hidden(const core::Viewpoint& viewpoint, const glm::dvec3& p, uint32_t own_face) const {
    if (nodes_.empty()) return false;
    const glm::dvec3 eye = viewpoint.orthographic() ? p + viewpoint.xyz * reach_ : viewpoint.xyz;
    const glm::dvec3 d = p - eye;
    const glm::dvec3 inv_d = 1.0 / d;
    const double t_max = 1.0 - kEndGap;
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
        const Node& node = nodes_[stack.back()];
        stack.pop_back();
        if (!meets_box(eye, inv_d, 0.0, t_max, node.lo, node.hi)) continue;
        if (node.count == 0) {
            stack.push_back(node.first);
            stack.push_back(node.right);
            continue;
        }
        for (uint32_t k = node.first; k < node.first + node.count; ++k) {
            const uint32_t f = order_[k];
            if (f == own_face) continue;
            const glm::dvec3* c = &corners_[size_t(f) * 3];
            if (meets_triangle(eye, d, t_max, c[0], c[1], c[2])) return true;
        }
    }
    return false;
}

glm::dvec3 SegmentOcclusion::point_of(const core::Dot& dot) const {
    const glm::dvec3* c = &corners_[size_t(dot.face) * 3];
    return dot.barycentric.x * c[0] + dot.barycentric.y * c[1] + dot.barycentric.z * c[2];
}

double SegmentOcclusion::hidden_share(const core::Viewpoint& eye, std::span<const core::Dot> dots) const {
    if (dots.empty()) return 0.0;
    size_t hidden_dots = 0;
    for (const core::Dot& dot : dots) hidden_dots += hidden(eye, point_of(dot), dot.face) ? 1 : 0;
    return double(hidden_dots) / double(dots.size());
}

}  // namespace inkline::test
