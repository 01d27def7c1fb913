// SPDX-License-Identifier: MIT
// PNG of one frame through Cairo: antialiased, transparent unless the style has a background.
// Also encodes RGBA pixels rendered elsewhere (the GL preview) as PNG.
#pragma once

#include "export/drawing.h"

#include <cstdint>
#include <span>
#include <string>

namespace inkline::output {

// The encoded PNG file contents, image size in pixels.
std::string png_image(const Drawing& drawing);

// The encoded PNG of width x height pixels given as #width*height*4 bytes: straight (not
// premultiplied) RGBA, sRGB, rows from the top.
std::string png_from_rgba(int width, int height, std::span<const uint8_t> rgba);

}  // namespace inkline::output
