// SPDX-License-Identifier: MIT
// Strokes cut where they turn back on themselves at a coarse scale (hairpins), so that a hairpin
// is cut at its tip every frame, whether or not a join ran through it.
#pragma once

#include <cstddef>
#include <vector>

#include "core/strokes/stroke_geometry.h"

namespace inkline::core {

// Open strokes cut where they turn back on themselves at a coarse scale: where the chords to the
// nearest points at least scale_px before and after a point turn by more than angle_deg (the
// sharpest point of each such run). Joins see only a few pixels of each side, and a zig-zag
// tangle hides the turn at the pixel scale, so a hairpin may be joined through in one frame and
// not the next. The cut ends are corners (A); the parts after the first are added at the end.
// Returns the number of cuts.
size_t split_at_reversals(std::vector<StrokeGeometry>& r_strokes, double scale_px, double angle_deg);

}  // namespace inkline::core
