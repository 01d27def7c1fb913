// SPDX-License-Identifier: MIT
// inkline_consumer SCENE FRAME OUT: one frame of a scene through the installed inkline library,
// with ray-cast visibility, written as polylines JSON; the same bytes as
// `inkline render SCENE --frames FRAME:FRAME --json OUT --visibility raycast` (stats.ms aside).
#include <inkline/core/error.h>
#include <inkline/core/lines/chaining.h>
#include <inkline/core/lines/features.h>
#include <inkline/core/mesh/mesh_frames.h>
#include <inkline/core/pipeline/frame_lines.h>
#include <inkline/core/scene/scene.h>
#include <inkline/core/strokes/strokes.h>
#include <inkline/core/version.h>
#include <inkline/core/visibility/raycast_visibility.h>
#include <inkline/core/visibility/visibility.h>
#include <inkline/export/json.h>

#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

namespace core = inkline::core;

namespace {

// One frame drawn as the inkline program draws a run of one frame (cli/render.cpp).
std::string frame_json(const core::Scene& scene, core::MeshFrames& meshes, int frame) {
    core::FrameLines lines;
    lines.frame = frame;
    lines.image = scene.image;
    lines.light = scene.light;
    const core::Mesh& mesh = meshes.at(frame);
    const core::EdgeTable& table = meshes.edges();

    const glm::dmat4 world_from_object = core::world_from_object_at(scene, frame);
    const core::Bounds object_bounds = core::bounds_of(mesh.positions);
    lines.camera = core::camera_at(scene, frame, core::transformed(object_bounds, world_from_object));
    const core::Projection projection(lines.camera, scene.image, world_from_object);

    const core::FeatureEdges features =
        core::extract_feature_edges(mesh, table, projection.eye_object(), scene.lines);
    const std::vector<core::Chain> chains = core::chain_feature_edges(features, table);
    const core::RaycastOcclusion occlusion(mesh, table);
    lines.strokes = core::split_by_visibility(chains, mesh, projection, occlusion, {.keep_hidden = true});
    if (!scene.lines.hidden) core::set_aside_occluded(lines);
    core::StrokeCoherence coherence;
    const core::FrameStrokes strokes = core::build_strokes(lines, mesh, table, projection, scene.brush, coherence);

    core::FrameStats& stats = lines.stats;
    stats.faces = mesh.triangles.size();
    stats.edges = table.edge_count();
    stats.edges_tested = features.edges_tested;
    stats.faces_tested = features.faces_tested;
    stats.feature_edges = features.count_by_kind();
    stats.silhouette_edges = stats.feature_edges[size_t(core::LineKind::kSilhouette)];
    stats.tracker = "brute";
    stats.visibility = "raycast";
    stats.visibility_reason = "asked for";
    core::tally_visible_length(lines);
    return inkline::output::polylines_json(lines, &strokes);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: inkline_consumer SCENE FRAME OUT (inkline %s)\n",
                     std::string(inkline::kVersion).c_str());
        return 2;
    }
    try {
        const core::Scene scene = core::load_scene(argv[1]);
        const int frame = std::stoi(argv[2]);
        core::MeshFrames meshes(scene.mesh, frame);
        std::ofstream out(argv[3], std::ios::binary);
        out << frame_json(scene, meshes, frame);
        if (!out.flush()) {
            std::fprintf(stderr, "inkline_consumer: %s: cannot write\n", argv[3]);
            return 3;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_consumer: %s\n", e.what());
        return 2;
    }
    return 0;
}
