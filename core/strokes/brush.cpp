// SPDX-License-Identifier: MIT
#include "core/strokes/brush.h"

#include "core/error.h"
#include "core/internal/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace inkline::core {
namespace {

// Below this many vertices, the normals are summed on the calling thread.
constexpr size_t kMinParallelVertices = 4096;

}  // namespace

std::vector<glm::dvec3> vertex_normals_at(const Mesh& mesh, const EdgeTable& table, std::span<const uint32_t> vertices) {
    // Degenerate faces are missing from the edge table, but vertex_normals counts those of
    // three distinct corners (their normals are tiny, not zero): listed here to be added back.
    std::vector<std::pair<size_t, uint32_t>> degenerate;  // (index in vertices, face)
    for (const uint8_t* p = table.face_valid.data(), *end = p + table.face_valid.size();
         (p = static_cast<const uint8_t*>(std::memchr(p, 0, size_t(end - p)))) != nullptr; ++p) {
        const uint32_t f = uint32_t(p - table.face_valid.data());
        const glm::uvec3 tri = mesh.triangles[f];
        if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) continue;
        for (int c = 0; c < 3; ++c) {
            const auto it = std::lower_bound(vertices.begin(), vertices.end(), tri[c]);
            if (it != vertices.end() && *it == tri[c]) degenerate.emplace_back(size_t(it - vertices.begin()), f);
        }
    }
    std::sort(degenerate.begin(), degenerate.end());

    // The faces around each vertex, ascending, summed in that order as vertex_normals sums them.
    // Each vertex is its own: slices of them run in parallel.
    std::vector<glm::dvec3> normals(vertices.size(), glm::dvec3(0.0));
    internal::parallel_for(vertices.size(), kMinParallelVertices, [&](size_t begin, size_t end) {
        std::vector<uint32_t> faces;
        auto next_degenerate =
            std::lower_bound(degenerate.begin(), degenerate.end(), std::pair<size_t, uint32_t>(begin, 0));
        for (size_t i = begin; i < end; ++i) {
            faces.clear();
            for (uint32_t e : table.edges_around(vertices[i])) {
                for (uint32_t f : table.faces_of(e)) faces.push_back(f);
            }
            for (; next_degenerate != degenerate.end() && next_degenerate->first == i; ++next_degenerate) {
                faces.push_back(next_degenerate->second);
            }
            std::sort(faces.begin(), faces.end());
            faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
            glm::dvec3 sum(0.0);
            for (uint32_t f : faces) sum += face_normal(mesh.positions, mesh.triangles[f]);
            const double len = glm::length(sum);
            normals[i] = len > 0.0 ? sum / len : glm::dvec3(0.0);
        }
    });
    return normals;
}

void VertexNormalCache::clear() {
    vertices_.clear();
    normals_.clear();
}

std::vector<glm::dvec3> VertexNormalCache::at(const Mesh& mesh, const EdgeTable& table,
                                              std::span<const uint32_t> vertices) {
    std::vector<glm::dvec3> normals(vertices.size());
    std::vector<uint32_t> missing;
    std::vector<size_t> missing_at;
    size_t j = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
        while (j < vertices_.size() && vertices_[j] < vertices[i]) ++j;
        if (j < vertices_.size() && vertices_[j] == vertices[i]) {
            normals[i] = normals_[j];
        } else {
            missing.push_back(vertices[i]);
            missing_at.push_back(i);
        }
    }
    const std::vector<glm::dvec3> computed = vertex_normals_at(mesh, table, missing);
    for (size_t k = 0; k < missing.size(); ++k) normals[missing_at[k]] = computed[k];
    vertices_.assign(vertices.begin(), vertices.end());
    normals_ = normals;
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

StrokeLighting::StrokeLighting(const Mesh& mesh, const EdgeTable& table, const glm::dmat4& world_from_object,
                               const Light& light, std::span<const uint32_t> edges, VertexNormalCache* cache)
    : mesh_(mesh),
      table_(table),
      restricted_(true),
      object_from_world_(glm::inverse(world_from_object)),
      world_from_object_normal_(glm::transpose(glm::inverse(glm::dmat3(world_from_object)))),
      light_(light) {
    for (uint32_t e : edges) {
        normal_vertices_.push_back(table.edge_vertices[e].x);
        normal_vertices_.push_back(table.edge_vertices[e].y);
    }
    std::sort(normal_vertices_.begin(), normal_vertices_.end());
    normal_vertices_.erase(std::unique(normal_vertices_.begin(), normal_vertices_.end()), normal_vertices_.end());
    normals_ = cache ? cache->at(mesh, table, normal_vertices_) : vertex_normals_at(mesh, table, normal_vertices_);
}

const glm::dvec3& StrokeLighting::normal_of(uint32_t vertex) const {
    if (!restricted_) return normals_[vertex];
    const auto it = std::lower_bound(normal_vertices_.begin(), normal_vertices_.end(), vertex);
    INKLINE_CHECK(it != normal_vertices_.end() && *it == vertex);
    return normals_[size_t(it - normal_vertices_.begin())];
}

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
        glm::dvec3 n = world_from_object_normal_ * (normal_of(v.x) * (1.0 - t) + normal_of(v.y) * t);
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

namespace {

// Values at the exact points of a stroke, linearly interpolated at each sample of its drawn path.
std::vector<double> along_path(const StrokePath& path, std::span<const double> values) {
    std::vector<double> out(path.points_px.size(), 0.0);
    if (values.empty()) return out;
    for (size_t i = 0; i < out.size(); ++i) {
        const double g = std::clamp(path.g[i], 0.0, double(values.size() - 1));
        const size_t k = std::min(size_t(g), values.size() > 1 ? values.size() - 2 : 0);
        const double f = values.size() > 1 ? g - double(k) : 0.0;
        out[i] = values[k] + (values[std::min(k + 1, values.size() - 1)] - values[k]) * f;
    }
    return out;
}

// Curvature (1/px) of the drawn path at each sample: the turn between its neighbours over the
// distance between them, smoothed along the path as the light is.
std::vector<double> path_curvature(const StrokePath& path, double smooth_px) {
    const std::vector<glm::dvec2>& p = path.points_px;
    const size_t n = p.size();
    std::vector<double> k(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
        if (!path.closed && (i == 0 || i + 1 == n)) continue;
        const glm::dvec2 a = p[(i + n - 1) % n], b = p[i], c = p[(i + 1) % n];
        const glm::dvec2 u = b - a, v = c - b;
        const double lu = glm::length(u), lv = glm::length(v);
        if (!(lu > 0.0 && lv > 0.0)) continue;
        const double turn = std::atan2(std::abs(u.x * v.y - u.y * v.x), glm::dot(u, v));
        k[i] = turn / (0.5 * (lu + lv));
    }
    if (!path.closed && n >= 3) k.front() = k[1], k.back() = k[n - 2];
    return smooth_samples(k, path.step_px, smooth_px, path.closed);
}

}  // namespace

BrushSamples brush_samples(const StrokePath& path, std::span<const double> facing, std::array<StrokeEnd, 2> ends,
                           const BrushStyle& style, std::span<const double> depth_scale) {
    BrushSamples out;
    const size_t n = path.points_px.size();
    // Raw intensity at each sample: facing interpolated along the exact polyline.
    std::vector<double> raw = along_path(path, facing);
    for (double& x : raw) x = std::clamp(x, 0.0, 1.0);
    out.intensity = smooth_samples(raw, path.step_px, style.smooth_px, path.closed);

    out.width.resize(n);
    for (size_t i = 0; i < n; ++i) out.width[i] = light_width_px(out.intensity[i], style);
    if (!depth_scale.empty()) {
        const std::vector<double> scale = along_path(path, depth_scale);
        for (size_t i = 0; i < n; ++i) out.width[i] *= scale[i];
    }
    if (style.curvature_width) {
        const CurvatureWidth& c = *style.curvature_width;
        const std::vector<double> k = path_curvature(path, std::max(style.smooth_px, 1.0));
        for (size_t i = 0; i < n; ++i) out.width[i] *= 1.0 + (c.scale - 1.0) * std::min(1.0, c.radius_px * k[i]);
    }
    if (n == 0) return out;

    // End profiles; on a short stroke the tapers shrink to meet in the middle.
    const double length = path.length_px;
    if (!path.closed) {
        const double taper = std::min(style.taper_px, 0.5 * length);
        for (size_t i = 0; i < n; ++i) {
            const double d0 = path.arc_px[i], d1 = length - path.arc_px[i];
            out.width[i] *= end_profile(ends[0], d0, taper) * end_profile(ends[1], d1, taper);
        }
    }
    // A short stroke is a short mark: its widest point is scaled down to what its length allows.
    const double widest = *std::max_element(out.width.begin(), out.width.end());
    const double allowed = short_stroke_width_px(length, style);
    if (widest > allowed) {
        for (double& w : out.width) w *= allowed / widest;
    }
    return out;
}

double short_stroke_width_px(double length_px, const BrushStyle& style) {
    return std::max(style.width_min_px, style.max_width_ratio * length_px);
}

double depth_width_scale(double depth, double near, double far, double far_scale) {
    if (!(far > near)) return depth > near ? far_scale : 1.0;
    const double t = std::clamp((depth - near) / (far - near), 0.0, 1.0);
    return 1.0 + (far_scale - 1.0) * t;
}

std::string color_hex(const glm::dvec3& color) {
    char text[8];
    const auto byte = [](double c) { return int(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); };
    std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(color.r), byte(color.g), byte(color.b));
    return text;
}

}  // namespace inkline::core
