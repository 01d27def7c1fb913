// SPDX-License-Identifier: MIT
// RaycastOcclusion in a build without Embree: the mode exists but reports itself unavailable.
#include "core/visibility/raycast_visibility.h"

#include "core/error.h"

namespace inkline::core {

struct RaycastOcclusion::Impl {};

bool raycast_available() { return false; }

RaycastOcclusion::RaycastOcclusion(const Mesh&, const EdgeTable&) {
    throw InputError(
        "--visibility raycast: this build has no Embree; install libembree-dev (Embree 3) and rebuild, "
        "or use --visibility exact");
}

RaycastOcclusion::~RaycastOcclusion() = default;

// Unreachable: the constructor always throws.
void RaycastOcclusion::update_positions(const Mesh&) { INKLINE_CHECK(impl_ != nullptr); }

void RaycastOcclusion::occluded(const glm::dvec3&, std::span<const OcclusionQuery>, std::span<uint8_t>) const {
    INKLINE_CHECK(impl_ != nullptr);
}

}  // namespace inkline::core
