// SPDX-License-Identifier: MIT
// Ink coverage of PNG images, decoded by Cairo, and the overlap of two coverages: how the tests
// and the preview benchmark compare two renderings of one frame.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace inkline::test {

// Which pixels carry ink.
enum class Ink : uint8_t {
    kAlpha,        // alpha above one half
    kAlphaOrDark,  // alpha above one half where the pixel is see-through, darker than mid-grey where opaque
    kFaint,        // alpha above a fifth: lines drawn at half opacity (hidden lines) count too
};

// Per pixel, rows from the top: 1 where there is ink. Throws std::runtime_error when the PNG
// cannot be decoded.
std::vector<uint8_t> png_coverage(const std::string& png_bytes, Ink ink);
std::vector<uint8_t> png_file_coverage(const std::filesystem::path& png, Ink ink);

// The sum over all pixels of their alpha (0..1): the total ink of a PNG in memory. Throws
// std::runtime_error when it cannot be decoded.
double png_alpha_sum(const std::string& png_bytes);
// A PNG file's pixels, straight-alpha RGBA, rows from the top. Throws std::runtime_error when it
// cannot be decoded.
struct Pixels {
    int width = 0, height = 0;
    std::vector<std::array<uint8_t, 4>> rgba;
};
Pixels png_file_pixels(const std::filesystem::path& png);

// Intersection over union of two coverages of one image size (1 when neither has ink). Throws
// std::invalid_argument when the sizes differ.
double iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

}  // namespace inkline::test
