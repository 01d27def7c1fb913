// SPDX-License-Identifier: MIT
// Brush style: how strokes are cleaned, split, weighted by the light and tapered (scene "brush").
// The line weight follows the light along each stroke (by default heavier where the surface turns
// from it, as a brush pressed harder on the shadow side); strokes are split where they turn sharply.
#pragma once

#include <glm/vec3.hpp>

#include <filesystem>

namespace inkline::core {

// The light that weights the brush (scene "light").
struct Light {
    bool is_point = false;
    glm::dvec3 direction{-0.4, -0.6, -0.7};  // directional: pointing from the light
    glm::dvec3 position{0.0};               // point light, world space
};

// Defaults are tuned for a 1024 px image of one object: a thin line on the lit side that swells
// to about four times its weight in the shadow, with brush-like pointed free ends.
struct BrushStyle {
    double width_min_px = 0.8;           // line weight where the response is 0 (fully lit by default)
    double width_max_px = 4.8;           // line weight where the response is 1 (facing away by default)
    double gamma = 1.4;                  // response f(x) = x^gamma of x = 1 - I (or I with invert)
    bool invert = false;                 // true: lit sides are heavier (x = I)
    double taper_px = 22.0;              // length over which free (S) ends thin to a point
    double min_length_px = 3.0;          // shorter strokes are kept in the data but not drawn
    double smooth_px = 6.0;              // Gaussian sigma along the stroke for the centerline and the light
    double max_deviation_px = 0.5;       // drawn centerline stays this close to the exact polyline
    double turn_angle_deg = 45.0;        // a turn sharper than this splits a stroke (an A end)
    glm::dvec3 color{0.09, 0.08, 0.07};  // sRGB in [0, 1] (#rrggbb / 255); a warm ink black
    double opacity = 1.0;                // in [0, 1]
    std::filesystem::path tip;           // brush-tip image of the GL preview (PNG); empty: the built-in tip
};

}  // namespace inkline::core
