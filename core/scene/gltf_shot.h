// SPDX-License-Identifier: MIT
// A glTF 2.0 shot (.gltf with external or embedded buffers, or .glb): every mesh instance of a
// scene, placed through the node hierarchy, as one world-space mesh per frame, and its cameras.
// The file is read by tinygltf; the evaluation is inkline's own and follows the glTF 2.0
// specification: node TRS or matrix, animation channels (STEP, LINEAR with quaternion slerp,
// CUBICSPLINE), morph targets with default and animated weights, skins with any number of
// JOINTS_n/WEIGHTS_n sets. docs/gltf.md describes what is read and how.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/mesh_frames.h"
#include "core/scene/camera.h"

#include <cstddef>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkline::core {

struct CameraPose;
struct Scene;

struct GltfOptions {
    int scene = -1;         // index into the file's scenes; -1: its default scene (else the first)
    std::string animation;  // an animation's name or index; empty: every animation together
    std::string camera;     // a camera's name, its node's name, or its index in the file's cameras; empty: the scene's
                            // first camera
    double fps = 24.0;      // frame F is animation time F / fps
    size_t max_faces = std::numeric_limits<size_t>::max();
};

// One mesh instance of the scene: a node with a mesh.
struct GltfObject {
    std::string name;  // the node's name, or "node N" when it has none
    int node = 0;
    uint32_t first_face = 0;  // its faces in the shot's mesh: [first_face, first_face + faces)
    uint32_t faces = 0;
};

// A camera as glTF gives it, placed by its node at one time.
struct GltfCameraView {
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0};  // the node's -Z
    glm::dvec3 up{0.0, 1.0, 0.0};        // the node's +Y
};

struct GltfCamera {
    std::string name;  // the camera's name, else its node's, else "cameras[i]"
    int node = 0;
    size_t index = 0;  // in the file's cameras
    bool orthographic = false;
    double yfov = 0.0;    // radians (perspective)
    double aspect = 0.0;  // width / height; 0 when the file gives none
    double xmag = 0.0, ymag = 0.0;  // half extents (orthographic)
    double znear = 0.0;
    std::optional<double> zfar;  // none: infinite (perspective)
};

class GltfShot final : public AnimatedMesh {
  public:
    // Reads and checks the file. Throws InputError naming the file and the glTF element
    // ("meshes[2].primitives[0]: ...") for anything that cannot be drawn.
    GltfShot(const std::filesystem::path& path, const GltfOptions& options = {});
    ~GltfShot() override;

    const Mesh& rest() const override;
    bool deforms() const override;
    void positions_at(int frame, std::vector<glm::vec3>& r_positions) const override;
    std::vector<std::string> warnings() const override;
    std::vector<MeshObject> mesh_objects() const override;
    std::vector<uint32_t> face_objects() const override;

    // World-space positions at an animation time, seconds.
    void positions_at_time(double seconds, std::vector<glm::vec3>& r_positions) const;
    // The frames the chosen animations span at options.fps (first and last key times rounded
    // to frames); none for a file without animation.
    std::optional<std::pair<int, int>> frame_range() const;
    double fps() const;
    std::string file() const;  // the path it was read from, for messages

    const std::vector<GltfObject>& objects() const;
    // The chosen camera; none when the scene has none.
    const std::optional<GltfCamera>& camera() const;
    // The file's animations by name ("animations[i]" for one without), in file order.
    std::vector<std::string> animations() const;
    // Every camera of the scene, in scene order: name, node, index and kind (the others' lenses
    // unread).
    const std::vector<GltfCamera>& cameras() const;
    GltfCameraView camera_view_at(int frame) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Whether a path names a glTF file (.gltf or .glb, any case).
bool is_gltf_path(const std::filesystem::path& path);

// The camera a glTF file gives a scene for every frame in [first, last], unless the scene gives
// one (`given.camera`), and the image size from the camera's aspect ratio unless `image_given`.
// A file without a camera gets a bare mesh's turntable view (docs/cli.md), still when the shot
// is animated and then framed on the geometry over [first, last]. An image size
// that differs from the camera's aspect keeps the view as Blender's automatic sensor fit does:
// the camera's field of view along its longer side becomes the field along the image's longer
// side. An orthographic camera stays orthographic (Camera::ortho_height), its xmag and ymag
// refitted the same way.
void apply_gltf_camera(const GltfShot& shot, Scene& r_scene, int first, int last, bool image_given);

}  // namespace inkline::core
