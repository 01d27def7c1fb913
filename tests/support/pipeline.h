// SPDX-License-Identifier: MIT
// Runs the core pipeline (brute extraction, chaining, exact visibility) on one mesh and camera.
#pragma once

#include "core/lines/chaining.h"
#include "core/mesh/mesh.h"
#include "core/pipeline/frame_lines.h"
#include "core/scene/scene.h"

#include <glm/vec3.hpp>

namespace inkline::test {

struct View {
    glm::dvec3 eye{0.0, 0.0, 4.0};
    glm::dvec3 target{0.0};
    double fov_y_deg = 35.0;
    int size = 1024;
};

core::Camera camera_for(const View& view, const core::Mesh& mesh);

// Feature chains (before visibility) seen from a view.
std::vector<core::Chain> feature_chains(const core::Mesh& mesh, const View& view, const core::LineOptions& lines);

core::FrameLines trace(const core::Mesh& mesh, const View& view, const core::LineOptions& lines = {});

}  // namespace inkline::test
