// SPDX-License-Identifier: MIT
// Strokes that were one stroke last frame joined again where a zig-zag silhouette's tangle of
// tiny visible and occluded pieces, or a fold back along itself, split them this frame.
#pragma once

#include <cstddef>
#include <vector>

#include "core/strokes/occluded_gaps.h"
#include "core/strokes/stroke_coherence.h"
#include "core/strokes/stroke_geometry.h"

namespace inkline::core {

// Strokes that were one stroke last frame, joined again: two visible ends whose sides lie along
// the same stroke of last frame, next to each other along it (their u there differs by about the
// path between them), are joined through what lies between them: occluded parts (`occluded`,
// those not bridged whole) and visible strokes of at most max_gap_px, the shortest such path, at
// most four times max_gap_px long, between ends at most max_gap_px apart. Parts bridged whole
// (r_use.bridged_whole) are not taken again; segments taken are added to r_use.segments_taken.
// This is where a zig-zag silhouette's junctions and visibility cuts change from frame to frame:
// the tangle of tiny pieces there would otherwise split a stroke differently each frame. Ends
// whose sides run back over each other (a fold), at most max_fold_px apart, are joined straight
// across by one segment, after every join by a path. Occluded segments taken, and the segment
// across a fold, are marked bridged; a stroke merged into another is left empty (no points) in
// place. Ends of one stroke are never joined (no loop is made). Deterministic. Returns the
// number of joins.
size_t rejoin_split_strokes(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                            OccludedUse& r_use, const StrokeCoherence& coherence, const GapBridgeOptions& options);

}  // namespace inkline::core
