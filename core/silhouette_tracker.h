// SPDX-License-Identifier: MIT
// Incremental silhouette tracker: each frame's feature edges, identical to extract_feature_edges,
// found by re-testing last frame's silhouette and walking from it, with a hierarchy of normal
// cones proving that no silhouette was missed elsewhere. Holds the only frame-to-frame state.
// Based on: P. Sander, X. Gu, S. Gortler, H. Hoppe, J. Snyder. Silhouette Clipping. SIGGRAPH 2000.
//           A. Johannsen, M. Carter. Clustered Backface Culling. Journal of Graphics Tools, 1998.
#pragma once

#include "core/features.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/topology.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace inkline::core {

namespace internal {
class ConeTree;
enum class ClusterFacing : uint8_t;
}  // namespace internal

struct TrackerOptions {
    bool deforming = false;    // positions change between updates (same topology): refit each frame
    bool exact = true;         // false: the thesis's walk alone, which loses lines (for comparison)
    uint32_t leaf_faces = 8;   // faces per leaf cluster of the cone hierarchy
};

// What the last update did, beyond FeatureEdges' edges_tested and faces_tested.
struct TrackerStats {
    bool full_pass = false;          // every edge tested (first update, after reset)
    size_t silhouette_edges = 0;
    size_t kept = 0;                 // last frame's silhouette edges that still are
    size_t walked = 0;               // found by walking from last frame's silhouette
    size_t proven = 0;               // found only by the cone hierarchy (new loops, lost lines)
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
    FeatureEdges update(const Mesh& mesh, const glm::dvec3& eye_object, const LineOptions& lines);

    // Forgets the previous frame, so that the next update is a full pass (chunk start, cut).
    void reset();

    const TrackerStats& stats() const { return stats_; }

  private:
    enum class Visit : uint8_t { kSeen, kPlain, kSilhouette };

    void begin_frame();
    bool is_front(uint32_t face);
    Visit visit_edge(uint32_t edge);
    void full_pass(const LineOptions& lines, double cos_crease);
    void track();
    void extend_from_found();
    void walk_from_stopped(uint32_t edge);
    internal::ClusterFacing prove(uint32_t node);
    internal::ClusterFacing certified_facing(uint32_t face, uint32_t below_node) const;
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
    glm::dvec3 eye_{0.0};
    uint32_t frame_ = 0;
    std::vector<uint32_t> face_stamp_;   // #F
    std::vector<uint8_t> face_front_;    // #F, facing_value > 0 when face_stamp_ == frame_
    std::vector<uint32_t> edge_stamp_;   // #E, tested this frame
    std::vector<uint32_t> node_stamp_;   // per cone node, tested this frame
    std::vector<internal::ClusterFacing> node_facing_;  // proven this frame
    std::vector<uint32_t> found_;        // silhouette edges found this frame, discovery order
    std::vector<uint32_t> stopped_;      // last frame's silhouette edges that no longer are
    std::vector<uint32_t> ring_, next_ring_;  // scratch of walk_from_stopped
    size_t extended_ = 0;                // found_[0, extended_) had their neighbours tested
    size_t edges_tested_ = 0;
    size_t faces_tested_ = 0;
    TrackerStats stats_;
};

}  // namespace inkline::core
