// SPDX-License-Identifier: MIT
// Feature edges of a triangle mesh seen from an eye: silhouette, boundary and crease.
// Based on: A. Hertzmann, D. Zorin. Illustrating Smooth Surfaces. SIGGRAPH 2000.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/scene/camera.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace inkline::core {

// Silhouettes, boundaries and creases run along mesh edges; intersection lines run where two
// surfaces cross (core/lines/intersections.h).
enum class LineKind : uint8_t { kSilhouette = 0, kBoundary = 1, kCrease = 2, kIntersection = 3 };
inline constexpr int kLineKindCount = 4;
inline constexpr std::array<LineKind, kLineKindCount> kAllLineKinds = {
    LineKind::kSilhouette, LineKind::kBoundary, LineKind::kCrease, LineKind::kIntersection};

// "silhouette", "boundary", "crease" or "intersection": the names used in JSON and SVG.
const char* line_kind_name(LineKind kind);

// Which feature lines a frame has (scene "lines").
// Where silhouettes run: along mesh edges between front and back faces, or along the smooth
// contour interpolated across faces (core/lines/smooth_contours.h).
enum class ContourMode : uint8_t { kMesh, kSmooth };

// "mesh" or "smooth": the names of the scene key lines.contour and of --contour.
const char* contour_mode_name(ContourMode mode);
std::optional<ContourMode> contour_mode_from_name(std::string_view name);

struct LineOptions {
    bool silhouette = true;
    ContourMode contour = ContourMode::kMesh;  // how silhouettes are found
    bool boundary = true;
    bool crease = true;
    bool intersection = true;        // where the surfaces of two objects cross
    bool self_intersection = false;  // also where one object's surface crosses itself
    double crease_angle_deg = 60.0;  // dihedral: angle between the two face normals
    bool hidden = false;             // keep occluded parts as visible:false strokes
};

struct FeatureEdge {
    uint32_t edge;
    LineKind kind;
};

struct FeatureEdges {
    std::vector<FeatureEdge> edges;  // ascending edge index, each edge once
    size_t edges_tested = 0;         // edges whose classification was computed this frame
    size_t faces_tested = 0;         // faces whose facing was evaluated this frame

    std::array<size_t, kLineKindCount> count_by_kind() const;
};

// Signed facing of a face: dot(n, eye_object.toward(centroid)), n from counter-clockwise order.
// Front-facing when > 0. Every extractor uses this one function so their results agree exactly.
double facing_value(const Mesh& mesh, uint32_t face, const Viewpoint& eye_object);
// The same for the triangle of corners a, b, c (the face's positions, in order).
double facing_value(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Viewpoint& eye_object);

// True when the dihedral angle between the two faces' normals exceeds the crease angle.
bool is_crease(const Mesh& mesh, uint32_t face0, uint32_t face1, double cos_crease_angle);

// Classifies one edge (priority boundary > silhouette > crease). `front` holds each face's
// facing; only the edge's own faces are read. Returns false when the edge is no feature.
bool classify_edge(const Mesh& mesh, const EdgeTable& table, uint32_t edge,
                   const std::vector<uint8_t>& front, const LineOptions& lines,
                   double cos_crease_angle, LineKind& r_kind);

// Reference extraction: tests every edge and every face (`--tracker brute`).
FeatureEdges extract_feature_edges(const Mesh& mesh, const EdgeTable& table,
                                   const Viewpoint& eye_object, const LineOptions& lines);

}  // namespace inkline::core
