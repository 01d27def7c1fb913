// SPDX-License-Identifier: MIT
#include "tests/support/pipeline.h"

#include "core/lines/features.h"
#include "core/mesh/topology.h"
#include "core/visibility/exact_visibility.h"
#include "core/visibility/visibility.h"

#include <glm/geometric.hpp>

namespace inkline::test {

core::Camera camera_for(const View& view, const core::Mesh& mesh) {
    const core::Bounds b = core::bounds_of(mesh.positions);
    const double d = glm::length(view.eye - b.center());
    return {view.eye, view.target, {0.0, 1.0, 0.0}, view.fov_y_deg,
            std::max(0.5 * (d - b.radius()), 1e-3), 2.0 * (d + b.radius())};
}

std::vector<core::Chain> feature_chains(const core::Mesh& mesh, const View& view, const core::LineOptions& lines) {
    const core::EdgeTable table = core::build_edge_table(mesh);
    return core::chain_feature_edges(core::extract_feature_edges(mesh, table, view.eye, lines), table);
}

core::FrameLines trace(const core::Mesh& mesh, const View& view, const core::LineOptions& lines) {
    const core::EdgeTable table = core::build_edge_table(mesh);
    core::FrameLines frame;
    frame.image = {view.size, view.size};
    frame.camera = camera_for(view, mesh);
    const core::Projection projection(frame.camera, frame.image, glm::dmat4(1.0));
    const core::FeatureEdges features = core::extract_feature_edges(mesh, table, projection.eye_object(), lines);
    const std::vector<core::Chain> chains = core::chain_feature_edges(features, table);
    const core::ExactOcclusion occlusion(mesh, table);
    core::VisibilityOptions options;
    options.keep_hidden = lines.hidden;
    frame.strokes = core::split_by_visibility(chains, mesh, projection, occlusion, options);
    frame.stats.feature_edges = features.count_by_kind();
    core::tally_visible_length(frame);
    return frame;
}

}  // namespace inkline::test
