// SPDX-License-Identifier: MIT
// SVG of one frame for compositing: size and viewBox in pixels, one Inkscape layer per line kind
// (and "hidden"), one path per stroke with a stable element id (stroke-<id>), under them a
// "tone" layer of dots when the frame has tone, frame and camera in <metadata>.
#pragma once

#include "export/drawing.h"

#include <cstdint>
#include <string>

namespace inkline::output {

// How the layers are grouped (--layers; export/drawing.h).
using SvgLayers = LayerGrouping;

struct SvgOptions {
    int decimals = 2;  // coordinate precision
    SvgLayers layers = SvgLayers::kKind;
    // Set: the drawing is written on as the animation says (SMIL): each timed stroke behind a
    // mask that its drawn centerline reveals from its start, the others hidden until the end.
    // Viewers without SMIL show the finished drawing.
    const WriteOnAnimation* write_on = nullptr;
};

std::string svg_document(const Drawing& drawing, const SvgOptions& options);

}  // namespace inkline::output
