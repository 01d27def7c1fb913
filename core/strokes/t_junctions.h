// SPDX-License-Identifier: MIT
// A stroke that ends on another stroke's side joined to the part of it that last frame's stroke
// turned into, where a zig-zag silhouette's fold now hides the turn.
#pragma once

#include <cstddef>
#include <vector>

#include "core/strokes/occluded_gaps.h"
#include "core/strokes/stroke_coherence.h"
#include "core/strokes/stroke_geometry.h"

namespace inkline::core {

// A stroke that ends on another stroke's side (a T-junction, typed C), where last frame's stroke
// turned from it into that other stroke: a zig-zag silhouette's fold now hides the turn, and the
// other stroke runs on past it. Every stroke with a point within 3 px of the end is a candidate,
// nearest first. The other stroke is cut at its point nearest the end; the part that last
// frame's stroke continued into is joined to the ending stroke across that short jump (marked
// bridged), and the rest, at most max_tee_rest_px long, becomes a stroke of its own. Only where
// last frame's stroke fits the new pair more closely than the two parts of the cut stroke, or
// where the rest is a stub beside the ending stroke: leading on from the junction the same way
// along last frame's stroke, and stopping sooner. A stroke joined away is left empty (no
// points) in place; the rest is added at the end. Deterministic. Returns the number of joins.
size_t join_at_t_junctions(std::vector<StrokeGeometry>& r_strokes, const StrokeCoherence& coherence,
                           const GapBridgeOptions& options);

}  // namespace inkline::core
