// SPDX-License-Identifier: MIT
#include "core/mesh/mesh_frames.h"

#include "core/error.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/frame_pattern.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace inkline::core {

MeshFrames::MeshFrames(const MeshSource& source, int first_frame, const MeshLimits& limits)
    : source_(source), limits_(limits), loaded_frame_(first_frame), reference_file_(path_of(first_frame)) {
    LoadedMesh loaded = load_mesh(reference_file_, limits_);
    mesh_ = std::move(loaded.mesh);
    warnings_ = std::move(loaded.warnings);
    for (std::string& name : loaded.object_names) objects_.push_back({std::move(name), -1});
    face_objects_ = std::move(loaded.face_objects);
    table_ = build_edge_table(mesh_);
    for (const std::string& w : mesh_warnings(describe_mesh(mesh_, table_, MeshReportScope::kWarnings))) {
        warnings_.push_back(reference_file_.string() + ": " + w);
    }
}

MeshFrames::MeshFrames(Mesh mesh) : mesh_(std::move(mesh)), loaded_frame_(0), table_(build_edge_table(mesh_)) {
    warnings_ = mesh_warnings(describe_mesh(mesh_, table_, MeshReportScope::kWarnings));
}

MeshFrames::MeshFrames(std::shared_ptr<const AnimatedMesh> animation, const std::filesystem::path& source)
    : animation_(std::move(animation)), mesh_(animation_->rest()), loaded_frame_(0),
      table_(build_edge_table(mesh_)) {
    source_.path = source;
    warnings_ = animation_->warnings();
    objects_ = animation_->mesh_objects();
    if (!objects_.empty()) {
        face_objects_ = animation_->face_objects();
        INKLINE_CHECK_EQ(face_objects_.size(), mesh_.triangles.size());
    }
    for (const std::string& w : mesh_warnings(describe_mesh(mesh_, table_, MeshReportScope::kWarnings))) {
        warnings_.push_back(source.string() + ": " + w);
    }
    loaded_frame_ = std::numeric_limits<int>::min();
}

std::filesystem::path MeshFrames::path_of(int frame) const {
    if (!source_.is_sequence) return source_.path;
    return format_frame(source_.path.string(), frame);
}

const Mesh& MeshFrames::at(int frame) {
    if (animation_) {
        if (animation_->deforms() && frame != loaded_frame_) {
            animation_->positions_at(frame, mesh_.positions);
            loaded_frame_ = frame;
        }
        return mesh_;
    }
    if (!source_.is_sequence || frame == loaded_frame_) return mesh_;
    const std::filesystem::path file = path_of(frame);
    LoadedMesh loaded = load_mesh(file, limits_);
    if (loaded.mesh.positions.size() != mesh_.positions.size() ||
        loaded.mesh.triangles != mesh_.triangles) {
        throw InputError(file.string() + ": frame " + std::to_string(frame) +
                         " has a different topology from " + reference_file_.string() + " (" +
                         std::to_string(loaded.mesh.positions.size()) + " vertices, " +
                         std::to_string(loaded.mesh.triangles.size()) + " faces vs " +
                         std::to_string(mesh_.positions.size()) + ", " +
                         std::to_string(mesh_.triangles.size()) + ")");
    }
    mesh_.positions = std::move(loaded.mesh.positions);
    loaded_frame_ = frame;
    return mesh_;
}

}  // namespace inkline::core
