// SPDX-License-Identifier: MIT
#include "core/lines/silhouette_tracker.h"

#include "core/error.h"
#include "core/internal/parallel.h"
#include "core/lines/internal/cone_tree.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <span>
#include <string>

namespace inkline::core {
namespace {

using internal::ClusterFacing;

// Edge rings walked from an edge that stopped being a silhouette, through faces of the facing
// its two faces now share, before the search is left to the cone hierarchy: a silhouette that
// moved by a few faces is found again here, and one that vanished costs no more than this.
constexpr int kStoppedWalkRings = 2;

// A full pass over fewer faces (edges) than this runs on the calling thread.
constexpr size_t kMinParallelItems = 100000;

}  // namespace

const char* tracker_mode_name(TrackerMode mode) {
    return mode == TrackerMode::kBrute ? "brute" : "incremental";
}

std::optional<TrackerMode> tracker_mode_from_name(std::string_view name) {
    for (const TrackerMode mode : {TrackerMode::kIncremental, TrackerMode::kBrute}) {
        if (name == tracker_mode_name(mode)) return mode;
    }
    return std::nullopt;
}

TrackerMode parse_tracker_mode(std::string_view text, const char* key) {
    if (const std::optional<TrackerMode> mode = tracker_mode_from_name(text)) return *mode;
    throw InputError(std::string(key) + " '" + quote_value(text) + "': expected incremental or brute");
}

SilhouetteTracker::SilhouetteTracker(const EdgeTable& table, const Mesh& mesh, const TrackerOptions& options)
    : table_(&table), options_(options), face_count_(mesh.triangles.size()) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    tree_ = std::make_unique<internal::ConeTree>(mesh, table, std::max<uint32_t>(1, options.leaf_faces));
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        if (!table.is_interior(e)) boundary_.push_back(e);
    }
    face_state_.assign(tree_->faces.size(), 0);
    leaf_facing_.assign(tree_->leaf_count(), ClusterFacing::kUnknown);
    found_bits_.assign((table.edge_count() + 63) / 64, 0);
    if (!options.deforming) {
        // The faces in tree order, their vertices renumbered in order of first use: a cluster's
        // corners then lie together in memory, wherever the file put them.
        std::vector<uint32_t> renumbered(mesh.positions.size(), kNoIndex);
        local_triangles_.resize(tree_->faces.size());
        for (size_t k = 0; k < local_triangles_.size(); ++k) {
            const glm::uvec3 t = mesh.triangles[tree_->faces[k]];
            for (int c = 0; c < 3; ++c) {
                if (renumbered[t[c]] == kNoIndex) {
                    renumbered[t[c]] = uint32_t(local_positions_.size());
                    local_positions_.push_back(mesh.positions[t[c]]);
                }
                local_triangles_[k][c] = renumbered[t[c]];
            }
        }
        local_positions_.shrink_to_fit();
    }
    if (options.search != TrackerSearch::kHierarchy) {
        face_position_.assign(face_count_, kNoIndex);
        for (uint32_t k = 0; k < tree_->faces.size(); ++k) face_position_[tree_->faces[k]] = k;
        vertex_stamp_.assign(mesh.positions.size(), 0);
    }
    // The hierarchy alone reaches each edge at most once a frame; the walk and a deforming
    // mesh's crease pass can reach edges again.
    stamp_edges_ = options.search != TrackerSearch::kHierarchy || options.deforming;
    if (stamp_edges_) edge_stamp_.assign(table.edge_count(), 0);
}

SilhouetteTracker::~SilhouetteTracker() = default;
SilhouetteTracker::SilhouetteTracker(SilhouetteTracker&&) noexcept = default;
SilhouetteTracker& SilhouetteTracker::operator=(SilhouetteTracker&&) noexcept = default;

void SilhouetteTracker::reset() {
    need_full_pass_ = true;
    silhouettes_.clear();
}

FeatureEdges SilhouetteTracker::update(const Mesh& mesh, const Viewpoint& eye_object, const LineOptions& lines) {
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
        if (lines.silhouette) search();
        if (lines.crease && options_.deforming) {
            creases_.clear();
            if (!tree_->nodes.empty()) collect_creases(0, crease_angle, cos_crease, creases_);
            std::sort(creases_.begin(), creases_.end());
        } else if (lines.crease && creases_angle_ != lines.crease_angle_deg) {
            // Creases of a static mesh change only with the crease angle.
            all_creases(cos_crease);
            creases_angle_ = lines.crease_angle_deg;
            edges_tested_ = table_->edge_count();
        }
    }
    sort_found();
    stats_.silhouette_edges = silhouettes_.size();
    FeatureEdges out = assemble(lines);
    mesh_ = nullptr;
    return out;
}

void SilhouetteTracker::sort_found() {
    // A bit per edge, read word by word: linear in the edge count / 64 rather than n log n in the
    // silhouette edges, which at a million faces number tens of thousands.
    silhouettes_.clear();
    if (found_.size() < 64) {
        silhouettes_ = found_;
        std::sort(silhouettes_.begin(), silhouettes_.end());
        return;
    }
    for (uint32_t e : found_) found_bits_[e >> 6] |= uint64_t(1) << (e & 63);
    silhouettes_.reserve(found_.size());
    for (size_t w = 0; w < found_bits_.size(); ++w) {
        for (uint64_t bits = found_bits_[w]; bits != 0; bits &= bits - 1) {
            silhouettes_.push_back(uint32_t(w * 64 + size_t(std::countr_zero(bits))));
        }
        found_bits_[w] = 0;
    }
}

void SilhouetteTracker::begin_frame() {
    if (frame_ == 0xffffffffu) {  // stamps would wrap: forget them all
        std::fill(edge_stamp_.begin(), edge_stamp_.end(), 0u);
        std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0u);
        frame_ = 0;
    }
    ++frame_;
    if (++face_stamp_ == 128) {  // seven bits of stamp per face
        std::fill(face_state_.begin(), face_state_.end(), uint8_t(0));
        face_stamp_ = 1;
    }
    found_.clear();
    extended_ = 0;
    edges_tested_ = 0;
    faces_tested_ = 0;
    stats_ = {};
}

double SilhouetteTracker::facing_at(uint32_t position) const {
    if (local_triangles_.empty()) return facing_value(*mesh_, tree_->faces[position], eye_);
    const glm::uvec3 t = local_triangles_[position];
    return facing_value(local_positions_[t.x], local_positions_[t.y], local_positions_[t.z], eye_);
}

bool SilhouetteTracker::is_front(uint32_t position) {
    uint8_t& state = face_state_[position];
    if ((state >> 1) != face_stamp_) {
        state = uint8_t((face_stamp_ << 1) | (facing_at(position) > 0.0 ? 1u : 0u));
        ++faces_tested_;
    }
    return (state & 1u) != 0;
}

SilhouetteTracker::Visit SilhouetteTracker::visit_edge(uint32_t edge) {
    if (!table_->is_interior(edge)) return Visit::kSeen;
    const auto faces = table_->faces_of(edge);
    const internal::ListedEdge le{edge, {face_position_[faces[0]], face_position_[faces[1]]}};
    return visit_interior_edge(le, ClusterFacing::kUnknown, ClusterFacing::kUnknown);
}

SilhouetteTracker::Visit SilhouetteTracker::visit_interior_edge(const internal::ListedEdge& le, ClusterFacing known0,
                                                                ClusterFacing known1) {
    if (stamp_edges_) {
        if (edge_stamp_[le.edge] == frame_) return Visit::kSeen;
        edge_stamp_[le.edge] = frame_;
    }
    ++edges_tested_;
    // A facing the cone tree proved is facing_value's sign: no need to evaluate it.
    const bool front0 = known0 == ClusterFacing::kUnknown ? is_front(le.position[0]) : known0 == ClusterFacing::kFront;
    const bool front1 = known1 == ClusterFacing::kUnknown ? is_front(le.position[1]) : known1 == ClusterFacing::kFront;
    if (front0 == front1) return Visit::kPlain;
    found_.push_back(le.edge);
    return Visit::kSilhouette;
}

void SilhouetteTracker::full_pass(const LineOptions& lines, double cos_crease) {
    const EdgeTable& table = *table_;
    if (lines.silhouette) {
        // Every face's facing, on every core (each face its own state), then every edge.
        internal::parallel_for(tree_->faces.size(), kMinParallelItems, [&](size_t begin, size_t end) {
            for (size_t k = begin; k < end; ++k) {
                face_state_[k] = uint8_t((face_stamp_ << 1) | (facing_at(uint32_t(k)) > 0.0 ? 1u : 0u));
            }
        });
        faces_tested_ += tree_->faces.size();
        for (const internal::ListedEdge& le : tree_->edges) {
            visit_interior_edge(le, ClusterFacing::kUnknown, ClusterFacing::kUnknown);
        }
    }
    creases_angle_.reset();
    if (lines.crease) {
        all_creases(cos_crease);
        if (!options_.deforming) creases_angle_ = lines.crease_angle_deg;
    }
    edges_tested_ = table.edge_count();
    need_full_pass_ = false;
    stats_.full_pass = true;
}

void SilhouetteTracker::all_creases(double cos_crease) {
    // Slices of the edges on every core, joined in edge order.
    const size_t edges = table_->edge_count();
    const size_t slices = edges < kMinParallelItems ? 1 : internal::hardware_threads();
    std::vector<std::vector<uint32_t>> found(slices);
    internal::run_tasks(slices, [&](size_t slice) {
        for (size_t e = edges * slice / slices; e < edges * (slice + 1) / slices; ++e) {
            if (!table_->is_interior(uint32_t(e))) continue;
            const auto faces = table_->faces_of(uint32_t(e));
            if (is_crease(*mesh_, faces[0], faces[1], cos_crease)) found[slice].push_back(uint32_t(e));
        }
    });
    creases_.clear();
    for (const std::vector<uint32_t>& part : found) creases_.insert(creases_.end(), part.begin(), part.end());
}

void SilhouetteTracker::search() {
    if (options_.search != TrackerSearch::kHierarchy) walk();
    // Prove that nothing else exists: loops that appeared, lines that the walk lost.
    if (options_.search != TrackerSearch::kWalkOnly && !tree_->nodes.empty()) prove(0);
    stats_.proven = found_.size() - stats_.kept - stats_.walked;
}

void SilhouetteTracker::walk() {
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
}

void SilhouetteTracker::extend_from_found() {
    for (; extended_ < found_.size(); ++extended_) {
        const glm::uvec2 v = table_->edge_vertices[found_[extended_]];
        for (uint32_t vertex : {v.x, v.y}) {
            if (!first_visit(vertex)) continue;
            for (uint32_t e : table_->edges_around(vertex)) visit_edge(e);
        }
    }
}

bool SilhouetteTracker::first_visit(uint32_t vertex) {
    // Every edge around a vertex visited once this frame answers kSeen to any later visit, so a
    // vertex is walked around once a frame: a fan's apex, with an edge to each of its hundreds of
    // thousands of faces, would otherwise be walked around again from each of its silhouette
    // edges.
    if (vertex_stamp_[vertex] == frame_) return false;
    vertex_stamp_[vertex] = frame_;
    return true;
}

void SilhouetteTracker::walk_from_stopped(uint32_t edge) {
    // Both faces of the edge now share one facing: the silhouette moved away through faces that
    // took it, so follow those until the sign changes.
    const bool side = is_front(face_position_[table_->faces_of(edge)[0]]);
    ring_.assign(1, edge);
    for (int r = 0; r < kStoppedWalkRings && !ring_.empty(); ++r) {
        next_ring_.clear();
        for (uint32_t e : ring_) {
            for (uint32_t vertex : {table_->edge_vertices[e].x, table_->edge_vertices[e].y}) {
                if (!first_visit(vertex)) continue;
                for (uint32_t n : table_->edges_around(vertex)) {
                    if (visit_edge(n) == Visit::kPlain &&
                        is_front(face_position_[table_->faces_of(n)[0]]) == side) {
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
    const ClusterFacing facing = tree_->facing(index, eye_);
    if (facing != ClusterFacing::kUnknown) {
        const auto [first, last] = tree_->leaves_of(node);
        std::fill(leaf_facing_.begin() + first, leaf_facing_.begin() + last, facing);
        return facing;
    }
    if (node.is_leaf()) {
        leaf_facing_[tree_->leaf_of(node.face_begin)] = ClusterFacing::kUnknown;
        for (uint32_t k = node.edge_begin; k < node.edge_end; ++k) {
            visit_interior_edge(tree_->edges[k], ClusterFacing::kUnknown, ClusterFacing::kUnknown);
        }
        return ClusterFacing::kUnknown;
    }
    const ClusterFacing l = prove(index + 1);
    const ClusterFacing r = prove(node.second_child);
    if (l == r && l != ClusterFacing::kUnknown) return l;  // both halves proven alike: so is the whole
    // Edges joining the halves: skip those whose faces lie in leaves proven of one facing.
    const uint32_t leaf_faces = tree_->leaf_faces();
    for (uint32_t k = node.edge_begin; k < node.edge_end; ++k) {
        const internal::ListedEdge& le = tree_->edges[k];
        const ClusterFacing f0 = leaf_facing_[le.position[0] / leaf_faces];
        const ClusterFacing f1 = leaf_facing_[le.position[1] / leaf_faces];
        if (f0 == ClusterFacing::kUnknown || f0 != f1) visit_interior_edge(le, f0, f1);
    }
    return ClusterFacing::kUnknown;
}

void SilhouetteTracker::collect_creases(uint32_t index, double crease_angle_rad, double cos_crease,
                                        std::vector<uint32_t>& r_creases) {
    if (tree_->crease_free(index, crease_angle_rad)) return;
    const internal::ConeNode& node = tree_->nodes[index];
    for (uint32_t k = node.edge_begin; k < node.edge_end; ++k) {
        const internal::ListedEdge& le = tree_->edges[k];
        if (edge_stamp_[le.edge] != frame_) {
            edge_stamp_[le.edge] = frame_;
            ++edges_tested_;
        }
        if (tree_->maybe_crease(le, cos_crease) &&
            is_crease(*mesh_, tree_->faces[le.position[0]], tree_->faces[le.position[1]], cos_crease)) {
            r_creases.push_back(le.edge);
        }
    }
    if (!node.is_leaf()) {
        collect_creases(index + 1, crease_angle_rad, cos_crease, r_creases);
        collect_creases(node.second_child, crease_angle_rad, cos_crease, r_creases);
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
