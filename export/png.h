// SPDX-License-Identifier: MIT
// PNG of one frame drawn by Cairo: antialiased, transparent unless the style has a background.
// Also encodes RGBA pixels rendered elsewhere (the GL preview) as PNG. Encoded with libpng at a
// fast setting; the files decode to exactly the pixels Cairo's own PNG encoder wrote.
#pragma once

#include "export/drawing.h"

#include <cstdint>
#include <span>
#include <string>

namespace inkline::output {

// The largest image side Cairo draws, px.
constexpr int kMaxPngSide = 32767;

// Throws InputError when a PNG of width x height px cannot be drawn (a side over kMaxPngSide):
// check before anything is written.
void check_png_size(int width, int height);

// The encoded PNG file contents, image size in pixels. Throws std::bad_alloc when Cairo runs out
// of memory, InputError or OutputError when it fails otherwise: a PNG is whole or not made.
std::string png_image(const Drawing& drawing);

// The encoded PNG of width x height pixels given as #width*height*4 bytes: straight (not
// premultiplied) RGBA, sRGB, rows from the top.
std::string png_from_rgba(int width, int height, std::span<const uint8_t> rgba);

}  // namespace inkline::output
