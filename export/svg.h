// SPDX-License-Identifier: MIT
// SVG of one frame: size and viewBox in pixels, one Inkscape layer per line kind, one path per
// stroke with a stable element id (stroke-<id>).
#pragma once

#include "core/frame_lines.h"

#include <string>

namespace inkline::output {

struct SvgOptions {
    double stroke_width_px = 1.5;  // centerline width
    int decimals = 2;              // coordinate precision
    std::string color = "#000000";
};

// Constant-width centerline paths (also what pen plotters want). Hidden strokes, when present,
// go dashed into their own "hidden" layer.
std::string centerline_svg(const core::FrameLines& frame, const SvgOptions& options);

}  // namespace inkline::output
