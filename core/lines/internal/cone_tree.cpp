// SPDX-License-Identifier: MIT
#include "core/lines/internal/cone_tree.h"

#include "core/error.h"
#include "core/internal/float_round.h"
#include "core/internal/parallel.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

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

// FaceCone keeps its values in float: a unit normal moves by at most sqrt(3) 2^-24 when rounded
// and a centroid by 2^-24 of its largest coordinate; a node's spread and box grow by these pads,
// which cover that with room for the sums' own rounding.
constexpr double kFloatNormalPad = 0x1p-22;
constexpr double kFloatBoxPad = 0x1p-22;

// Chord between two unit vectors at 90 degrees (sqrt 2): a cone this wide proves no facing.
constexpr double kMaxSpread = 1.4142135623730951;

// Weight of a node's centroid spread (relative to the whole mesh's diagonal) against its spread
// of unit normals when choosing the split: both widen the cone test's uncertain band by about
// that angle for an eye a mesh diagonal away.
constexpr double kPositionWeight = 1.0;

double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// Below these sizes the build's loops run on the calling thread.
constexpr size_t kMinParallelItems = 50000;
constexpr size_t kMinParallelNodes = 4096;
// The refit fetches a face's triangle twice this many faces ahead of its cone, and its corners this many.
constexpr size_t kFetchAhead = 16;

// Faces in the first child of a node of n > leaf_faces faces: half its leaves, rounded up, so that
// every node starts at a multiple of leaf_faces and every leaf but the last is full.
uint32_t first_child_faces(uint32_t n, uint32_t leaf_faces) {
    const uint32_t leaves = (n + leaf_faces - 1) / leaf_faces;
    return (leaves + 1) / 2 * leaf_faces;
}

// The number of nodes in the subtree of a node of n faces, split as first_child_faces says down
// to leaves of at most leaf_faces. Remembers the few distinct sizes a tree has.
class SubtreeSizes {
  public:
    explicit SubtreeSizes(uint32_t leaf_faces) : leaf_faces_(leaf_faces) {}
    uint32_t operator()(uint32_t n) {
        if (n <= leaf_faces_) return 1;
        for (const auto& [faces, count] : known_) {
            if (faces == n) return count;
        }
        const uint32_t first = first_child_faces(n, leaf_faces_);
        const uint32_t count = 1 + (*this)(first) + (*this)(n - first);
        known_.emplace_back(n, count);
        return count;
    }

  private:
    uint32_t leaf_faces_;
    std::vector<std::pair<uint32_t, uint32_t>> known_;
};

}  // namespace

ConeTree::ConeTree(const Mesh& mesh, const EdgeTable& table, uint32_t leaf_faces, std::span<const glm::dvec3> normals,
                   std::span<const glm::uvec3> face_corners)
    : leaf_faces_(leaf_faces), over_corner_normals_(!normals.empty()) {
    INKLINE_CHECK(leaf_faces >= 1);
    const CornerNormals corner_normals{normals, face_corners};
    if (over_corner_normals_) {
        INKLINE_CHECK_EQ(face_corners.size(), mesh.triangles.size());
        corners_.resize(mesh.triangles.size());
    }
    const size_t n_faces = mesh.triangles.size();
    for (uint32_t f = 0; f < n_faces; ++f) {
        if (table.face_valid[f]) faces.push_back(f);
    }
    if (faces.empty()) return;
    // The cones are built in face order and then reordered by the splits; each carries its face.
    cones_.resize(faces.size());
    parallel_for(faces.size(), kMinParallelItems, [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) cones_[k] = cone_of(mesh, corner_normals, faces[k]);
    });

    // Top-down splits near the median, depth first so that a traversal reads the nodes in order. A node
    // of n faces heads subtree_nodes(n) nodes, so every node's index is known before its
    // subtree is built and the subtrees below the top levels are built in parallel, each exactly
    // as the sequential recursion would.
    Bounds all;
    for (const FaceCone& cone : cones_) all.add(glm::dvec3(cone.centroid));
    const double diagonal = std::max(2.0 * all.radius(), std::numeric_limits<double>::min());
    std::vector<uint32_t> face_leaf(n_faces, kNoIndex);
    SubtreeSizes sizes(leaf_faces);
    nodes.resize(sizes(uint32_t(faces.size())));
    std::vector<uint32_t> parent(nodes.size()), depth(nodes.size());
    struct Task {
        uint32_t index, begin, end, up;
    };
    // Returns the split point of [begin, end), or end for a leaf.
    auto split_one = [&](const Task& t, SubtreeSizes& local_sizes) -> uint32_t {
        nodes[t.index].face_begin = t.begin;
        nodes[t.index].face_end = t.end;
        parent[t.index] = t.up;
        depth[t.index] = t.up == kNoIndex ? 0 : depth[t.up] + 1;
        if (t.end - t.begin <= leaf_faces) {
            for (uint32_t k = t.begin; k < t.end; ++k) face_leaf[cones_[k].face] = t.index;
            return t.end;
        }
        // Split along the widest of three centroid axes and three normal components.
        glm::vec3 p_min(std::numeric_limits<float>::max()), p_max(-std::numeric_limits<float>::max());
        glm::vec3 n_min(2.0f), n_max(-2.0f);
        for (uint32_t k = t.begin; k < t.end; ++k) {
            p_min = glm::min(p_min, cones_[k].centroid);
            p_max = glm::max(p_max, cones_[k].centroid);
            n_min = glm::min(n_min, cones_[k].normal);
            n_max = glm::max(n_max, cones_[k].normal);
        }
        const glm::dvec3 p_spread = kPositionWeight * glm::dvec3(p_max - p_min) / diagonal;
        const glm::dvec3 n_spread(n_max - n_min);
        int key = 0;
        double widest = -1.0;
        for (int k = 0; k < 6; ++k) {
            const double spread = k < 3 ? p_spread[k] : n_spread[k - 3];
            if (spread > widest) widest = spread, key = k;
        }
        auto value = [key](const FaceCone& cone) { return key < 3 ? cone.centroid[key] : cone.normal[key - 3]; };
        const uint32_t mid = t.begin + first_child_faces(t.end - t.begin, leaf_faces);
        std::nth_element(cones_.begin() + t.begin, cones_.begin() + mid, cones_.begin() + t.end,
                         [&](const FaceCone& a, const FaceCone& b) { return value(a) < value(b); });
        nodes[t.index].second_child = t.index + 1 + local_sizes(mid - t.begin);
        return mid;
    };
    auto build = [&](auto& self, const Task& t, SubtreeSizes& local_sizes) -> void {
        const uint32_t mid = split_one(t, local_sizes);
        if (mid == t.end) return;
        self(self, {t.index + 1, t.begin, mid, t.index}, local_sizes);
        self(self, {t.index + 1 + local_sizes(mid - t.begin), mid, t.end, t.index}, local_sizes);
    };
    // The top levels on this thread, until there is a subtree per thread.
    std::vector<Task> tasks{{0, 0, uint32_t(faces.size()), kNoIndex}};
    const size_t threads = faces.size() < kMinParallelItems ? 1 : hardware_threads();
    while (tasks.size() < threads) {
        std::vector<Task> next;
        for (const Task& t : tasks) {
            const uint32_t mid = split_one(t, sizes);
            if (mid == t.end) continue;
            next.push_back({t.index + 1, t.begin, mid, t.index});
            next.push_back({nodes[t.index].second_child, mid, t.end, t.index});
        }
        if (next.empty()) break;
        tasks = std::move(next);
    }
    if (tasks.size() == 1 && tasks[0].index == 0) {
        build(build, tasks[0], sizes);
    } else {
        parallel_for(tasks.size(), 2, [&](size_t begin, size_t end) {
            SubtreeSizes local_sizes(leaf_faces);
            for (size_t i = begin; i < end; ++i) build(build, tasks[i], local_sizes);
        });
    }
    // The position of each face in `faces`, while the edges are listed.
    std::vector<uint32_t> face_position(n_faces, kNoIndex);
    for (uint32_t k = 0; k < faces.size(); ++k) {
        faces[k] = cones_[k].face;
        face_position[faces[k]] = k;
    }
    parallel_for(nodes.size(), kMinParallelNodes, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) fit_node(nodes[i]);
    });
    // A static mesh never needs the cones again (refit recomputes them): released before the
    // edge lists grow. Not "cones_ = {}", which assigns an empty list and keeps the memory.
    cones_ = std::vector<FaceCone>();
    corners_ = std::vector<CornerBounds>();

    // Each interior edge goes to the deepest node holding both its faces (counting sort).
    std::vector<uint32_t> edge_node(table.edge_count(), kNoIndex);
    parallel_for(table.edge_count(), kMinParallelItems, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e) {
            if (!table.is_interior(uint32_t(e))) continue;
            const auto pair = table.faces_of(uint32_t(e));
            uint32_t a = face_leaf[pair[0]], b = face_leaf[pair[1]];
            while (a != b) {
                if (depth[a] >= depth[b]) {
                    a = parent[a];
                } else {
                    b = parent[b];
                }
            }
            edge_node[e] = a;
        }
    });
    face_leaf = std::vector<uint32_t>();
    std::vector<uint32_t> offsets(nodes.size() + 1, 0);
    for (uint32_t node : edge_node) {
        if (node != kNoIndex) ++offsets[node + 1];
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
        edges[offsets[edge_node[e]]++] = {e, {face_position[f0], face_position[f1]}};
    }
    edge_node = std::vector<uint32_t>();
    parallel_for(nodes.size(), kMinParallelNodes, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const ConeNode& node = nodes[i];
            if (!node.is_leaf()) {
                std::sort(edges.begin() + node.edge_begin, edges.begin() + node.edge_end,
                          [](const ListedEdge& a, const ListedEdge& b) { return a.position[0] < b.position[0]; });
            }
        }
    });
}

ConeTree::FaceCone ConeTree::face_cone(const Mesh& mesh, uint32_t face) {
    // The same expressions as facing_value, so that the cones bound the values it computes.
    const glm::uvec3 t = mesh.triangles[face];
    const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
    const glm::dvec3 ab = b - a, ac = c - a;
    const glm::dvec3 n = glm::cross(ab, ac);
    const double len = glm::length(n);
    // The centroid and the normal are rounded to float, which the boxes' and spreads' padding
    // covers; one division for the normal's three components.
    FaceCone fc{.centroid = glm::vec3((a + b + c) * (1.0 / 3.0)), .normal = glm::vec3(0.0f, 0.0f, 1.0f), .error = 1.0f, .face = face};
    if (!(len > 0.0)) return fc;
    const double inverse = 1.0 / len;
    fc.normal = glm::vec3(n * inverse);
    // Relative error of facing_value's normal against this one, were they rounded differently
    // (about 12 ulp of |b-a||c-a| per cross product, large for slivers), plus the rounding of
    // eye - centroid and of the dot product.
    const double edges2 = glm::dot(ab, ab) * glm::dot(ac, ac);
    fc.error = float_above(std::min(1.0, 8.0 * kEpsilon * (std::sqrt(edges2) * inverse + 1.0)));
    return fc;
}

ConeTree::FaceCone ConeTree::corner_cone(const Mesh& mesh, const CornerNormals& corner_normals, uint32_t face) {
    const glm::uvec3 t = mesh.triangles[face];
    const glm::uvec3 corner = corner_normals.face_corners[face];
    CornerBounds& bounds = corners_[face];
    bounds.box_min = glm::min(glm::min(mesh.positions[t.x], mesh.positions[t.y]), mesh.positions[t.z]);
    bounds.box_max = glm::max(glm::max(mesh.positions[t.x], mesh.positions[t.y]), mesh.positions[t.z]);
    glm::dvec3 sum(0.0);
    bool unit = true;
    for (int c = 0; c < 3; ++c) {
        const glm::dvec3& n = corner_normals.normals[corner[c]];
        unit = unit && std::abs(glm::dot(n, n) - 1.0) < 1e-9;  // a zero normal bounds nothing
        sum += n;
    }
    // The corners' values are dot products of the very normals bounded here: only their own
    // rounding (and that of corner - eye, which the box padding covers) is left.
    FaceCone fc{.centroid = glm::vec3(0.5 * (glm::dvec3(bounds.box_min) + glm::dvec3(bounds.box_max))),
                .normal = glm::vec3(0.0f, 0.0f, 1.0f),
                .error = float_above(8.0 * kEpsilon),
                .face = face};
    bounds.spread = 2.0f;
    const double len = glm::length(sum);
    if (!unit || !(len > 1e-6)) return fc;
    const glm::dvec3 normal = sum / len;
    fc.normal = glm::vec3(normal);
    double spread2 = 0.0;
    for (int c = 0; c < 3; ++c) {
        const glm::dvec3 d = corner_normals.normals[corner[c]] - normal;
        spread2 = std::max(spread2, glm::dot(d, d));
    }
    bounds.spread = float_above(std::sqrt(spread2));
    return fc;
}

ConeTree::FaceCone ConeTree::cone_of(const Mesh& mesh, const CornerNormals& corner_normals, uint32_t face) {
    return over_corner_normals_ ? corner_cone(mesh, corner_normals, face) : face_cone(mesh, face);
}

void ConeTree::fit_node(ConeNode& node) const {
    glm::dvec3 sum(0.0);
    node.box_min = glm::dvec3(std::numeric_limits<double>::max());
    node.box_max = glm::dvec3(-std::numeric_limits<double>::max());
    node.error = 0.0;
    for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
        const FaceCone& fc = cones_[k];
        sum += glm::dvec3(fc.normal);
        if (over_corner_normals_) {
            node.box_min = glm::min(node.box_min, glm::dvec3(corners_[fc.face].box_min));
            node.box_max = glm::max(node.box_max, glm::dvec3(corners_[fc.face].box_max));
        } else {
            node.box_min = glm::min(node.box_min, glm::dvec3(fc.centroid));
            node.box_max = glm::max(node.box_max, glm::dvec3(fc.centroid));
        }
        node.error = std::max(node.error, double(fc.error));
    }
    if (!over_corner_normals_) {
        // The centroids were rounded to float (the corners' boxes are exact); the floor covers
        // subnormal centroids, whose rounding is absolute.
        const double pad = std::max(kFloatBoxPad * std::max(max_abs(node.box_min), max_abs(node.box_max)), 0x1p-148);
        node.box_min -= pad;
        node.box_max += pad;
    }
    const double len = glm::length(sum);
    if (!(len > 1e-6 * double(node.face_end - node.face_begin))) {
        node.axis = glm::dvec3(0.0, 0.0, 1.0);
        set_spread(node, 2.0);
        return;
    }
    node.axis = sum / len;
    if (over_corner_normals_) {
        // Every corner normal lies within its face's spread of the face's normal.
        double spread = 0.0;
        for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
            const glm::dvec3 d = glm::dvec3(cones_[k].normal) - node.axis;
            spread = std::max(spread, std::sqrt(glm::dot(d, d)) + double(corners_[cones_[k].face].spread));
        }
        set_spread(node, spread + kFloatNormalPad);
        return;
    }
    double spread2 = 0.0;
    for (uint32_t k = node.face_begin; k < node.face_end; ++k) {
        const glm::dvec3 d = glm::dvec3(cones_[k].normal) - node.axis;
        spread2 = std::max(spread2, glm::dot(d, d));
    }
    set_spread(node, std::sqrt(spread2) + kFloatNormalPad);
}

void ConeTree::set_spread(ConeNode& node, double spread) { node.spread = std::min(2.0, spread); }

void ConeTree::refit(const Mesh& mesh, std::span<const glm::dvec3> normals, std::span<const glm::uvec3> face_corners) {
    INKLINE_CHECK_EQ(over_corner_normals_, !normals.empty());
    const CornerNormals corner_normals{normals, face_corners};
    cones_.resize(faces.size());
    if (over_corner_normals_) corners_.resize(mesh.triangles.size());
    // The leaves first, in depth-first order, which is the order of their faces: each face's
    // cone, then the leaf's while they are in cache. A cluster's faces lie together in the tree
    // but anywhere in the mesh: each face's triangle is fetched ahead, and then its corners.
    const size_t n = faces.size();
    for (ConeNode& node : nodes) {
        if (!node.is_leaf()) continue;
        for (size_t k = node.face_begin; k < node.face_end; ++k) {
            if (k + 2 * kFetchAhead < n) __builtin_prefetch(&mesh.triangles[faces[k + 2 * kFetchAhead]]);
            if (k + kFetchAhead < n) {
                const glm::uvec3 t = mesh.triangles[faces[k + kFetchAhead]];
                for (int c = 0; c < 3; ++c) __builtin_prefetch(&mesh.positions[t[c]]);
            }
            cones_[k] = cone_of(mesh, corner_normals, faces[k]);
        }
        fit_node(node);
    }
    // Then each inner node from its children, below it in the order.
    for (size_t i = nodes.size(); i-- > 0;) {
        ConeNode& node = nodes[i];
        if (node.is_leaf()) continue;
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

ClusterFacing ConeTree::facing(uint32_t index, const Viewpoint& eye) const {
    const ConeNode& node = nodes[index];
    if (!(node.spread < kMaxSpread)) return ClusterFacing::kUnknown;

    // Over the box, v = eye.toward(centroid) has axis . v within along +- reach and |v| <=
    // farthest. Towards an eye at infinity v is the same everywhere: the box shrinks to its pad.
    const double pad =
        kBoxPad * std::max({max_abs(eye.xyz), eye.w * max_abs(node.box_min), eye.w * max_abs(node.box_max)});
    const glm::dvec3 center = 0.5 * (node.box_min + node.box_max);
    const glm::dvec3 half = eye.w * 0.5 * (node.box_max - node.box_min) + pad;
    const glm::dvec3 to_eye = eye.toward(center);
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
    // A unit normal n with |n - axis| <= r makes an angle of at most alpha with the axis, where
    // r = 2 sin(alpha / 2): cos alpha = 1 - r^2 / 2, sin alpha = r sqrt(1 - r^2 / 4). Computed
    // here rather than stored: 16 bytes less per node.
    const double r = node.spread;
    const double cos_alpha = 1.0 - 0.5 * r * r;
    const double sin_alpha = r * std::sqrt(std::max(0.0, 1.0 - 0.25 * r * r));
    const double m = node.error + kConeMargin;
    const double lhs = nearest * cos_alpha - m * std::sqrt(farthest2);
    if (!(lhs > 0.0)) return ClusterFacing::kUnknown;
    const double rest2 = std::max(0.0, farthest2 - nearest * nearest) * sin_alpha * sin_alpha;
    return lhs * lhs > rest2 ? side : ClusterFacing::kUnknown;
}

bool ConeTree::maybe_crease(const ListedEdge& edge, double cos_crease) const {
    INKLINE_CHECK_EQ(cones_.size(), faces.size());
    // Unit normals within error of is_crease's own directions: their cosine is within the sum.
    const FaceCone& a = cones_[edge.position[0]];
    const FaceCone& b = cones_[edge.position[1]];
    return glm::dot(glm::dvec3(a.normal), glm::dvec3(b.normal)) -
               (double(a.error) + double(b.error) + 2.0 * kFloatNormalPad + kConeMargin) <
           cos_crease;
}

bool ConeTree::crease_free(uint32_t index, double crease_angle_rad) const {
    const ConeNode& node = nodes[index];
    if (!(node.spread < 2.0)) return false;
    // Two normals within alpha of the axis are within 2 alpha of each other.
    const double alpha = 2.0 * std::asin(0.5 * node.spread);
    return 2.0 * alpha + 2.0 * node.error + kCreaseMargin < crease_angle_rad;
}

}  // namespace inkline::core::internal
