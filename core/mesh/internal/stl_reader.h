// SPDX-License-Identifier: MIT
// A strict reader for STL, binary and ASCII. OpenMesh's STL reader draws what it got from a
// truncated ASCII file without a word, and takes a binary file whose triangle count disagrees
// with its size for ASCII. This one refuses both, naming the line (ASCII) or the counts (binary).
#pragma once

#include "core/mesh/mesh.h"

#include <cstddef>
#include <filesystem>
#include <string>

namespace inkline::core::internal {

struct StlContents {
    Mesh mesh;             // corners at the same position share one vertex
    size_t collapsed = 0;  // triangles with two corners at the same position, skipped
};

// Binary when the size is exactly 84 + 50 * (the count at byte 80); ASCII ("solid ...
// endsolid", facets of three vertices) when the file is text starting with "solid". Every
// coordinate must be finite and within kMaxCoordinate; normals are not used. Throws InputError
// naming the file; also when the mesh has more than max_triangles triangles.
StlContents read_stl(const std::filesystem::path& path, const std::string& bytes, size_t max_triangles);

}  // namespace inkline::core::internal
