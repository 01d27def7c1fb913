// SPDX-License-Identifier: MIT
#include "core/lines/features.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace inkline::core {

const char* contour_mode_name(ContourMode mode) { return mode == ContourMode::kSmooth ? "smooth" : "mesh"; }

std::optional<ContourMode> contour_mode_from_name(std::string_view name) {
    if (name == "mesh") return ContourMode::kMesh;
    if (name == "smooth") return ContourMode::kSmooth;
    return std::nullopt;
}

const char* line_kind_name(LineKind kind) {
    switch (kind) {
        case LineKind::kSilhouette: return "silhouette";
        case LineKind::kBoundary: return "boundary";
        case LineKind::kCrease: return "crease";
        case LineKind::kIntersection: return "intersection";
    }
    return "unknown";
}

std::array<size_t, kLineKindCount> FeatureEdges::count_by_kind() const {
    std::array<size_t, kLineKindCount> counts{};
    for (const FeatureEdge& fe : edges) ++counts[size_t(fe.kind)];
    return counts;
}

double facing_value(const Mesh& mesh, uint32_t face, const Viewpoint& eye_object) {
    const glm::uvec3 t = mesh.triangles[face];
    return facing_value(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z], eye_object);
}

double facing_value(const glm::vec3& corner_a, const glm::vec3& corner_b, const glm::vec3& corner_c,
                    const Viewpoint& eye_object) {
    const glm::dvec3 a(corner_a), b(corner_b), c(corner_c);
    const glm::dvec3 centroid = (a + b + c) / 3.0;
    return glm::dot(glm::cross(b - a, c - a), eye_object.toward(centroid));
}

bool is_crease(const Mesh& mesh, uint32_t face0, uint32_t face1, double cos_crease_angle) {
    const glm::dvec3 n0 = face_normal(mesh.positions, mesh.triangles[face0]);
    const glm::dvec3 n1 = face_normal(mesh.positions, mesh.triangles[face1]);
    const double len = std::sqrt(glm::dot(n0, n0) * glm::dot(n1, n1));
    if (!(len > 0.0)) return false;
    return glm::dot(n0, n1) < cos_crease_angle * len;
}

bool classify_edge(const Mesh& mesh, const EdgeTable& table, uint32_t edge,
                   const std::vector<uint8_t>& front, const LineOptions& lines,
                   double cos_crease_angle, LineKind& r_kind) {
    if (!table.is_interior(edge)) {
        r_kind = LineKind::kBoundary;
        return lines.boundary;
    }
    const auto faces = table.faces_of(edge);
    if (lines.silhouette && front[faces[0]] != front[faces[1]]) {
        r_kind = LineKind::kSilhouette;
        return true;
    }
    if (lines.crease && is_crease(mesh, faces[0], faces[1], cos_crease_angle)) {
        r_kind = LineKind::kCrease;
        return true;
    }
    return false;
}

FeatureEdges extract_feature_edges(const Mesh& mesh, const EdgeTable& table,
                                   const Viewpoint& eye_object, const LineOptions& lines) {
    FeatureEdges out;
    std::vector<uint8_t> front(mesh.triangles.size(), 0);
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (table.face_valid[f]) front[f] = facing_value(mesh, f, eye_object) > 0.0 ? 1 : 0;
    }
    out.faces_tested = mesh.triangles.size();
    const double cos_crease = std::cos(glm::radians(lines.crease_angle_deg));
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        LineKind kind;
        if (classify_edge(mesh, table, e, front, lines, cos_crease, kind)) out.edges.push_back({e, kind});
    }
    out.edges_tested = table.edge_count();
    return out;
}

}  // namespace inkline::core
