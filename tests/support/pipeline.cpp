// SPDX-License-Identifier: MIT
#include "tests/support/pipeline.h"

#include "core/lines/features.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/visibility/occlusion_source.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace inkline::test {

core::Camera camera_for(const View& view, const core::Mesh& mesh) {
    const core::Bounds b = core::bounds_of(mesh.positions);
    const double d = glm::length(view.eye - b.center());
    if (view.ortho_height) {
        return {view.eye, view.target, {0.0, 1.0, 0.0}, view.fov_y_deg, d - 2.0 * b.radius(), d + 2.0 * b.radius(),
                view.ortho_height};
    }
    return {view.eye, view.target, {0.0, 1.0, 0.0}, view.fov_y_deg,
            std::max(0.5 * (d - b.radius()), 1e-3), 2.0 * (d + b.radius())};
}

core::Scene scene_for(const View& view, const core::Mesh& mesh) {
    const core::Camera camera = camera_for(view, mesh);
    core::Scene scene;
    scene.image = {view.size, view.size};
    scene.camera.pose = {camera.eye, camera.target, camera.up, camera.fov_y_deg, camera.ortho_height};
    scene.camera.near = camera.near;
    scene.camera.far = camera.far;
    return scene;
}

std::vector<core::Chain> feature_chains(const core::Mesh& mesh, const View& view, const core::LineOptions& lines) {
    const core::EdgeTable table = core::build_edge_table(mesh);
    const core::Viewpoint eye = core::viewpoint_of(camera_for(view, mesh));
    return core::chain_feature_edges(core::extract_feature_edges(mesh, table, eye, lines), table);
}

Drawn draw(const core::Mesh& mesh, const core::Scene& scene) {
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    core::FrameResult result = pipeline.run(scene.first_frame);
    return {std::move(result.lines), std::move(result.strokes)};
}

core::FrameLines trace(const core::Mesh& mesh, const View& view, const core::LineOptions& lines) {
    core::Scene scene = scene_for(view, mesh);
    scene.lines = lines;
    return draw(mesh, scene).lines;
}

core::FrameResult render_frame(const core::Mesh& mesh, const View& view, core::VisibilityMode mode,
                               core::ContourMode contour) {
    core::Scene scene = scene_for(view, mesh);
    scene.lines.contour = contour;
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(mode));
    return pipeline.run(scene.first_frame);
}

double visible_length(const core::FrameLines& lines) {
    double sum = 0.0;
    for (const core::Polyline& line : lines.polylines) sum += line.visible ? line.length_px() : 0.0;
    return sum;
}

}  // namespace inkline::test
