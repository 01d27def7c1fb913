// SPDX-License-Identifier: MIT
// SVG of one frame for compositing: size and viewBox in pixels, one Inkscape layer per line kind
// (and "hidden"), one path per stroke with a stable element id (stroke-<id>), frame and camera
// in <metadata>.
#pragma once

#include "export/drawing.h"

#include <string>

namespace inkline::output {

struct SvgOptions {
    int decimals = 2;                // coordinate precision
    bool layers_by_object = false;  // one layer per object with its kind layers inside (--layers object)
};

std::string svg_document(const Drawing& drawing, const SvgOptions& options);

}  // namespace inkline::output
