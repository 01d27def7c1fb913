// SPDX-License-Identifier: MIT
// Incremental silhouette tracker: each frame's feature edges, identical to extract_feature_edges,
// testing only the edges that a hierarchy of normal cones cannot prove silhouette-free, with
// boundary and crease edges cached per topology. Holds the only frame-to-frame state. A walk
// from last frame's silhouette alone (N. Thongthungwong, R. Lipikorn. Data Reduction for Finding
// Silhouette Edges on 3D-Animated Model. ICFCC 2013) is kept as an option to compare (TrackerSearch).
// Based on: P. Sander, X. Gu, S. Gortler, H. Hoppe, J. Snyder. Silhouette Clipping. SIGGRAPH 2000.
//           A. Johannsen, M. Carter. Clustered Backface Culling. Journal of Graphics Tools, 1998.
#pragma once

#include "core/lines/features.h"
#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace inkline::core {

// How a run finds each frame's feature edges (`--tracker`): both give the same edges.
enum class TrackerMode : uint8_t {
    kIncremental,  // SilhouetteTracker: a full pass on the first frame, then what it cannot rule out
    kBrute,        // extract_feature_edges: every edge, every frame
};

// "incremental" or "brute".
const char* tracker_mode_name(TrackerMode mode);
// The mode of that name; nullopt for any other text.
std::optional<TrackerMode> tracker_mode_from_name(std::string_view name);
// The mode of that name; throws InputError "KEY 'TEXT': expected incremental or brute".
TrackerMode parse_tracker_mode(std::string_view text, const char* key);

namespace internal {
class ConeTree;
enum class ClusterFacing : uint8_t;
struct ListedEdge;
}  // namespace internal

// How frames after a full pass search for silhouette edges.
enum class TrackerSearch : uint8_t {
    kHierarchy,         // the cone hierarchy alone: exact, and the fastest
    kWalkAndHierarchy,  // the walk from last frame's silhouette, then the hierarchy: exact
    kWalkOnly,          // the walk alone: loses lines that appear or jump (comparison only)
};

struct TrackerOptions {
    bool deforming = false;  // positions change between updates (same topology): refit each frame
    TrackerSearch search = TrackerSearch::kHierarchy;
    uint32_t leaf_faces = 16;  // faces per leaf cluster of the cone hierarchy
};

// What the last update did, beyond FeatureEdges' edges_tested and faces_tested.
struct TrackerStats {
    bool full_pass = false;          // every edge tested (first update, after reset)
    size_t silhouette_edges = 0;
    size_t kept = 0;                 // last frame's silhouette edges that still are (walk only)
    size_t walked = 0;               // found by walking from last frame's silhouette (walk only)
    size_t proven = 0;               // found by the cone hierarchy, after the walk if any
    size_t nodes_visited = 0;        // cone tests
};

class SilhouetteTracker {
  public:
    // Builds the cone hierarchy from the first frame's mesh. `table` is the mesh's edge table and
    // must outlive the tracker. Without options.deforming every later update must pass a mesh
    // with these same positions (camera and rigid motion enter only through eye_object).
    SilhouetteTracker(const EdgeTable& table, const Mesh& mesh, const TrackerOptions& options = {});
    ~SilhouetteTracker();
    SilhouetteTracker(SilhouetteTracker&&) noexcept;
    SilhouetteTracker& operator=(SilhouetteTracker&&) noexcept;

    // The feature edges of `mesh` seen from `eye_object` (object space): the same edges, kinds
    // and order as extract_feature_edges(mesh, table, eye_object, lines). edges_tested and
    // faces_tested count the edges classified and the faces whose facing was evaluated.
    FeatureEdges update(const Mesh& mesh, const Viewpoint& eye_object, const LineOptions& lines);

    // Forgets the previous frame, so that the next update is a full pass (chunk start, cut).
    void reset();

    const TrackerStats& stats() const { return stats_; }

  private:
    enum class Visit : uint8_t { kSeen, kPlain, kSilhouette };

    void begin_frame();
    void sort_found();  // found_ into silhouettes_, ascending
    bool is_front(uint32_t position);  // of the face at this position in ConeTree::faces
    double facing_at(uint32_t position) const;  // facing_value of that face
    Visit visit_edge(uint32_t edge);
    // Tests an edge listed in the cone tree; a face's facing given as known is not evaluated.
    Visit visit_interior_edge(const internal::ListedEdge& edge, internal::ClusterFacing known0,
                              internal::ClusterFacing known1);
    void full_pass(const LineOptions& lines, double cos_crease);
    void all_creases(double cos_crease);
    void search();
    void walk();
    void extend_from_found();
    void walk_from_stopped(uint32_t edge);
    // False when the vertex was already walked around this frame; marks it.
    bool first_visit(uint32_t vertex);
    internal::ClusterFacing prove(uint32_t node);
    void collect_creases(uint32_t node, double crease_angle_rad, double cos_crease,
                         std::vector<uint32_t>& r_creases);
    FeatureEdges assemble(const LineOptions& lines) const;

    const EdgeTable* table_;
    TrackerOptions options_;
    std::unique_ptr<internal::ConeTree> tree_;
    size_t face_count_;
    std::vector<uint32_t> boundary_;       // non-interior edges, ascending (constant)
    std::vector<uint32_t> creases_;        // ascending; for a static mesh cached per crease angle
    std::optional<double> creases_angle_;  // the crease angle creases_ holds, static meshes
    std::vector<uint32_t> silhouettes_;    // this (after update: last) frame's, ascending
    bool need_full_pass_ = true;

    // Per-frame work, valid during update. Stamps equal to frame_ mark this frame's entries, so
    // nothing is cleared between frames.
    const Mesh* mesh_ = nullptr;
    Viewpoint eye_;
    uint32_t frame_ = 0;
    // Per valid face, in ConeTree::faces order: (stamp << 1) | (facing_value > 0), for the
    // frame whose face_stamp_ (1..127, cycling) last evaluated it.
    std::vector<uint8_t> face_state_;
    uint8_t face_stamp_ = 0;
    // A static mesh's faces in ConeTree::faces order with their own copy of the vertices (empty
    // for a deforming mesh, which is read in place).
    std::vector<glm::uvec3> local_triangles_;
    std::vector<glm::vec3> local_positions_;
    std::vector<uint32_t> face_position_;  // #F, each face's index in ConeTree::faces (walk only)
    bool stamp_edges_ = true;
    std::vector<uint32_t> edge_stamp_;   // #E when stamp_edges_, tested this frame
    std::vector<uint32_t> vertex_stamp_; // #V with the walk, every edge around it tested this frame
    // Per leaf of the cone tree, what this frame proved of it (kUnknown: its edges were tested).
    std::vector<internal::ClusterFacing> leaf_facing_;
    std::vector<uint32_t> found_;        // silhouette edges found this frame, discovery order
    std::vector<uint64_t> found_bits_;   // #E bits, all zero between frames: sorts found_
    std::vector<uint32_t> stopped_;      // last frame's silhouette edges that no longer are
    std::vector<uint32_t> ring_, next_ring_;  // scratch of walk_from_stopped
    size_t extended_ = 0;                // found_[0, extended_) had their neighbours tested
    size_t edges_tested_ = 0;
    size_t faces_tested_ = 0;
    TrackerStats stats_;
};

}  // namespace inkline::core
