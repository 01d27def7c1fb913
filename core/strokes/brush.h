// SPDX-License-Identifier: MIT
// Light-weighted brush: line weight from the light intensity along a stroke, a response curve,
// and end profiles by end type (pointed S ends, blunt A/C ends, none on L loops). The light at
// each point of a line sets the brush weight; a free end thins to a point, as a brush lifted off
// the paper does, while an end that meets another stroke keeps its weight.
#pragma once

#include <array>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/strokes/brush_style.h"
#include "core/strokes/stroke_geometry.h"
#include "core/strokes/stroke_path.h"

namespace inkline::core {

// vertex_normals(mesh)[v] for each v of `vertices` (ascending, distinct), bit for bit, reading
// only the faces around them: a frame's strokes touch a few thousand of a million vertices.
std::vector<glm::dvec3> vertex_normals_at(const Mesh& mesh, const EdgeTable& table, std::span<const uint32_t> vertices);

// Vertex normals kept from one frame to the next while the mesh holds still: a frame's strokes
// run through mostly the vertices of the last frame's.
class VertexNormalCache {
  public:
    // Forgets every normal: the mesh moved or changed.
    void clear();
    // vertex_normals_at(mesh, table, vertices), reusing those kept from the last call; only these
    // are kept for the next.
    std::vector<glm::dvec3> at(const Mesh& mesh, const EdgeTable& table, std::span<const uint32_t> vertices);

  private:
    std::vector<uint32_t> vertices_;  // ascending
    std::vector<glm::dvec3> normals_;
};

// The light as one frame's strokes see it: mesh normals in world space and the light direction.
class StrokeLighting {
  public:
    StrokeLighting(const Mesh& mesh, const EdgeTable& table, const glm::dmat4& world_from_object, const Light& light);
    // Normals at the vertices of `edges` only; facing() may then only be asked about those edges.
    // With a cache, normals kept from the last frame are reused (the caller clears it when the
    // mesh changes).
    StrokeLighting(const Mesh& mesh, const EdgeTable& table, const glm::dmat4& world_from_object, const Light& light,
                   std::span<const uint32_t> edges, VertexNormalCache* cache = nullptr);

    // dot(N, -l) at each point, not clamped: N interpolated from the normals of the vertices of
    // the point's edge (edges[i] for point i, the last point uses the last edge), l the light
    // direction at the point (from a point light's position, or the directional light's).
    std::vector<double> facing(std::span<const glm::dvec3> points_world, std::span<const uint32_t> edges) const;

  private:
    const Mesh& mesh_;
    const glm::dvec3& normal_of(uint32_t vertex) const;

    const EdgeTable& table_;
    bool restricted_ = false;                // normals_ at normal_vertices_ only, else at every vertex
    std::vector<uint32_t> normal_vertices_;  // ascending
    std::vector<glm::dvec3> normals_;        // object space
    glm::dmat4 object_from_world_;
    glm::dmat3 world_from_object_normal_;
    Light light_;
};

// Line weight (px) for an intensity I in [0, 1]: w_min + (w_max - w_min) * x^gamma with
// x = 1 - I, or x = I when the style is inverted.
double light_width_px(double intensity, const BrushStyle& style);

// Width factor in [0, 1] at distance d (px) from an end: an S end rises from a point to full
// width over taper_px; A and C ends stay blunt (1; the outline gives them round caps); L is 1.
double end_profile(StrokeEnd end, double d_px, double taper_px);

// Intensity and width at each sample of a drawn path.
struct BrushSamples {
    std::vector<double> intensity;  // clamp(dot(N, -l), 0, 1) smoothed along the path
    std::vector<double> width;      // px, light width times both end profiles
};

// facing: dot(N, -l) at each exact point of the stroke the path was built from; depth_scale, when
// not empty, the width-by-depth factor at each of those points (style.depth_width). The width is
// the light's, times depth_scale, times the curvature factor (style.curvature_width), times both
// end profiles, all scaled down on a short stroke (short_stroke_width_px).
BrushSamples brush_samples(const StrokePath& path, std::span<const double> facing, std::array<StrokeEnd, 2> ends,
                           const BrushStyle& style, std::span<const double> depth_scale = {});

// The widest a stroke of that drawn length may be: max_width_ratio times its length, but not
// below width_min_px. brush_samples scales a wider stroke's widths down to it.
double short_stroke_width_px(double length_px, const BrushStyle& style);

// Width-by-depth factor at a depth along the view axis (world units) between near and far.
double depth_width_scale(double depth, double near, double far, double far_scale);

// "#rrggbb" for a color with components in [0, 1].
std::string color_hex(const glm::dvec3& color);

}  // namespace inkline::core
