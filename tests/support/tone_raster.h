// SPDX-License-Identifier: MIT
// Measuring stippled tone independently of core/tone: the ink coverage of a frame's dots per
// pixel (the union of the discs, supersampled), the surface's N.L per pixel (an analytic sphere,
// or a mesh through a small z-buffer with interpolated vertex normals), and the two compared in
// bands of N.L against the tone asked for. The tests and bench/tone share them.
#pragma once

#include "core/mesh/mesh.h"
#include "core/scene/camera.h"
#include "core/strokes/brush_style.h"
#include "core/tone/stipple.h"
#include "core/tone/tone_options.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace inkline::test {

// Per pixel, rows from the top, in [0, 1]: the share of the pixel that the union of the dots'
// discs covers (overlapping dots count once), from samples_per_side^2 samples per pixel (at most
// 8, one bit each).
std::vector<double> dot_coverage(std::span<const core::Dot> dots, core::ImageSize image, int samples_per_side = 8);

// The surface seen through each pixel's centre (rows from the top).
struct SurfacePixels {
    core::ImageSize image;
    std::vector<uint8_t> on_surface;  // 1 where the pixel's centre sees the surface
    std::vector<double> n_dot_l;      // there: the unit normal dotted with the unit direction to the light
    std::vector<uint32_t> face;       // there: the face seen (mesh_pixels; 0 for the sphere)

    // Whether the pixel and its eight neighbours all see the surface: away from the outline, where
    // a pixel is partly surface and partly background.
    bool interior(int x, int y) const;
    size_t count() const;  // pixels on the surface
};

// A sphere (object space: centre, radius) through `projection` (its world_from_object turns the
// normals to world space), lit by `light`: ray-sphere intersection in double precision through
// every pixel's centre.
SurfacePixels sphere_pixels(const glm::dvec3& centre, double radius, const core::Projection& projection,
                            const core::Light& light);

// A mesh (object space) through `projection`, lit by `light`: a z-buffer sampled at pixel
// centres, with perspective-correct interpolation of `normals` (its vertex normals, object space).
// Every face is drawn, front- or back-facing; the nearest one wins.
SurfacePixels mesh_pixels(const core::Mesh& mesh, std::span<const glm::dvec3> normals,
                          const core::Projection& projection, const core::Light& light);

// The share of `now`'s dots whose surface sample is also among `before`'s (both ascending by
// sample, as core::Stippler gives them); 1 without dots now.
double kept_share(std::span<const core::Dot> before, std::span<const core::Dot> now);

// Ink coverage against the tone asked for in one band of N.L.
struct ToneBand {
    double lo = 0.0, hi = 0.0;  // N.L in [lo, hi)
    size_t pixels = 0;          // interior pixels in the band
    double target = 0.0;        // mean of core::tone_of(N.L) over them
    double coverage = 0.0;      // mean ink coverage over them
    // The dots' areas over the band's area: the discs (pi r^2) of the dots whose centre lies in
    // its pixels, summed, over its pixels. Coverage below it is the share lost to overlaps.
    double fill = 0.0;

    double relative_error() const { return target > 0.0 ? (coverage - target) / target : 0.0; }
};

// `bands` equal bands of N.L over [-1, 1], over the interior pixels of `surface`; `dots` give
// ToneBand::fill.
std::vector<ToneBand> tone_bands(const SurfacePixels& surface, std::span<const double> coverage,
                                 std::span<const core::Dot> dots, const core::ToneOptions& options, int bands = 10);

// The bands as a table, one line each: N.L range, pixels, target, coverage, relative error, fill.
std::string band_table(std::span<const ToneBand> bands);

}  // namespace inkline::test
