// SPDX-License-Identifier: MIT
// Mesh files (OBJ, OFF, PLY, STL) read through OpenMesh's readers into a plain Mesh.
#pragma once

#include "core/mesh.h"

#include <filesystem>
#include <string>
#include <vector>

namespace inkline::core {

struct LoadedMesh {
    Mesh mesh;
    std::vector<std::string> warnings;  // drawable oddities, e.g. skipped faces of < 3 vertices
};

// Reads a mesh file; polygons are fan-triangulated. Throws InputError naming the file when it is
// missing, unreadable, empty, has no faces, non-finite coordinates or out-of-range indices.
LoadedMesh load_mesh(const std::filesystem::path& path);

}  // namespace inkline::core
