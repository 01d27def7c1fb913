// SPDX-License-Identifier: MIT
// Pure strokes: a frame's visible polylines split at sharp image-space turns, each end typed
// S (free), A (sharp corner), C (junction) or L (loop), then linked through junctions where the
// longest stroke continues most smoothly. A pure stroke is a piece of line without a sharp turn,
// one a hand would draw in a single movement.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "core/strokes/stroke_geometry.h"
#include "core/visibility/visibility.h"

namespace inkline::core {

// Directions are chords this long (px) on the back-tracking-free path: long enough that the
// sub-pixel wobble of visibility cuts makes no corner, short enough to keep true corners sharp.
inline constexpr double kTurnWindowPx = 3.0;
// A corner must also turn sharply at this smaller scale, so a tight smooth bend is no corner.
inline constexpr double kCornerScalePx = 1.0;
// Stroke ends this close (px) touch: they form a junction.
inline constexpr double kTouchPx = 0.5;
// An end this close (px) to another stroke's interior is a T-junction, as where a line goes
// behind an occluder: the cut lies on the occluding line to within the bisection precision.
inline constexpr double kTJunctionPx = 1.0;
// Ends this close (px) are the same mesh point and can be joined into one stroke.
inline constexpr double kJoinPx = 1e-3;

struct PureStrokeOptions {
    double turn_angle_deg = 45.0;  // sharper turns split strokes (A ends) and block links
};

struct PureStrokes {
    std::vector<StrokeGeometry> strokes;  // deterministic order: by first polyline, then position
    size_t pure_strokes = 0;              // before linking
    size_t corners = 0;                   // splits at sharp turns
    size_t links = 0;                     // pure strokes joined through junctions
};

// Splits polylines at sharp turns, types every end and links strokes through junctions.
PureStrokes build_pure_strokes(const std::vector<Polyline>& polylines, const PureStrokeOptions& options);

// Turn angle (degrees) at each exact point of a polyline, measured between the chords of
// `window_px` before and after it on the back-tracking-free path; 0 at open ends.
std::vector<double> turn_angles_deg(const std::vector<glm::dvec2>& points_px, bool closed, double window_px);

}  // namespace inkline::core
