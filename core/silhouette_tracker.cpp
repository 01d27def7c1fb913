// SPDX-License-Identifier: MIT
#include "core/silhouette_tracker.h"

#include "core/error.h"
#include "core/internal/cone_tree.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <span>

namespace inkline::core {
namespace {

using internal::ClusterFacing;

// Edge rings walked from an edge that stopped being a silhouette, through faces of the facing
// its two faces now share, before the search is left to the cone hierarchy: a silhouette that
// moved by a few faces is found again here, and one that vanished costs no more than this.
constexpr int kStoppedWalkRings = 3;

}  // namespace

SilhouetteTracker::SilhouetteTracker(const EdgeTable& table, const Mesh& mesh, const TrackerOptions& options)
    : table_(&table), options_(options), face_count_(mesh.triangles.size()) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    tree_ = std::make_unique<internal::ConeTree>(mesh, table, std::max<uint32_t>(1, options.leaf_faces));
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        if (!table.is_interior(e)) boundary_.push_back(e);
    }
    face_stamp_.assign(face_count_, 0);
    face_front_.assign(face_count_, 0);
    edge_stamp_.assign(table.edge_count(), 0);
    node_stamp_.assign(tree_->nodes.size(), 0);
    node_facing_.assign(tree_->nodes.size(), ClusterFacing::kUnknown);
}

SilhouetteTracker::~SilhouetteTracker() = default;
SilhouetteTracker::SilhouetteTracker(SilhouetteTracker&&) noexcept = default;
SilhouetteTracker& SilhouetteTracker::operator=(SilhouetteTracker&&) noexcept = default;

void SilhouetteTracker::reset() {
    need_full_pass_ = true;
    silhouettes_.clear();
}

FeatureEdges SilhouetteTracker::update(const Mesh& mesh, const glm::dvec3& eye_object, const LineOptions& lines) {
    INKLINE_CHECK_EQ(mesh.triangles.size(), face_count_);
    begin_frame();
    mesh_ = &mesh;
    eye_ = eye_object;
    const double crease_angle = glm::radians(lines.crease_angle_deg);
    const double cos_crease = std::cos(crease_angle);
    if (need_full_pass_) {
        full_pass(lines, cos_crease);
    } else {
        if (options_.deforming) tree_->refit(mesh);
        if (lines.silhouette) track();
        // Creases of a static mesh change only with the crease angle.
        if (lines.crease && (options_.deforming || creases_angle_ != lines.crease_angle_deg)) {
            creases_.clear();
            if (!tree_->nodes.empty()) collect_creases(0, crease_angle, cos_crease, creases_);
            std::sort(creases_.begin(), creases_.end());
            creases_angle_ = options_.deforming ? std::nullopt : std::optional<double>(lines.crease_angle_deg);
        }
    }
    silhouettes_ = found_;
    std::sort(silhouettes_.begin(), silhouettes_.end());
    stats_.silhouette_edges = silhouettes_.size();
    FeatureEdges out = assemble(lines);
    mesh_ = nullptr;
    return out;
}

void SilhouetteTracker::begin_frame() {
    if (frame_ == 0xffffffffu) {  // stamps wrapped: forget them all
        std::fill(face_stamp_.begin(), face_stamp_.end(), 0u);
        std::fill(edge_stamp_.begin(), edge_stamp_.end(), 0u);
        std::fill(node_stamp_.begin(), node_stamp_.end(), 0u);
        frame_ = 0;
    }
    ++frame_;
    found_.clear();
    extended_ = 0;
    edges_tested_ = 0;
    faces_tested_ = 0;
    stats_ = {};
}

bool SilhouetteTracker::is_front(uint32_t face) {
    if (face_stamp_[face] != frame_) {
        face_stamp_[face] = frame_;
        face_front_[face] = facing_value(*mesh_, face, eye_) > 0.0 ? 1 : 0;
        ++faces_tested_;
    }
    return face_front_[face] != 0;
}

SilhouetteTracker::Visit SilhouetteTracker::visit_edge(uint32_t edge) {
    if (edge_stamp_[edge] == frame_ || !table_->is_interior(edge)) return Visit::kSeen;
    edge_stamp_[edge] = frame_;
    ++edges_tested_;
    const auto faces = table_->faces_of(edge);
    if (is_front(faces[0]) == is_front(faces[1])) return Visit::kPlain;
    found_.push_back(edge);
    return Visit::kSilhouette;
}

void SilhouetteTracker::full_pass(const LineOptions& lines, double cos_crease) {
    const EdgeTable& table = *table_;
    if (lines.silhouette) {
        for (uint32_t f = 0; f < face_count_; ++f) {
            if (table.face_valid[f]) is_front(f);
        }
        for (uint32_t e = 0; e < table.edge_count(); ++e) visit_edge(e);
    }
    creases_.clear();
    creases_angle_.reset();
    if (lines.crease) {
        for (uint32_t e = 0; e < table.edge_count(); ++e) {
            if (!table.is_interior(e)) continue;
            const auto faces = table.faces_of(e);
            if (is_crease(*mesh_, faces[0], faces[1], cos_crease)) creases_.push_back(e);
        }
        if (!options_.deforming) creases_angle_ = lines.crease_angle_deg;
    }
    edges_tested_ = table.edge_count();
    need_full_pass_ = false;
    stats_.full_pass = true;
}

void SilhouetteTracker::track() {
    // 1. Re-test last frame's silhouette.
    stopped_.clear();
    for (uint32_t e : silhouettes_) {
        if (visit_edge(e) != Visit::kSilhouette) stopped_.push_back(e);
    }
    stats_.kept = found_.size();
    // 2. Walk along every silhouette found to its neighbours (this extends chain ends), and
    //    from every edge that stopped being one towards where it went.
    extend_from_found();
    for (uint32_t e : stopped_) {
        walk_from_stopped(e);
        extend_from_found();
    }
    stats_.walked = found_.size() - stats_.kept;
    // 3. Prove that nothing else exists: loops that appeared, lines that the walk lost.
    if (options_.exact && !tree_->nodes.empty()) prove(0);
    stats_.proven = found_.size() - stats_.kept - stats_.walked;
}

void SilhouetteTracker::extend_from_found() {
    for (; extended_ < found_.size(); ++extended_) {
        const glm::uvec2 v = table_->edge_vertices[found_[extended_]];
        for (uint32_t e : table_->edges_around(v.x)) visit_edge(e);
        for (uint32_t e : table_->edges_around(v.y)) visit_edge(e);
    }
}

void SilhouetteTracker::walk_from_stopped(uint32_t edge) {
    // Both faces of the edge now share one facing: the silhouette moved away through faces that
    // took it, so follow those until the sign changes.
    const bool side = is_front(table_->faces_of(edge)[0]);
    ring_.assign(1, edge);
    for (int r = 0; r < kStoppedWalkRings && !ring_.empty(); ++r) {
        next_ring_.clear();
        for (uint32_t e : ring_) {
            for (uint32_t vertex : {table_->edge_vertices[e].x, table_->edge_vertices[e].y}) {
                for (uint32_t n : table_->edges_around(vertex)) {
                    if (visit_edge(n) == Visit::kPlain && is_front(table_->faces_of(n)[0]) == side) {
                        next_ring_.push_back(n);
                    }
                }
            }
        }
        std::swap(ring_, next_ring_);
    }
}

ClusterFacing SilhouetteTracker::prove(uint32_t index) {
    ++stats_.nodes_visited;
    const internal::ConeNode& node = tree_->nodes[index];
    ClusterFacing facing = tree_->facing(index, eye_);
    if (facing == ClusterFacing::kUnknown) {
        if (node.is_leaf()) {
            for (uint32_t k = node.edge_begin; k < node.edge_end; ++k) visit_edge(tree_->edges[k]);
        } else {
            const ClusterFacing l = prove(node.first_child);
            const ClusterFacing r = prove(node.first_child + 1);
            if (l == r && l != ClusterFacing::kUnknown) {
                facing = l;  // both halves proven alike, so is the whole
            } else {
                // Edges joining the halves: skip those whose faces both lie in proven clusters
                // of one facing.
                for (uint32_t k = node.edge_begin; k < node.edge_end; ++k) {
                    const uint32_t e = tree_->edges[k];
                    const auto faces = table_->faces_of(e);
                    const ClusterFacing f0 = certified_facing(faces[0], index);
                    if (f0 == ClusterFacing::kUnknown || f0 != certified_facing(faces[1], index)) visit_edge(e);
                }
            }
        }
    }
    node_stamp_[index] = frame_;
    node_facing_[index] = facing;
    return facing;
}

ClusterFacing SilhouetteTracker::certified_facing(uint32_t face, uint32_t below_node) const {
    // Nodes not visited this frame carry old stamps; the proven ancestor that hid them has one.
    for (uint32_t n = tree_->face_leaf[face]; n != below_node; n = tree_->nodes[n].parent) {
        if (node_stamp_[n] == frame_ && node_facing_[n] != ClusterFacing::kUnknown) return node_facing_[n];
    }
    return ClusterFacing::kUnknown;
}

void SilhouetteTracker::collect_creases(uint32_t index, double crease_angle_rad, double cos_crease,
                                        std::vector<uint32_t>& r_creases) {
    if (tree_->crease_free(index, crease_angle_rad)) return;
    const internal::ConeNode& node = tree_->nodes[index];
    for (uint32_t k = node.edge_begin; k < node.edge_end; ++k) {
        const uint32_t e = tree_->edges[k];
        if (edge_stamp_[e] != frame_) {
            edge_stamp_[e] = frame_;
            ++edges_tested_;
        }
        const auto faces = table_->faces_of(e);
        if (is_crease(*mesh_, faces[0], faces[1], cos_crease)) r_creases.push_back(e);
    }
    if (!node.is_leaf()) {
        collect_creases(node.first_child, crease_angle_rad, cos_crease, r_creases);
        collect_creases(node.first_child + 1, crease_angle_rad, cos_crease, r_creases);
    }
}

FeatureEdges SilhouetteTracker::assemble(const LineOptions& lines) const {
    // Merge three ascending lists; an edge both silhouette and crease is a silhouette, as in
    // classify_edge, and boundary edges are never interior.
    using List = std::span<const uint32_t>;
    const List b = lines.boundary ? List(boundary_) : List();
    const List s = lines.silhouette ? List(silhouettes_) : List();
    const List c = lines.crease ? List(creases_) : List();
    FeatureEdges out;
    out.edges.reserve(b.size() + s.size() + c.size());
    size_t i = 0, j = 0, k = 0;
    for (;;) {
        const uint32_t eb = i < b.size() ? b[i] : kNoIndex;
        const uint32_t es = j < s.size() ? s[j] : kNoIndex;
        const uint32_t ec = k < c.size() ? c[k] : kNoIndex;
        const uint32_t e = std::min({eb, es, ec});
        if (e == kNoIndex) break;
        if (e == eb) {
            out.edges.push_back({e, LineKind::kBoundary});
            ++i;
        } else if (e == es) {
            out.edges.push_back({e, LineKind::kSilhouette});
            ++j;
            if (ec == e) ++k;
        } else {
            out.edges.push_back({e, LineKind::kCrease});
            ++k;
        }
    }
    out.edges_tested = edges_tested_;
    out.faces_tested = faces_tested_;
    return out;
}

}  // namespace inkline::core
