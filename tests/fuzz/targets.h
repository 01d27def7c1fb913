// SPDX-License-Identifier: MIT
// Fuzz targets for the input paths: the scene parser and mesh loading. Both must either succeed
// or throw InputError: any other exception, crash or sanitizer report is a bug.
#pragma once

#include <cstddef>
#include <cstdint>

namespace inkline::fuzz {

// Parses the bytes as a scene file.
void scene_target(const uint8_t* data, size_t size);

// Writes bytes [1, size) to a temporary mesh file whose extension (.obj .off .ply .stl) is chosen
// by data[0], then loads it and builds its topology report.
void mesh_target(const uint8_t* data, size_t size);

// Writes all the bytes to a temporary mesh file with the given extension (".obj", ".off", ".ply"
// or ".stl"), then loads it and builds its topology report: one reader fuzzed on its own.
void mesh_format_target(const char* extension, const uint8_t* data, size_t size);

// Writes bytes [1, size) to a temporary .glb (data[0] even) or .gltf file, reads it as a glTF
// shot and evaluates its first and last frames and its camera.
void gltf_target(const uint8_t* data, size_t size);

// The Python module's in-code meshes: data[0] splits the rest into float64 coordinates and int64
// indices (little-endian, as numpy holds them; a trailing part of a value is dropped), made into
// a mesh with core::mesh_from_arrays and its topology report built.
void mesh_arrays_target(const uint8_t* data, size_t size);

}  // namespace inkline::fuzz
