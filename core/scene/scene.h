// SPDX-License-Identifier: MIT
// The scene file (JSON, version 1): mesh or mesh sequence, frames, image, camera, object motion,
// light and line kinds. docs/scene.md describes every key. Each stage owns its options (LineOptions
// in core/lines/features.h, BrushStyle and Light in core/strokes/brush_style.h, MeshSource in
// core/mesh/mesh_frames.h); the scene holds them.
#pragma once

#include "core/lines/features.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_frames.h"
#include "core/scene/camera.h"
#include "core/strokes/brush_style.h"
#include "core/strokes/line_styles.h"
#include "core/tone/tone_options.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace inkline::core {

// Largest accepted image side by default, px: keeps a typo from allocating gigabytes
// (`--max-image-side` changes it).
inline constexpr int kMaxImageSide = 16384;

// The narrowest orthographic view, world units (a scene's camera.ortho_height, a glTF camera's
// 2 ymag): 2 / height times a coordinate at the limit of 1e19 stays inside float range for the
// GL pass.
inline constexpr double kMinOrthoHeight = 1e-18;

struct Rotation {
    glm::dvec3 axis{0.0, 1.0, 0.0};
    double degrees = 0.0;  // over the scene's frame range
    glm::dvec3 center{0.0};
};

struct CameraPose {
    glm::dvec3 eye{0.0, 0.0, 4.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fov_y_deg = 35.0;
    std::optional<double> ortho_height{};  // set: orthographic, this high (world units); Camera::ortho_height
};

struct CameraSpec {
    CameraPose pose;                      // the single-pose form
    std::optional<Rotation> orbit;        // turntable about pose.target
    std::map<int, CameraPose> per_frame;  // the explicit form; non-empty selects it
    std::optional<double> near, far;      // default: fitted to the mesh bounds each frame
};

// What a scene whose `mesh` is a glTF file picks from it (docs/gltf.md).
struct GltfSettings {
    int scene = -1;         // the file's scene; -1: its default
    std::string animation;  // empty: every animation together
    std::string camera;     // empty: the scene's first camera
};

// Line settings for the objects whose names match a glob (scene "objects"; docs/scene.md).
struct ObjectRule {
    std::string pattern;  // fnmatch(3) glob over object names ("Ground", "Tree.*")
    bool lines = true;    // false: a holdout, which hides lines and draws none
    std::optional<bool> silhouette, boundary, crease, intersection;  // override the scene's lines.*
    std::optional<bool> tone;  // false: no tone on the object (a holdout has none either)
    TonePatch tone_set;        // "tone": {...}: the object's own mode, curve, colour and opacity
};

// The longest write-on (s): a day.
inline constexpr double kMaxWriteOnSeconds = 86400.0;

struct Scene {
    std::filesystem::path file;  // where it was read from; empty for a built-in scene
    MeshSource mesh;
    std::optional<GltfSettings> gltf;  // set when mesh.path is a .gltf or .glb file
    double fps = 24.0;                 // frame F of an animated glTF is its time F / fps; write-on frames per second
    double write_on_s = 0.0;           // write-on: each frame drawn stroke by stroke in this time; 0: none
    // Which of frames, image and camera the scene file set; a glTF file sets the others.
    struct Given {
        bool frames = false, image = false, camera = false;
    } given;
    int first_frame = 1;
    int last_frame = 1;
    ImageSize image{1024, 1024};
    CameraSpec camera;
    std::optional<Rotation> object_rotation;
    Light light;
    LineOptions lines;
    BrushStyle brush;
    // Per-object line settings: glob patterns in sorted order, exact names after every glob, so
    // a later rule that matches overrides an earlier one key by key.
    std::vector<ObjectRule> objects;
    // Line styles (docs/styles.md), in the order they apply.
    std::vector<StyleRule> styles;
    // Tone on the surface (docs/tone.md); mode kNone: none.
    ToneOptions tone;
};

// Where the normals tone reads (and the preview's toon underlay) split at creases, degrees:
// tone.crease_angle_deg, else lines.crease_angle_deg.
inline double tone_crease_angle_deg(const Scene& scene) {
    return scene.tone.crease_angle_deg.value_or(scene.lines.crease_angle_deg);
}

// Which kinds of line an object draws: the scene's lines.* with every matching rule applied.
std::array<bool, kLineKindCount> object_line_kinds(const Scene& scene, const std::string& object_name);

// How an object is shaded: the scene's "tone", then the keys of every matching "objects" rule's
// "tone" in their order, then those of every "styles" rule with a "tone" whose object selector
// matches, in order (docs/tone.md). `object_name` is nullopt for a mesh without objects, which
// only style rules without an object selector apply to.
struct ObjectTone {
    bool shaded = true;  // false: a holdout, or an "objects" rule says "tone": false
    ToneMode mode = ToneMode::kNone;  // kNone where the scene has no tone or the object is not shaded
    ToneCurve curve;
    ToneInk ink;
};
ObjectTone object_tone(const Scene& scene, std::optional<std::string_view> object_name);


// Reads and validates a scene file; relative paths resolve against its folder.
// Throws InputError naming the file and key.
Scene load_scene(const std::filesystem::path& scene_file, int max_image_side = kMaxImageSide);

// Parses scene JSON text; scene_file names errors and anchors relative paths.
Scene parse_scene(std::string_view json_text, const std::filesystem::path& scene_file,
                  int max_image_side = kMaxImageSide);

// A 48-frame turntable around a mesh whose object-space bounds are given.
Scene default_turntable_scene(const std::filesystem::path& mesh_file, const Bounds& bounds);

// Object motion at a frame (identity without "object").
glm::dmat4 world_from_object_at(const Scene& scene, int frame);

// Throws InputError naming the first frame of [first, last] that the explicit per-frame camera
// form has no camera for; nothing for the other forms.
void check_cameras(const Scene& scene, int first, int last);

// Camera at a frame; near/far fitted to world_bounds unless the scene gives them.
// Throws InputError when the explicit form lacks the frame.
Camera camera_at(const Scene& scene, int frame, const Bounds& world_bounds);

// Fraction of the scene's frame range elapsed at a frame: 0 at the first frame, and a full
// turn of 360 degrees returns to the start one frame after the last (seamless loops).
double motion_fraction(const Scene& scene, int frame);

}  // namespace inkline::core
