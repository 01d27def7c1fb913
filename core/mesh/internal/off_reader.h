// SPDX-License-Identifier: MIT
// A strict reader for ASCII OFF files. OpenMesh's OFF reader trusts the counts in the file
// (a face declaring two billion corners allocates them), so inkline reads OFF itself.
#pragma once

#include "core/mesh/mesh.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace inkline::core::internal {

struct OffContents {
    Mesh mesh;                // polygons fan-triangulated from their first corner
    size_t short_faces = 0;   // faces with fewer than 3 corners, skipped
};

// Reads [ST][C][N]OFF: the counts, then one vertex per line (its first three numbers; colours,
// normals and texture coordinates after them are ignored), then one face per line. Throws
// InputError naming the file and line for anything malformed; binary OFF is refused.
// Throws too when the mesh has more than max_triangles triangles, as soon as reading passes it.
OffContents read_off(const std::filesystem::path& path, uintmax_t file_size, size_t max_triangles);

}  // namespace inkline::core::internal
