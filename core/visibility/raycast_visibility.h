// SPDX-License-Identifier: MIT
// Occlusion by Embree occlusion rays against a BVH of the mesh triangles (`--visibility raycast`):
// the fast exact answer on machines without a GPU. Same definition and end gap as ExactOcclusion.
// Based on: I. Wald et al. Embree: A Kernel Framework for Efficient CPU Ray Tracing. SIGGRAPH 2014.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/visibility/visibility.h"

#include <memory>

namespace inkline::core {

// True when this build has Embree; otherwise constructing RaycastOcclusion throws InputError.
bool raycast_available();

class RaycastOcclusion final : public Occlusion {
  public:
    // Builds the BVH over the valid faces of the mesh in its current (object-space) positions.
    // The faces around a vertex of very high valence (a cone's apex, a disc cap's centre) are
    // indexed apart, so that a ray near that vertex tests a few of them, not a share of all.
    // Keeps a reference to `table`, which must outlive this object, and reads the triangles of
    // `mesh` in place: the mesh must outlive it too, with the same triangles, until the first
    // update_positions (which copies what it keeps). Throws InputError when this build has no
    // Embree.
    RaycastOcclusion(const Mesh& mesh, const EdgeTable& table);
    ~RaycastOcclusion() override;

    // Moves the vertices to `mesh`'s positions and refits the BVH (a deforming sequence). The
    // topology must be the one given to the constructor. Rigid motion needs no update: callers
    // move the eye into object space instead.
    void update_positions(const Mesh& mesh);

    // Queries run in parallel; each result depends on its query only.
    void occluded(const Viewpoint& eye_object, std::span<const OcclusionQuery> queries,
                  std::span<uint8_t> r_occluded) const override;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace inkline::core
