// SPDX-License-Identifier: MIT
// A fast reader for plain OBJ text, the common case of big meshes: one pass over the bytes
// instead of OpenMesh's two passes through string streams (1M triangles: about 10x faster).
// Anything it does not know for certain how OpenMesh would read is handed back to load_mesh,
// which reads the file through check_obj and OpenMesh as before.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.h"

namespace inkline::core::internal {

// An "o" or "g" statement: the name it gives to the triangles from `first_triangle` on.
struct ObjGroupStart {
    size_t first_triangle = 0;
    bool is_object = false;  // "o"; else "g" (its first name)
    std::string name;
};

struct ObjContents {
    Mesh mesh;               // polygons fan-triangulated from their first corner
    size_t short_faces = 0;  // "f" lines with fewer than 3 corners, skipped (as check_obj counts)
    bool over_limit = false; // reading stopped: more than max_triangles triangles (mesh incomplete)
    std::vector<ObjGroupStart> groups;  // every "o" and "g" statement, in file order
};

// The objects of an OBJ file's triangles: named by its "o" statements, or by its "g" statements
// when it has no "o" (each by its first name; triangles before the first are "default").
// Fewer than two distinct names: no objects (r_names and r_face_objects left empty).
void obj_objects(const ObjContents& contents, std::vector<std::string>& r_names, std::vector<uint32_t>& r_face_objects);

// The mesh of an OBJ file's text, exactly as check_obj + OpenMesh's reader + load_mesh's
// importer produce it (same float positions, same triangles in the same order), when every
// line is plain:
//   - empty, or a comment ('#' first);
//   - "v X Y Z [more]" with three plain decimal numbers (no '+', hex, inf or nan) within
//     kMaxCoordinate, anything after them ignored as OpenMesh ignores it;
//   - "vt U V [...]" with two plain numbers; "vn ..." and any other OBJ statement that OpenMesh
//     ignores for geometry ("o", "g", "s", "usemtl", "mtllib", "l", ...; is_obj_statement);
//   - "f C1 C2 ... [# comment]" with corners "I", "I/J", "I//K" or "I/J/K" (plain integers; a
//     negative I counts back from the vertices read so far), every I resolving to an existing
//     vertex; a face of fewer than 3 distinct corners is counted in short_faces.
// Lines start at their first byte (no leading blanks) and may end in '\r'; a UTF-8 byte order
// mark before the first line is skipped. nullopt for anything
// else, including every file load_mesh would refuse: the caller then reads it the general way,
// which reports the problem.
// Reading stops, with over_limit set, once the triangles pass max_triangles.
std::optional<ObjContents> read_plain_obj(std::string_view text,
                                          size_t max_triangles = std::numeric_limits<size_t>::max());

}  // namespace inkline::core::internal
