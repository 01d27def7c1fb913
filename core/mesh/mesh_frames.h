// SPDX-License-Identifier: MIT
// The mesh of every frame: one file for all frames, or one file per frame of a sequence with
// the same topology. The edge table is built once from the first frame loaded.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"

#include <array>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace inkline::core {

// Where the meshes come from (scene "mesh").
struct MeshSource {
    std::filesystem::path path;  // a file, or a pattern with a frame field for a sequence
    bool is_sequence = false;
};

// A named part of a mesh: an object of a glTF shot, or an "o" (or "g") group of an OBJ file.
struct MeshObject {
    std::string name;
    int node = -1;  // the glTF node it instances; -1 when it has none
};

// A mesh whose vertices move from frame to frame over one topology, evaluated in memory (an
// animated glTF shot: core/scene/gltf_shot.h).
class AnimatedMesh {
  public:
    virtual ~AnimatedMesh() = default;
    // Topology, and the positions of a frame that positions_at() has not been asked for.
    virtual const Mesh& rest() const = 0;
    // Whether positions_at() ever differs from rest().positions.
    virtual bool deforms() const = 0;
    // The positions at a frame, rest().positions.size() of them. Throws InputError for a frame
    // that cannot be evaluated.
    virtual void positions_at(int frame, std::vector<glm::vec3>& r_positions) const = 0;
    // Drawable oddities found while loading, one line each.
    virtual std::vector<std::string> warnings() const { return {}; }
    // Its objects, and the object of every face of rest(); none when it is one unnamed whole.
    virtual std::vector<MeshObject> mesh_objects() const { return {}; }
    virtual std::vector<uint32_t> face_objects() const { return {}; }
};

class MeshFrames {
  public:
    // Loads the mesh of `first_frame` (the only one for a single file). Throws InputError, also
    // for a mesh over `limits` (checked while reading, for every frame's file).
    MeshFrames(const MeshSource& source, int first_frame, const MeshLimits& limits = {});
    // A mesh already in memory, the same at every frame (a generated shape); path_of() is empty.
    explicit MeshFrames(Mesh mesh);
    // An animated mesh; at(frame) evaluates it. `source` names it in messages (path_of()).
    MeshFrames(std::shared_ptr<const AnimatedMesh> animation, const std::filesystem::path& source);

    // The mesh at a frame; for a sequence this reads the frame's file and checks that its
    // topology matches, throwing InputError naming the file when it does not. A deforming mesh
    // is kept twice over: the mesh returned stays as it is until at() has returned the meshes of
    // two other frames, so one frame's mesh can be drawn while the next one's is loaded.
    const Mesh& at(int frame);

    const EdgeTable& edges() const { return table_; }
    bool is_sequence() const { return source_.is_sequence; }
    // Whether positions change from frame to frame (a sequence, or an animation that deforms).
    bool deforming() const { return source_.is_sequence || (animation_ && animation_->deforms()); }
    // Warnings gathered while loading (skipped faces, degenerate faces, non-manifold edges).
    const std::vector<std::string>& warnings() const { return warnings_; }
    // The mesh's objects (empty for a plain mesh file) and the object of a face.
    const std::vector<MeshObject>& objects() const { return objects_; }
    uint32_t object_of_face(uint32_t face) const { return face_objects_[face]; }
    // The object of every face; empty without objects.
    std::span<const uint32_t> face_objects() const { return face_objects_; }
    std::filesystem::path path_of(int frame) const;

  private:
    MeshSource source_;
    std::shared_ptr<const AnimatedMesh> animation_;
    MeshLimits limits_;
    // The frames' meshes: [current_] the last one returned; the other, of a deforming mesh, the
    // one before it (empty until a second frame is loaded).
    std::array<Mesh, 2> mesh_;
    std::array<int, 2> loaded_frame_;
    size_t current_ = 0;
    std::filesystem::path reference_file_;
    EdgeTable table_;
    std::vector<std::string> warnings_;
    std::vector<MeshObject> objects_;
    std::vector<uint32_t> face_objects_;  // per face, when there are objects
};

}  // namespace inkline::core
