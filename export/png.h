// SPDX-License-Identifier: MIT
// PNG of one frame through Cairo: antialiased, transparent unless the style has a background.
#pragma once

#include "export/drawing.h"

#include <string>

namespace inkline::output {

// The encoded PNG file contents, image size in pixels.
std::string png_image(const Drawing& drawing);

}  // namespace inkline::output
