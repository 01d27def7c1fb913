// SPDX-License-Identifier: MIT
#include "core/brush.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace inkline::core {

std::vector<glm::dvec3> vertex_normals(const Mesh& mesh) {
    std::vector<glm::dvec3> normals(mesh.positions.size(), glm::dvec3(0.0));
    // The unnormalised face normal is twice the area times the unit normal: area weighting.
    for (const glm::uvec3& tri : mesh.triangles) {
        if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) continue;
        const glm::dvec3 n = face_normal(mesh.positions, tri);
        for (int c = 0; c < 3; ++c) normals[tri[c]] += n;
    }
    for (glm::dvec3& n : normals) {
        const double len = glm::length(n);
        n = len > 0.0 ? n / len : glm::dvec3(0.0);
    }
    return normals;
}

StrokeLighting::StrokeLighting(const Mesh& mesh, const EdgeTable& table, const glm::dmat4& world_from_object,
                               const Light& light)
    : mesh_(mesh),
      table_(table),
      normals_(vertex_normals(mesh)),
      object_from_world_(glm::inverse(world_from_object)),
      world_from_object_normal_(glm::transpose(glm::inverse(glm::dmat3(world_from_object)))),
      light_(light) {}

std::vector<double> StrokeLighting::facing(std::span<const glm::dvec3> points_world,
                                           std::span<const uint32_t> edges) const {
    std::vector<double> out(points_world.size(), 0.0);
    if (edges.empty()) return out;
    for (size_t i = 0; i < points_world.size(); ++i) {
        const uint32_t edge = edges[std::min(i, edges.size() - 1)];
        const glm::uvec2 v = table_.edge_vertices[edge];
        const glm::dvec3 a(mesh_.positions[v.x]), b(mesh_.positions[v.y]);
        // Where the point lies on its edge, from its object-space position.
        const glm::dvec3 p = glm::dvec3(object_from_world_ * glm::dvec4(points_world[i], 1.0));
        const glm::dvec3 ab = b - a;
        const double len2 = glm::dot(ab, ab);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
        glm::dvec3 n = world_from_object_normal_ * (normals_[v.x] * (1.0 - t) + normals_[v.y] * t);
        const double n_len = glm::length(n);
        if (!(n_len > 0.0)) continue;
        n /= n_len;
        glm::dvec3 to_light = -light_.direction;
        if (light_.is_point) to_light = light_.position - points_world[i];
        const double l_len = glm::length(to_light);
        if (!(l_len > 0.0)) continue;
        out[i] = glm::dot(n, to_light / l_len);
    }
    return out;
}

double light_width_px(double intensity, const BrushStyle& style) {
    const double i = std::clamp(intensity, 0.0, 1.0);
    const double x = style.invert ? i : 1.0 - i;
    return style.width_min_px + (style.width_max_px - style.width_min_px) * std::pow(x, style.gamma);
}

double end_profile(StrokeEnd end, double d_px, double taper_px) {
    if (end != StrokeEnd::kFree) return 1.0;  // blunt: the outline closes it with a round cap
    const double d = std::max(d_px, 0.0);
    if (!(taper_px > 0.0) || d >= taper_px) return 1.0;
    // Ease-out: the tip widens quickly, like a brush set down, then levels off.
    const double x = d / taper_px;
    return x * (2.0 - x);
}

BrushSamples brush_samples(const StrokePath& path, std::span<const double> facing, std::array<StrokeEnd, 2> ends,
                           const BrushStyle& style) {
    BrushSamples out;
    const size_t n = path.points_px.size();
    // Raw intensity at each sample: facing interpolated along the exact polyline.
    std::vector<double> raw(n, 0.0);
    for (size_t i = 0; i < n && !facing.empty(); ++i) {
        const double g = std::clamp(path.g[i], 0.0, double(facing.size() - 1));
        const size_t k = std::min(size_t(g), facing.size() > 1 ? facing.size() - 2 : 0);
        const double f = facing.size() > 1 ? g - double(k) : 0.0;
        const double value = facing[k] + (facing[std::min(k + 1, facing.size() - 1)] - facing[k]) * f;
        raw[i] = std::clamp(value, 0.0, 1.0);
    }
    out.intensity = smooth_samples(raw, path.step_px, style.smooth_px, path.closed);

    out.width.resize(n);
    for (size_t i = 0; i < n; ++i) out.width[i] = light_width_px(out.intensity[i], style);
    if (path.closed || n == 0) return out;

    // End profiles; on a short stroke the tapers shrink to meet in the middle.
    const double length = path.length_px;
    const double taper = std::min(style.taper_px, 0.5 * length);
    for (size_t i = 0; i < n; ++i) {
        const double d0 = path.arc_px[i], d1 = length - path.arc_px[i];
        out.width[i] *= end_profile(ends[0], d0, taper) * end_profile(ends[1], d1, taper);
    }
    return out;
}

std::string color_hex(const glm::dvec3& color) {
    char text[8];
    const auto byte = [](double c) { return int(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); };
    std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(color.r), byte(color.g), byte(color.b));
    return text;
}

}  // namespace inkline::core
