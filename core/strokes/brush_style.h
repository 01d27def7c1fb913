// SPDX-License-Identifier: MIT
// Brush style: how strokes are cleaned, split, weighted by the light and tapered (scene "brush").
// The line weight follows the light along each stroke (by default heavier where the surface turns
// from it, as a brush pressed harder on the shadow side); strokes are split where they turn sharply.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace inkline::core {

// The light that weights the brush (scene "light").
struct Light {
    bool is_point = false;
    glm::dvec3 direction{-0.4, -0.6, -0.7};  // directional: pointing from the light
    glm::dvec3 position{0.0};               // point light, world space

    bool operator==(const Light&) const = default;
};

// How an end with width is closed: a half circle, flat across, or flat half a width beyond.
enum class LineCap : uint8_t { kRound, kButt, kSquare };

// Width by depth: the weight scales from 1 at `near` to far_scale at `far`, linearly in the
// distance from the eye (world units), and stays there beyond. Without near or far, the
// camera's near or far plane (fitted to the mesh each frame unless the scene gives them).
struct DepthWidth {
    std::optional<double> near, far;
    double far_scale = 0.5;
};

// Width by screen-space curvature: the weight scales by 1 + (scale - 1) * min(1, radius_px * k),
// k the curvature of the drawn centerline (1/px): `scale` where it bends as tightly as a circle
// of radius_px or more, 1 where it runs straight.
struct CurvatureWidth {
    double radius_px = 20.0;
    double scale = 0.5;
};

// The brush's character in vector output (core/strokes/brush_texture.h): each amount in [0, 1].
struct BrushTexture {
    double dry = 0.6;        // how far the tail of a free end breaks up as the brush runs dry
    double dry_px = 40.0;    // length of that tail, px
    double streaks = 0.5;    // how often bristle streaks open along the stroke
    double pressure = 0.25;  // how much darker the ink is where the brush presses (wider)
};

// Defaults are tuned for a 1024 px image of one object: a thin line on the lit side that swells
// to about four times its weight in the shadow, with brush-like pointed free ends.
struct BrushStyle {
    double width_min_px = 0.8;           // line weight where the response is 0 (fully lit by default)
    double width_max_px = 4.8;           // line weight where the response is 1 (facing away by default)
    double gamma = 1.4;                  // response f(x) = x^gamma of x = 1 - I (or I with invert)
    bool invert = false;                 // true: lit sides are heavier (x = I)
    double taper_px = 22.0;              // length over which free (S) ends thin to a point
    // A stroke is at most this many times as wide as it is long (but may always be width_min_px
    // wide): short strokes draw as short marks, not as fat specks.
    double max_width_ratio = 0.2;
    double min_length_px = 3.0;          // shorter strokes are kept in the data but not drawn
    double smooth_px = 6.0;              // Gaussian sigma along the stroke for the centerline and the light
    double max_deviation_px = 0.5;       // drawn centerline stays this close to the exact polyline
    double turn_angle_deg = 45.0;        // a turn sharper than this splits a stroke (an A end)
    glm::dvec3 color{0.09, 0.08, 0.07};  // sRGB in [0, 1] (#rrggbb / 255); a warm ink black
    double opacity = 1.0;                // in [0, 1]
    std::filesystem::path tip;           // brush-tip image of the GL preview (PNG); empty: the built-in tip

    // Off by default: today's look.
    std::optional<DepthWidth> depth_width;
    std::optional<CurvatureWidth> curvature_width;
    // Dash pattern along u (px): on, off, on, off...; an "on" of 0 with round caps is a dot. Empty:
    // solid. Dashes are anchored to u, so they travel with the stroke from frame to frame.
    std::vector<double> dash_px;
    LineCap cap = LineCap::kRound;
    // Weight of lines drawn as constant-width centerlines (hidden lines, --centerline); unset:
    // the writers' default (1.5 px).
    std::optional<double> line_width_px;
    // The brush's dry breaks, streaks and pressure drawn as vector shapes; unset: flat ink.
    std::optional<BrushTexture> texture;
};

}  // namespace inkline::core
