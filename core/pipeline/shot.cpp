// SPDX-License-Identifier: MIT
#include "core/pipeline/shot.h"

#include "core/error.h"
#include "core/mesh/mesh_io.h"

#include <tuple>
#include <utility>

namespace inkline::core {

bool is_scene_file(const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    return ext == ".json" || ext == ".JSON";
}

Shot open_shot(const ShotRequest& request) {
    Shot shot;
    shot.from_scene = is_scene_file(request.input);
    Scene& scene = shot.scene;
    if (shot.from_scene) {
        scene = load_scene(request.input, request.max_image_side);
    } else {
        scene.mesh.path = request.input;
        scene.first_frame = 1;
        scene.last_frame = 48;
        if (is_gltf_path(request.input)) scene.gltf.emplace();
    }
    const ShotRequest::Names& n = request.names;
    if (request.write_on != 0.0) {
        if (!(request.write_on > 0.0 && request.write_on <= kMaxWriteOnSeconds))
            throw InputError(std::string(n.write_on) + ": must be above 0 and at most " + std::to_string(int(kMaxWriteOnSeconds)) + " seconds");
        scene.write_on_s = request.write_on;
    }
    if (!scene.gltf) {
        for (const auto& [given, option] : {std::pair(request.gltf_scene >= 0, n.gltf_scene), std::pair(!request.animation.empty(), n.animation),
                                            std::pair(!request.camera.empty(), n.camera)}) {
            if (given) throw InputError(std::string(option) + ": applies only to glTF input (.gltf, .glb)");
        }
        if (request.fps > 0.0) {
            if (scene.write_on_s == 0.0) throw InputError(std::string(n.fps) + ": applies only to glTF input (.gltf, .glb) or with a write-on");
            scene.fps = request.fps;
        }
    } else {
        GltfSettings& g = *scene.gltf;
        if (request.gltf_scene >= 0) g.scene = request.gltf_scene;
        if (!request.animation.empty()) g.animation = request.animation;
        if (!request.camera.empty()) g.camera = request.camera;
        if (request.fps > 0.0) scene.fps = request.fps;
        shot.gltf = std::make_shared<GltfShot>(scene.mesh.path,
                                               GltfOptions{g.scene, g.animation, g.camera, scene.fps, request.max_faces});
        // The file's frames unless the scene gives them: its animation, else one still frame
        // through its camera, else the 48-frame turntable of a bare mesh.
        if (!scene.given.frames) {
            if (const auto range = shot.gltf->frame_range()) {
                std::tie(scene.first_frame, scene.last_frame) = *range;
            } else if (shot.gltf->camera() || scene.given.camera) {
                scene.first_frame = scene.last_frame = 1;
            }
        }
    }
    shot.first_frame = scene.first_frame;
    shot.last_frame = scene.last_frame;
    return shot;
}

void settle_cameras(Shot& shot, int first, int last, const std::optional<ImageSize>& size) {
    if (shot.gltf) {
        if (size) shot.scene.image = *size;
        apply_gltf_camera(*shot.gltf, shot.scene, first, last, shot.scene.given.image || size.has_value());
    }
    check_cameras(shot.scene, first, last);
}

std::unique_ptr<MeshFrames> load_meshes(Shot& shot, const ShotRequest& request, int first,
                                        const ShotOverrides& overrides) {
    Scene& scene = shot.scene;
    std::unique_ptr<MeshFrames> meshes;
    if (shot.gltf) {
        meshes = std::make_unique<MeshFrames>(shot.gltf, scene.mesh.path);
    } else {
        meshes = std::make_unique<MeshFrames>(scene.mesh, first, MeshLimits{request.max_faces});
    }
    const size_t faces = meshes->at(first).triangles.size();
    if (faces > request.max_faces) {
        throw InputError(meshes->path_of(first).string() + ": " + std::to_string(faces) + " faces exceed the limit of " +
                         std::to_string(request.max_faces) + " (raise it with " + request.names.max_faces + ")");
    }
    if (!shot.from_scene && !shot.gltf) {
        const int first_frame = scene.first_frame, last_frame = scene.last_frame;
        scene = default_turntable_scene(request.input, bounds_of(meshes->at(first).positions));
        scene.first_frame = first_frame;
        scene.last_frame = last_frame;
    }
    apply_overrides(scene, overrides);
    return meshes;
}

void apply_overrides(Scene& r_scene, const ShotOverrides& overrides) {
    if (overrides.size) r_scene.image = *overrides.size;
    if (overrides.hidden) r_scene.lines.hidden = true;
    if (overrides.contour) r_scene.lines.contour = *overrides.contour;
}

}  // namespace inkline::core
