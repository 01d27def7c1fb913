// SPDX-License-Identifier: MIT
// Short occluded gaps bridged inside strokes, with hysteresis from the previous frame: where last
// frame drew one stroke across a dip of the silhouette behind its neighbouring faces, this frame
// does too; where it drew two, the gap stays unless it almost closes (occluded_gaps.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/strokes/occluded_gaps.h"
#include "core/strokes/stroke_coherence.h"
#include "core/strokes/stroke_geometry.h"

namespace inkline::core {

// Joins visible strokes (r_strokes, visible == true) through occluded strokes (`occluded`,
// visible == false) whose two ends are exactly ends of visible strokes of the same kind:
// the joined stroke keeps the occluded points, marked in StrokeGeometry::bridged, so the exact
// geometry stays honest. Which gaps are bridged depends on last frame's strokes (coherence):
// where both sides continue one stroke of last frame, up to max_gap_px; where they continued two,
// up to split_gap_px; elsewhere up to new_gap_px. A gap between one stroke's own ends stays.
// Occluded strokes used as bridges are marked in r_bridged_whole (sized to occluded); a stroke
// merged into another is left empty (no points) in place.
// Deterministic. Returns the number of gaps bridged.
size_t bridge_hidden_gaps(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                          const StrokeCoherence& coherence, const GapBridgeOptions& options,
                          std::vector<uint8_t>& r_bridged_whole);

}  // namespace inkline::core
