// SPDX-License-Identifier: MIT
// What one frame produces: its camera, light, visible feature polylines and statistics.
// The writers in export/ read this; nothing here knows about file formats.
#pragma once

#include "core/lines/features.h"
#include "core/mesh/mesh_frames.h"
#include "core/scene/camera.h"
#include "core/strokes/brush_style.h"
#include "core/visibility/visibility.h"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace inkline::core {

struct FrameStats {
    size_t faces = 0;
    size_t edges = 0;
    size_t edges_tested = 0;
    size_t faces_tested = 0;
    size_t silhouette_edges = 0;
    std::string tracker;            // "incremental" or "brute"
    std::string visibility;         // the occlusion test used: "gl", "raycast" or "exact"
    std::string visibility_reason;  // why that one (with --visibility auto)
    std::string gl_context;         // "egl: <renderer>" when a GL context was used
    // Intersection lines were traced (the mesh has objects, or lines.self_intersection); without
    // them the writers leave the kind out of the tallies.
    bool intersections = false;
    std::array<size_t, kLineKindCount> feature_edges{};         // by LineKind; intersection: segments
    std::array<double, kLineKindCount> visible_length_px{};     // by LineKind
    std::vector<std::pair<std::string, double>> ms;             // stage name -> milliseconds
};

struct FrameLines {
    int frame = 0;
    ImageSize image;
    Camera camera;
    Light light;
    // The visible feature polylines in output order (with lines.hidden the occluded ones too, as
    // visible == false); the stroke stage (core/strokes/) makes brush strokes of them.
    std::vector<Polyline> polylines;
    // Occluded parts not output (lines.hidden off): the stroke stage draws short ones across
    // where they bridge a stroke (core/strokes/bridge_gaps.h). With lines.hidden they are in
    // polylines.
    std::vector<Polyline> occluded;
    // The mesh's objects (a glTF shot's mesh instances); Polyline::object and
    // StrokeGeometry::object index them. Empty for a plain mesh.
    std::vector<MeshObject> objects;
    FrameStats stats;
};

// Moves the occluded polylines of frame.polylines into frame.occluded (kept for the stroke stage,
// not output) and numbers the visible ones again in order, as if only they had been found.
void set_aside_occluded(FrameLines& frame);

// Sums the visible length of the polylines per kind into stats.visible_length_px.
void tally_visible_length(FrameLines& frame);

}  // namespace inkline::core
