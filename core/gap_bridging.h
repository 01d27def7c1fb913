// SPDX-License-Identifier: MIT
// Short occluded gaps bridged inside strokes, with hysteresis from the previous frame: a scanned
// mesh's zig-zag silhouette dips behind its neighbouring faces for a few pixels, and those dips
// come and go from frame to frame. Split there, a stroke would split and rejoin every frame
// (new ids, ends popping); bridged where last frame drew one stroke, it stays one.
#pragma once

#include <vector>

#include "core/pure_strokes.h"
#include "core/stroke_coherence.h"

namespace inkline::core {

struct GapBridgeOptions {
    // A gap is bridged only when its ends are at most this far apart in the image (px) and the
    // occluded part runs at most twice as far along the mesh (a short dip, not a detour).
    double max_gap_px = 9.6;
    // With no memory of the place (last frame had no visible stroke on either side), gaps up to
    // this (px) are bridged.
    double new_gap_px = 4.8;
    // Last frame split here (two strokes met at the gap): the gap stays unless it closes to this
    // (px), well below max_gap_px, so the split does not flicker either.
    double split_gap_px = 2.4;
};

// Default bounds from the brush: the gap at most twice the widest line weight.
GapBridgeOptions gap_bridge_options(double width_max_px);

// Joins visible strokes (r_strokes, visible == true) through occluded strokes (`occluded`,
// visible == false) whose two ends are exactly ends of visible strokes of the same kind:
// the joined stroke keeps the occluded points, marked in StrokeGeometry::hidden, so the exact
// geometry stays honest. Which gaps are bridged depends on last frame's strokes (coherence):
// where both sides continue one stroke of last frame, up to max_gap_px; where they continued two,
// up to split_gap_px; elsewhere up to new_gap_px. A gap between one stroke's own ends stays. Occluded strokes used as bridges are marked in
// r_used (sized to occluded); a stroke merged into another is left empty (no points) in place.
// Deterministic. Returns the number of gaps bridged.
size_t bridge_hidden_gaps(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                          const StrokeCoherence& coherence, const GapBridgeOptions& options,
                          std::vector<uint8_t>& r_used);

}  // namespace inkline::core
