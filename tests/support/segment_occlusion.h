// SPDX-License-Identifier: MIT
// An independent occlusion check for points on a mesh: the segment from the eye to the point
// against every face but the point's own, in double precision (Moller-Trumbore over a bounding
// volume hierarchy of the faces), stopping 1e-6 of its length short of the point as
// core::internal::kSegmentEndGap does. The tone tests and bench/tone check drawn dots with it.
// Based on: T. Moller, B. Trumbore. Fast, Minimum Storage Ray-Triangle Intersection. JGT 1997.
#pragma once

#include "core/mesh/mesh.h"
#include "core/scene/camera.h"
#include "core/tone/stipple.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace inkline::test {

class SegmentOcclusion {
  public:
    // The mesh in object space; it is copied.
    explicit SegmentOcclusion(const core::Mesh& mesh);

    // Whether a face other than own_face meets the segment from eye to p (object space), short
    // of its last 1e-6. From an eye at infinity the segment starts four mesh diagonals from p.
    bool hidden(const core::Viewpoint& eye, const glm::dvec3& p, uint32_t own_face) const;

    // The share of the dots (their face and barycentric coordinates on this mesh) hidden seen from
    // eye (object space); 0 without dots.
    double hidden_share(const core::Viewpoint& eye, std::span<const core::Dot> dots) const;

    // A dot's point on this mesh, object space.
    glm::dvec3 point_of(const core::Dot& dot) const;

  private:
    struct Node {
        glm::dvec3 lo, hi;
        uint32_t first = 0, count = 0;  // a leaf: its faces in order_; an inner node: count 0, first its left child
        uint32_t right = 0;             // an inner node's right child
    };
    uint32_t build(uint32_t first, uint32_t count);

    std::vector<glm::dvec3> corners_;  // three per face
    double reach_ = 1.0;               // four diagonals of the mesh's box
    std::vector<uint32_t> order_;      // faces, grouped by leaf
    std::vector<Node> nodes_;
};

}  // namespace inkline::test
