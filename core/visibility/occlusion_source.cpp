// SPDX-License-Identifier: MIT
#include "core/visibility/occlusion_source.h"

#include "core/error.h"
#include "core/visibility/exact_visibility.h"
#include "core/visibility/raycast_visibility.h"

namespace inkline::core {
namespace {

class RaycastSource final : public OcclusionSource {
  public:
    const Occlusion& prepare(const Mesh& mesh, const EdgeTable& table, const Projection&, MeshChange change) override {
        if (!occlusion_ || change == MeshChange::kTopology) {
            occlusion_ = std::make_unique<RaycastOcclusion>(mesh, table);
        } else if (change == MeshChange::kPositions) {
            occlusion_->update_positions(mesh);
        }
        return *occlusion_;
    }
    VisibilityMode mode() const override { return VisibilityMode::kRaycast; }

  private:
    std::unique_ptr<RaycastOcclusion> occlusion_;
};

class ExactSource final : public OcclusionSource {
  public:
    const Occlusion& prepare(const Mesh& mesh, const EdgeTable& table, const Projection&, MeshChange change) override {
        // A CGAL tree cannot be refitted: built again for new positions.
        if (!occlusion_ || change != MeshChange::kNone) occlusion_ = std::make_unique<ExactOcclusion>(mesh, table);
        return *occlusion_;
    }
    VisibilityMode mode() const override { return VisibilityMode::kExact; }

  private:
    std::unique_ptr<ExactOcclusion> occlusion_;
};

constexpr VisibilityMode kModes[] = {VisibilityMode::kGl, VisibilityMode::kRaycast, VisibilityMode::kExact};

}  // namespace

const char* visibility_mode_name(VisibilityMode mode) {
    switch (mode) {
        case VisibilityMode::kGl: return "gl";
        case VisibilityMode::kRaycast: return "raycast";
        case VisibilityMode::kExact: return "exact";
    }
    throw InternalError("visibility mode " + std::to_string(int(mode)));
}

std::optional<VisibilityMode> visibility_mode_from_name(std::string_view name) {
    for (const VisibilityMode mode : kModes) {
        if (name == visibility_mode_name(mode)) return mode;
    }
    return std::nullopt;
}

VisibilityMode parse_visibility_mode(std::string_view text, const char* key) {
    if (const std::optional<VisibilityMode> mode = visibility_mode_from_name(text)) return *mode;
    throw InputError(std::string(key) + " '" + quote_value(text) + "': expected gl, raycast or exact");
}

std::unique_ptr<OcclusionSource> make_cpu_occlusion(VisibilityMode mode) {
    switch (mode) {
        case VisibilityMode::kRaycast:
            if (!raycast_available()) {
                throw InputError("raycast visibility: this build has no Embree; install libembree-dev (Embree 3) "
                                 "and rebuild, or use exact visibility");
            }
            return std::make_unique<RaycastSource>();
        case VisibilityMode::kExact: return std::make_unique<ExactSource>();
        case VisibilityMode::kGl: break;
    }
    throw InternalError(std::string("make_cpu_occlusion: no CPU test for visibility mode ") + visibility_mode_name(mode));
}

}  // namespace inkline::core
