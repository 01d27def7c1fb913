// SPDX-License-Identifier: MIT
// What the stroke repairs share: the occluded parts of a frame's lines, the bounds on the gaps
// they draw across, and what they took of the occluded parts. A scanned mesh's zig-zag
// silhouette dips behind its neighbouring faces for a few pixels, and those dips come and go
// from frame to frame: split there, a stroke would split and rejoin every frame (new ids, ends
// popping). The repairs, in the order build_strokes runs them:
//   bridge_gaps.h     short occluded gaps drawn across, with hysteresis from the previous frame
//   rejoin_strokes.h  strokes that were one last frame joined again through a tangle or a fold
//   t_junctions.h     a stroke ending on another's side joined to the part it turned into
//   reversals.h       strokes cut where they turn back on themselves (hairpins)
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "core/strokes/stroke_geometry.h"
#include "core/visibility/visibility.h"

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
    // Strokes split where a zig-zag silhouette folds back along itself are joined again straight
    // across the fold when their ends are at most this far apart (px).
    double max_fold_px = 28.8;
    // At a T-junction, the part cut off the crossing stroke is at most this long (px).
    double max_tee_rest_px = 24.0;
};

// Default bounds from the brush: the gap at most twice the widest line weight, a fold three
// times that, the part cut off at a T-junction two and a half times.
GapBridgeOptions gap_bridge_options(double width_max_px);

// The occluded polylines as they are, one geometry each (not split at corners: a gap that folds
// back on itself, as a zig-zag silhouette's hidden fold does, is still one gap).
std::vector<StrokeGeometry> occluded_parts(const std::vector<Polyline>& occluded);

// What the joins took of the occluded parts: whole parts bridged as gaps, and single segments of
// the paths that joined split strokes again.
struct OccludedUse {
    std::vector<uint8_t> bridged_whole;                  // per occluded part: 1 when bridged whole
    std::set<std::pair<size_t, size_t>> segments_taken;  // (occluded part, segment) taken by a path
};

// The occluded polylines less what the joins took (use): each untouched polyline as it is, the
// rest of a partly taken one as its runs of untaken segments. With hidden lines in the output,
// these are the hidden lines.
std::vector<Polyline> occluded_left(const std::vector<Polyline>& occluded, const OccludedUse& use);

}  // namespace inkline::core
