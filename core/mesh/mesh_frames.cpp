// SPDX-License-Identifier: MIT
#include "core/mesh/mesh_frames.h"

#include "core/error.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/frame_pattern.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace inkline::core {

namespace {

constexpr int kNoFrame = std::numeric_limits<int>::min();

}  // namespace

MeshFrames::MeshFrames(const MeshSource& source, int first_frame, const MeshLimits& limits)
    : source_(source), limits_(limits), loaded_frame_{first_frame, kNoFrame}, reference_file_(path_of(first_frame)) {
    LoadedMesh loaded = load_mesh(reference_file_, limits_);
    mesh_[0] = std::move(loaded.mesh);
    warnings_ = std::move(loaded.warnings);
    for (std::string& name : loaded.object_names) objects_.push_back({std::move(name), -1});
    face_objects_ = std::move(loaded.face_objects);
    table_ = build_edge_table(mesh_[0]);
    for (const std::string& w : mesh_warnings(describe_mesh(mesh_[0], table_, MeshReportScope::kWarnings))) {
        warnings_.push_back(reference_file_.string() + ": " + w);
    }
}

MeshFrames::MeshFrames(Mesh mesh)
    : mesh_{std::move(mesh), Mesh{}}, loaded_frame_{0, kNoFrame}, table_(build_edge_table(mesh_[0])) {
    warnings_ = mesh_warnings(describe_mesh(mesh_[0], table_, MeshReportScope::kWarnings));
}

MeshFrames::MeshFrames(std::shared_ptr<const AnimatedMesh> animation, const std::filesystem::path& source)
    : animation_(std::move(animation)), mesh_{animation_->rest(), Mesh{}}, loaded_frame_{kNoFrame, kNoFrame},
      table_(build_edge_table(mesh_[0])) {
    source_.path = source;
    warnings_ = animation_->warnings();
    objects_ = animation_->mesh_objects();
    if (!objects_.empty()) {
        face_objects_ = animation_->face_objects();
        INKLINE_CHECK_EQ(face_objects_.size(), mesh_[0].triangles.size());
    }
    for (const std::string& w : mesh_warnings(describe_mesh(mesh_[0], table_, MeshReportScope::kWarnings))) {
        warnings_.push_back(source.string() + ": " + w);
    }
}

std::filesystem::path MeshFrames::path_of(int frame) const {
    if (!source_.is_sequence) return source_.path;
    return format_frame(source_.path.string(), frame);
}

const Mesh& MeshFrames::at(int frame) {
    if (!deforming() || frame == loaded_frame_[current_]) return mesh_[current_];
    const size_t other = 1 - current_;
    if (frame == loaded_frame_[other]) {
        current_ = other;
        return mesh_[current_];
    }
    // The other buffer takes the frame, so that the mesh returned last stays as it is.
    Mesh& mesh = mesh_[other];
    loaded_frame_[other] = kNoFrame;  // until its positions are the frame's
    if (mesh.triangles.empty()) mesh.triangles = mesh_[current_].triangles;
    if (animation_) {
        animation_->positions_at(frame, mesh.positions);
    } else {
        const std::filesystem::path file = path_of(frame);
        LoadedMesh loaded = load_mesh(file, limits_);
        const Mesh& reference = mesh_[current_];
        if (loaded.mesh.positions.size() != reference.positions.size() || loaded.mesh.triangles != reference.triangles) {
            throw InputError(file.string() + ": frame " + std::to_string(frame) +
                             " has a different topology from " + reference_file_.string() + " (" +
                             std::to_string(loaded.mesh.positions.size()) + " vertices, " +
                             std::to_string(loaded.mesh.triangles.size()) + " faces vs " +
                             std::to_string(reference.positions.size()) + ", " +
                             std::to_string(reference.triangles.size()) + ")");
        }
        mesh.positions = std::move(loaded.mesh.positions);
    }
    loaded_frame_[other] = frame;
    current_ = other;
    return mesh;
}

}  // namespace inkline::core
