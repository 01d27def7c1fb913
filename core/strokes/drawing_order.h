// SPDX-License-Identifier: MIT
// The order a person would draw a frame's strokes in (seed 002's grouping and hierarchical
// linking): strokes connected through junctions (points they share) form a group; each group
// has a main stroke (level 0), its level-1 strokes touch the main stroke, level-2 strokes touch
// a level-1 stroke, and so on; a frame is drawn group after group, each level after the one
// before. The groups, levels and order stay as they were last frame where the strokes persist;
// two groups of last frame that come to touch join only once the touch has held a few frames.
#pragma once

#include "core/strokes/strokes.h"

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace inkline::core {

struct DrawingOrderOptions {
    // Two strokes touch where an end of one is a point of the other (an end or a corner of its
    // exact polyline) to within this (image px), as seed 002 groups edges that share a vertex:
    // strokes that meet at a junction share the point, visible and hidden parts of a line meet
    // end to end. A line that ends on another's side where it passes behind it (an occlusion
    // T-junction) does not touch it: on a scanned mesh those come and go every frame, and groups
    // joined through them split and merge (docs/strokes.md). Rounding only: both strokes take a
    // shared point from the same mesh point.
    double junction_px = 1e-3;
    // A stroke and last frame's parent still touch while an end of one lies within this (image
    // px) of the other's polyline: a junction that opens by a pixel as the strokes move does not
    // split their group.
    double keep_parent_px = 1.0;
    // A group's main stroke is one at least this share of the group's longest stroke (the one
    // under which most strokes keep last frame's level), chosen among the longest
    // main_candidates of them.
    double keep_main_share = 0.5;
    size_t main_candidates = 16;
    // Two of last frame's groups join only once a touch between their strokes has held this many
    // frames in a row (a third of a second at 24 frames/s): on a turning scanned mesh most
    // touches between groups last a frame or two, and each join and split would move every
    // level of the smaller group. New strokes join what they touch at once. 1: at once.
    uint32_t join_after_frames = 8;
};

// Which strokes touch which (an end of one within junction_px of a point of the other): for
// each stroke, the indices of the others it touches, ascending. An end is checked against at
// most 64 points around it; strokes whose ends share a point exactly always touch (where more
// than 64 do, each is listed with the first of them only), so a junction of thousands of strokes
// costs time linear in them. Every listed pair touches.
std::vector<std::vector<uint32_t>> touching_strokes(std::span<const Stroke> strokes, double junction_px);

class DrawingOrder {
  public:
    explicit DrawingOrder(DrawingOrderOptions options = {}) : options_(options) {}

    // Sets every stroke's group, level, parent and order (a permutation of 0 .. n-1), and
    // remembers them for the next frame:
    // - group: the strokes it is connected with through touching strokes (a stroke and last
    //   frame's parent touching while keep_parent_px apart; two strokes of different groups of
    //   last frame only once they have touched join_after_frames frames in a row), named by the
    //   id of the group's main stroke;
    // - main stroke (level 0): in a first frame the group's longest (exact length; the lower id
    //   on a tie); after that, of the strokes at least keep_main_share of the longest, the one
    //   under which the most strokes keep last frame's level (last frame's main stroke, then the
    //   longer, on a tie);
    // - a tree per group from the main stroke, each stroke hanging from one it touches (its
    //   parent, at the level above): last frame's parent while the two still touch in one group,
    //   else the stroke that reaches it first, breadth first from the main stroke;
    // - order: groups one after another, each level after level; strokes that were drawn last
    //   frame keep their order among themselves (groups by their main stroke); a new stroke
    //   from which some of them hang comes just before the first of those, the others longest
    //   first (lower id on a tie).
    void assign(std::vector<Stroke>& r_strokes);

  private:
    // Drops from r_touches each touch between strokes of two different groups of last frame
    // that has held fewer than join_after_frames frames in a row, and counts them in held_.
    void hold_back_joins(std::span<const Stroke> strokes, std::vector<std::vector<uint32_t>>& r_touches);

    DrawingOrderOptions options_;
    std::unordered_map<uint32_t, uint32_t> last_order_;  // stroke id -> its order last frame
    std::unordered_map<uint32_t, uint32_t> last_level_;   // stroke id -> its level (0: a main stroke)
    std::unordered_map<uint32_t, uint32_t> last_parent_;  // stroke id -> its parent's id
    std::unordered_map<uint32_t, uint32_t> last_group_;   // stroke id -> its group
    // Touches between strokes of two different groups of last frame:
    // (lower id << 32 | higher id) -> frames they have held in a row.
    std::unordered_map<uint64_t, uint32_t> held_;
};

}  // namespace inkline::core
