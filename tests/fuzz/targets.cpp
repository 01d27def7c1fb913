// SPDX-License-Identifier: MIT
#include "tests/fuzz/targets.h"

#include "core/error.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"
#include "core/scene/scene.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace inkline::fuzz {

void scene_target(const uint8_t* data, size_t size) {
    try {
        const core::Scene scene = core::parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
        // Cameras of the first and last frame exercise the motion and near/far fitting.
        core::Bounds bounds;
        bounds.add({-1.0, -1.0, -1.0});
        bounds.add({1.0, 1.0, 1.0});
        core::camera_at(scene, scene.first_frame, bounds);
        core::camera_at(scene, scene.last_frame, bounds);
    } catch (const InputError&) {
    }
}

void mesh_format_target(const char* extension, const uint8_t* data, size_t size) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("inkline_fuzz_" + std::to_string(::getpid()) + extension);
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
    try {
        const core::LoadedMesh loaded = core::load_mesh(path);
        const core::EdgeTable table = core::build_edge_table(loaded.mesh);
        core::describe_mesh(loaded.mesh, table);
    } catch (const InputError&) {
    }
    std::filesystem::remove(path);
}

void mesh_target(const uint8_t* data, size_t size) {
    if (size == 0) return;
    static const char* const kExtensions[] = {".obj", ".off", ".ply", ".stl"};
    mesh_format_target(kExtensions[data[0] % 4], data + 1, size - 1);
}

}  // namespace inkline::fuzz
