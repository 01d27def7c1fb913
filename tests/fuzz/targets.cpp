// SPDX-License-Identifier: MIT
#include "tests/fuzz/targets.h"

#include "core/error.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"
#include "core/scene/gltf_shot.h"
#include "core/scene/scene.h"
#include "core/strokes/line_styles.h"

#include <cstring>
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
        // Every combination of what style rules select, and the dashes of each resulting style.
        core::StyleSheet sheet(scene.brush, scene.styles);
        for (const core::LineKind kind : core::kAllLineKinds) {
            for (const bool visible : {true, false}) {
                for (const core::LineRole role : {core::LineRole::kOuter, core::LineRole::kInner}) {
                    const uint32_t style = sheet.resolve({kind, visible, "Tree.001", role});
                    core::dash_intervals(sheet.styles()[style].brush.dash_px, -37.5, 1000.0);
                }
            }
        }
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

void gltf_target(const uint8_t* data, size_t size) {
    if (size == 0) return;
    const auto path = std::filesystem::temp_directory_path() /
                      ("inkline_fuzz_" + std::to_string(::getpid()) + (data[0] % 2 == 0 ? ".glb" : ".gltf"));
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    try {
        core::GltfOptions options;
        options.max_faces = 1'000'000;
        const core::GltfShot shot(path, options);
        const core::EdgeTable table = core::build_edge_table(shot.rest());
        core::describe_mesh(shot.rest(), table);
        std::vector<glm::vec3> positions;
        const auto range = shot.frame_range().value_or(std::pair(1, 1));
        shot.positions_at(range.first, positions);
        shot.positions_at(range.second, positions);
        core::Scene scene;
        core::apply_gltf_camera(shot, scene, range.first, std::min(range.second, range.first + 2), false);
    } catch (const InputError&) {
    }
    std::filesystem::remove(path);
}

void mesh_arrays_target(const uint8_t* data, size_t size) {
    if (size == 0) return;
    const size_t split = std::min(size - 1, size_t(data[0]) * 8);
    std::vector<double> coordinates(split / 8);
    if (!coordinates.empty()) std::memcpy(coordinates.data(), data + 1, coordinates.size() * 8);
    std::vector<int64_t> indices((size - 1 - split) / 8);
    if (!indices.empty()) std::memcpy(indices.data(), data + 1 + split, indices.size() * 8);
    try {
        const core::Mesh mesh = core::mesh_from_arrays(coordinates, indices, "vertices", "faces", {.max_faces = 100'000});
        core::describe_mesh(mesh, core::build_edge_table(mesh));
    } catch (const InputError&) {
    }
}

}  // namespace inkline::fuzz
