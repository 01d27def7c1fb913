// SPDX-License-Identifier: MIT
// Mesh files (OBJ, OFF, PLY, STL) read into a plain Mesh: OFF, PLY and STL by inkline's own strict
// readers (core/internal/), OBJ by a fast reader of its own or through OpenMesh after check_obj.
#pragma once

#include "core/mesh/mesh.h"

#include <cstddef>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace inkline::core {

struct LoadedMesh {
    Mesh mesh;
    std::vector<std::string> warnings;  // drawable oddities, e.g. skipped faces of < 3 vertices
    // An OBJ file's objects ("o" groups, or "g" groups without any "o") when it has two or more,
    // and the object of every face; empty otherwise.
    std::vector<std::string> object_names = {};
    std::vector<uint32_t> face_objects = {};
};

struct MeshLimits {
    // The most triangles (after fan triangulation) a mesh may have; checked while reading, from
    // the header's count where the format has one, so a larger mesh is refused before its
    // memory is spent.
    size_t max_faces = std::numeric_limits<size_t>::max();
};

// Reads a mesh file; polygons are fan-triangulated. Throws InputError naming the file (and the
// line or element) when it is missing, unreadable, not a regular file, empty, has no faces,
// non-finite coordinates, out-of-range indices, anything a reader would have to guess at (counts
// that disagree with the data, truncation), or more faces than `limits` allow. Nothing a
// library prints reaches the user.
LoadedMesh load_mesh(const std::filesystem::path& path, const MeshLimits& limits = {});

// A mesh from flat arrays (the Python module's vertices and faces): `coordinates` holds x, y, z
// of each vertex, `indices` three vertex indices per counter-clockwise triangle. Messages name
// the arrays `coordinates_name` and `indices_name`, with the row at fault. Throws InputError for
// a count that is not a multiple of 3, no vertex or no triangle, a coordinate not finite or beyond
// kMaxCoordinate, an index out of range, or more triangles than `limits` allow.
Mesh mesh_from_arrays(std::span<const double> coordinates, std::span<const int64_t> indices,
                      const std::string& coordinates_name, const std::string& indices_name,
                      const MeshLimits& limits = {});

// The whole of an input file, with the checks load_mesh makes first: InputError naming the file
// when it is missing, a folder or not a regular file, unreadable (and why), empty, or too large
// for memory.
std::string read_input_file(const std::filesystem::path& path);

}  // namespace inkline::core
