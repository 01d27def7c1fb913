// SPDX-License-Identifier: MIT
// One mesh seen from one view, drawn by core::FramePipeline as `inkline render --visibility
// exact` draws a single frame (brute-force extraction, exact visibility, gap bridging, strokes).
#pragma once

#include "core/lines/chaining.h"
#include "core/mesh/mesh.h"
#include "core/pipeline/frame_lines.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/strokes/strokes.h"

#include <glm/vec3.hpp>

#include <optional>

namespace inkline::test {

struct View {
    glm::dvec3 eye{0.0, 0.0, 4.0};
    glm::dvec3 target{0.0};
    double fov_y_deg = 35.0;
    int size = 1024;
    std::optional<double> ortho_height{};  // set: an orthographic view this high
};

// The view's camera, near and far fitted to the mesh's bounding sphere (for an orthographic
// view, the whole sphere, also behind the eye).
core::Camera camera_for(const View& view, const core::Mesh& mesh);

// A one-frame scene (frame 1) of `mesh` seen from `view` with camera_for's camera, size x size.
core::Scene scene_for(const View& view, const core::Mesh& mesh);

// Feature chains (before visibility) seen from a view.
std::vector<core::Chain> feature_chains(const core::Mesh& mesh, const View& view, const core::LineOptions& lines);

struct Drawn {
    core::FrameLines lines;
    core::FrameStrokes strokes;
};

// Frame 1 of `scene` with `mesh` as its mesh, through core::FramePipeline with exact visibility.
Drawn draw(const core::Mesh& mesh, const core::Scene& scene);

// The lines of scene_for(view, mesh) with `lines` as its line options.
core::FrameLines trace(const core::Mesh& mesh, const View& view, const core::LineOptions& lines = {});

// Frame 1 of scene_for(view, mesh) with `contour` silhouettes, under a CPU visibility mode (the
// result's `mesh` is not valid).
core::FrameResult render_frame(const core::Mesh& mesh, const View& view, core::VisibilityMode mode,
                               core::ContourMode contour);

// Summed pixel length of the visible polylines.
double visible_length(const core::FrameLines& lines);

}  // namespace inkline::test
