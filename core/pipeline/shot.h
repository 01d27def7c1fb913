// SPDX-License-Identifier: MIT
// What a render draws, from what it is given: a scene file, a bare mesh (drawn as a 48-frame
// turntable around it) or a bare glTF file (its objects, animation and camera), with the
// caller's overrides. `inkline render` and the Python module open their input here.
//
//   open_shot -> (choose frames) -> settle_cameras -> load_meshes -> FramePipeline
#pragma once

#include "core/lines/smooth_contours.h"
#include "core/mesh/mesh_frames.h"
#include "core/scene/camera.h"
#include "core/scene/gltf_shot.h"
#include "core/scene/scene.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace inkline::core {

// A scene file (.json, any case of the extension) rather than a mesh or glTF file.
bool is_scene_file(const std::filesystem::path& path);

struct ShotRequest {
    std::filesystem::path input;       // scene (.json), mesh (.obj .off .ply .stl) or glTF (.gltf .glb)
    int max_image_side = kMaxImageSide;  // px; larger scene images are refused
    size_t max_faces = 50'000'000;       // larger meshes are refused while they are read
    // glTF input only (a bare glTF file, or a scene whose mesh is one; fps also with a write-on):
    // InputError otherwise, naming the option as `names` gives it.
    int gltf_scene = -1;    // the file's scene to draw; -1: its default scene
    std::string animation;  // the one animation to play (name or index); empty: all
    std::string camera;     // the camera to look through (its or its node's name); empty: the first
    double fps = 0.0;       // frame F is animation time F / fps; 0: the scene's (24 by default)
    // Write-on (s): overrides the scene's write_on; 0: the scene's. fps applies with a write-on on
    // any input.
    double write_on = 0.0;
    struct Names {
        const char* gltf_scene = "--gltf-scene";
        const char* animation = "--animation";
        const char* camera = "--camera";
        const char* fps = "--fps";
        const char* write_on = "--write-on";
        const char* max_faces = "--max-faces";
    } names;
};

struct Shot {
    Scene scene;
    bool from_scene = false;  // a scene file, not a bare mesh or glTF file
    std::shared_ptr<const GltfShot> gltf;  // the glTF read, when the input is or names one
    // The frames the input gives: the scene's, a glTF animation's, one still frame through a
    // glTF camera, or the bare mesh turntable's 1..48.
    int first_frame = 1;
    int last_frame = 48;
};

// Reads the scene (or the glTF file) and chooses the frames; meshes are read by load_meshes.
// Throws InputError.
Shot open_shot(const ShotRequest& request);

// With frames first..last chosen: a glTF shot's camera (and image size, unless the scene or
// `size` gives one) put into the scene, then every camera of those frames checked. Throws
// InputError for a camera that cannot be drawn.
void settle_cameras(Shot& shot, int first, int last, const std::optional<ImageSize>& size);

// What the caller sets over the scene, the default turntable's included.
struct ShotOverrides {
    std::optional<ImageSize> size;
    bool hidden = false;  // lines.hidden on (never off)
    std::optional<ContourMode> contour;
};

// Sets what `overrides` gives over the scene.
void apply_overrides(Scene& r_scene, const ShotOverrides& overrides);

// The meshes of the shot from frame `first` on; a bare mesh's default turntable is made around
// the mesh read, and `overrides` applied to the scene. Throws InputError (a mesh that cannot be
// read, or of more than request.max_faces faces).
std::unique_ptr<MeshFrames> load_meshes(Shot& shot, const ShotRequest& request, int first,
                                        const ShotOverrides& overrides);

}  // namespace inkline::core
