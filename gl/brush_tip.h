// SPDX-License-Identifier: MIT
// The brush-tip texture of the GL preview: a grayscale image used as the strokes' alpha, x along
// the stroke (its head on the left, its tail on the right) and y across it. A built-in tip made
// procedurally (soft ink edge, bristle streaks, dry-brush breaks toward the tail), or a PNG.
// Strokes drawn as textured strips, as in J. D. Northrup, L. Markosian. Artistic Silhouettes:
// A Hybrid Approach. NPAR 2000.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace inkline::gl {

// Largest accepted tip image side, texels: a typo guard; every GL 3.3 context takes 4096.
inline constexpr int kMaxBrushTipSide = 4096;

// How a tip image is laid along a stroke, in fractions of the image width. A stroke shows the
// head at a free (S) start and the tail at a free end, where the brush is set down and lifted;
// the middle repeats everywhere else, so the image keeps its proportions on long strokes and
// runs on through blunt ends that meet other strokes. Head and tail fade into the middle where
// they meet it. A loop shows the middle only.
//
//   image x:  0 ---- head ----|------------ middle ------------|---- tail ---- 1
//   stroke:   S start  [head]  [middle][middle] ... [middle]  [tail]  S end
struct BrushTip {
    int width = 0;               // texels along the stroke
    int height = 0;              // texels across the stroke
    std::vector<uint8_t> alpha;  // #width*height, row-major, row 0 on the stroke's left; 255: full ink
    double head_fraction = 0.25;
    double tail_fraction = 0.25;
    // Rows outside the stroke's outline on each side, as a fraction of the height: the quad
    // strip is widened to make room for them, so a soft edge fades out across the outline
    // instead of inside it. 0 for an image whose ink reaches its border.
    double edge_margin = 0.0;

    uint8_t at(int x, int y) const { return alpha[size_t(y) * size_t(width) + size_t(x)]; }
    // Length over height: how many stroke widths long the image is laid.
    double aspect() const { return double(width) / double(height); }
};

// The built-in tip: an even ink body with a soft edge (alpha one half on the outline), bristle
// streaks along the stroke that tile seamlessly through the middle, and dry-brush breaks that
// open up toward the tail. Deterministic.
BrushTip default_brush_tip();

// A tip from a PNG: brightness is ink (white full, black none); an image with transparency uses its alpha channel instead. Head and tail take a quarter
// of the width each, and the ink reaches the border (edge_margin 0). Throws InputError naming
// the file when it cannot be read or a side is not 2..kMaxBrushTipSide texels.
BrushTip load_brush_tip(const std::filesystem::path& png);

}  // namespace inkline::gl
