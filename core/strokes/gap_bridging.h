// SPDX-License-Identifier: MIT
// Short occluded gaps bridged inside strokes, with hysteresis from the previous frame: a scanned
// mesh's zig-zag silhouette dips behind its neighbouring faces for a few pixels, and those dips
// come and go from frame to frame. Split there, a stroke would split and rejoin every frame
// (new ids, ends popping); bridged where last frame drew one stroke, it stays one.
#pragma once

#include <set>
#include <utility>
#include <vector>

#include "core/strokes/pure_strokes.h"
#include "core/strokes/stroke_coherence.h"

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
std::vector<StrokeGeometry> occluded_runs(const std::vector<Polyline>& occluded);

// What the joins took of the occluded parts: whole parts bridged as gaps, and single segments of
// the paths that joined split strokes again.
struct OccludedUse {
    std::vector<uint8_t> runs;                         // per occluded part: 1 when bridged whole
    std::set<std::pair<size_t, size_t>> segments;      // (occluded part, segment) taken by a path
};

// Joins visible strokes (r_strokes, visible == true) through occluded strokes (`occluded`,
// visible == false) whose two ends are exactly ends of visible strokes of the same kind:
// the joined stroke keeps the occluded points, marked in StrokeGeometry::hidden, so the exact
// geometry stays honest. Which gaps are bridged depends on last frame's strokes (coherence):
// where both sides continue one stroke of last frame, up to max_gap_px; where they continued two,
// up to split_gap_px; elsewhere up to new_gap_px. A gap between one stroke's own ends stays.
// Occluded strokes used as bridges are marked in r_used (sized to occluded); a stroke merged into
// another is left empty (no points) in place.
// Deterministic. Returns the number of gaps bridged.
size_t bridge_hidden_gaps(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                          const StrokeCoherence& coherence, const GapBridgeOptions& options,
                          std::vector<uint8_t>& r_used);

// Strokes that were one stroke last frame, joined again: two visible ends whose sides lie along
// the same stroke of last frame, next to each other along it (their u there differs by about the
// path between them), are joined through what lies between them: occluded parts (`occluded`,
// those not bridged whole) and visible strokes of at most max_gap_px, the shortest such
// path, at most four times max_gap_px long, between ends at most max_gap_px apart. Parts bridged
// whole (r_use.runs) are not taken again; segments taken are added to r_use.segments. This is where a
// zig-zag silhouette's junctions and visibility cuts change from frame to frame: the tangle of
// tiny pieces there would otherwise split a stroke differently each frame. Occluded segments
// taken are marked hidden; a stroke merged into another is left empty (no points) in place. Ends
// of one stroke are never joined (no loop is made). Deterministic. Returns the number of joins.
size_t rejoin_split_strokes(std::vector<StrokeGeometry>& r_strokes, const std::vector<StrokeGeometry>& occluded,
                            OccludedUse& r_use, const StrokeCoherence& coherence, const GapBridgeOptions& options);

// A stroke that ends on another stroke's side (a T-junction, typed C), where last frame's stroke
// turned from it into that other stroke: a zig-zag silhouette's fold now hides the turn, and the
// other stroke runs on past it. Every stroke with a point within 3 px of the end is a candidate,
// nearest first. The other stroke is cut at its point nearest the end; the part that last
// frame's stroke continued into is joined to the ending stroke across that short jump (marked
// hidden), and the rest, at most max_tee_rest_px long, becomes a stroke of its own. Only where
// last frame's stroke fits the new pair more closely than the two parts of the cut stroke, or
// where the rest is a stub beside the ending stroke: leading on from the junction the same way
// along last frame's stroke, and stopping sooner. Deterministic. Returns the number of joins.
size_t join_at_t_junctions(std::vector<StrokeGeometry>& r_strokes, const StrokeCoherence& coherence,
                           const GapBridgeOptions& options);

// Open strokes cut where they turn back on themselves at a coarse scale: where the chords to the
// nearest points at least scale_px before and after a point turn by more than angle_deg (the
// sharpest point of each such run). Joins see only a few pixels of each side, and a zig-zag
// tangle hides the turn at the pixel scale, so a hairpin may be joined through in one frame and
// not the next. The cut ends are corners (A). Returns the number of cuts.
size_t split_at_reversals(std::vector<StrokeGeometry>& r_strokes, double scale_px, double angle_deg);

// The occluded polylines less what the joins took (r_use): each untouched polyline as it is, the
// rest of a partly taken one as its runs of untaken segments. With hidden lines in the output,
// these are the hidden lines.
std::vector<Polyline> occluded_left(const std::vector<Polyline>& occluded, const OccludedUse& use);

}  // namespace inkline::core
