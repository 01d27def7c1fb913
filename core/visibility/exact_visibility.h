// SPDX-License-Identifier: MIT
// Exact occlusion by segment queries against a CGAL AABB tree of the mesh triangles: the
// reference every faster visibility pass is tested against (`--visibility exact`).
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/visibility/visibility.h"

#include <memory>

namespace inkline::core {

class ExactOcclusion final : public Occlusion {
  public:
    // Builds the tree over the valid faces of the mesh in its current (object-space) positions;
    // the faces around a vertex of very high valence are indexed apart, as for ray casting.
    ExactOcclusion(const Mesh& mesh, const EdgeTable& table);
    ~ExactOcclusion() override;

    void occluded(const Viewpoint& eye_object, std::span<const OcclusionQuery> queries,
                  std::span<uint8_t> r_occluded) const override;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace inkline::core
