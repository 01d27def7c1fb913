// SPDX-License-Identifier: MIT
// Test helper: several named meshes as the objects of one core::MeshFrames, each moving at its own
// constant velocity (a shot of rigid objects in memory, as a glTF shot gives them).
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/mesh_frames.h"

#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

namespace inkline::test {

struct Part {
    std::string name;
    core::Mesh mesh;
    glm::dvec3 velocity{0.0};  // world units per frame; frame 1 is the mesh as given
};

// The parts as one mesh of objects, in order (a part's faces follow the previous part's).
std::unique_ptr<core::MeshFrames> objects_frames(std::vector<Part> parts);

// An open tube around the y axis, |y| <= half_length: `segments` around, `rings` along.
core::Mesh tube(int segments, int rings, double radius, double half_length);

}  // namespace inkline::test
