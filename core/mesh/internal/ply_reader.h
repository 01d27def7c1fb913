// SPDX-License-Identifier: MIT
// A strict reader for PLY (ASCII, binary little and big endian). OpenMesh's PLY reader trusts the
// file: a vertex count larger than the data reads face lines as vertices, float index lists give
// a garbage mesh, a list count beyond the data reads past it. This one reads every element the
// header declares and refuses, naming the line (ASCII) or element (binary), anything it would
// have to guess at. Runs after check_ply (mesh_checks.h), which checks the header's structure.
#pragma once

#include "core/mesh/mesh.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace inkline::core::internal {

struct PlyContents {
    Mesh mesh;               // polygons fan-triangulated from their first corner
    size_t short_faces = 0;  // faces with fewer than 3 corners, skipped
};

// Reads the vertex element's x, y, z (any numeric type) and the face element's vertex_indices
// (or vertex_index) list of integers; other elements and properties are read and dropped.
// ASCII elements stand one per line, each with exactly the values its properties take; binary
// data ends exactly where the last element does. Throws InputError naming the file; also when
// the mesh has more than max_triangles triangles, as soon as reading passes that number.
PlyContents read_ply(const std::filesystem::path& path, const std::string& bytes, size_t max_triangles);

}  // namespace inkline::core::internal
