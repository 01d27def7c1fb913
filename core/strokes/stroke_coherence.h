// SPDX-License-Identifier: MIT
// Stroke coherence across frames: stable ids, a direction and arc-length parameter u carried over
// from the previous frame, and loop start points that stay put. The only frame-to-frame state
// of the stroke stage; a value that depends on the previous frame's strokes alone.
// Based on: L. Bourdev. Rendering Nonphotorealistic Strokes with Temporal and Arc-Length
// Coherence. Master's thesis, Brown University, 1998: each sample takes the parameter of the
// nearest sample of the previous frame, as in X. Yuan, M. X. Nguyen, N. Zhang, B. Chen. Stippling
// and Silhouettes Rendering in Geometry-Image Space. Eurographics Symposium on Rendering 2005,
// section 6.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "core/lines/features.h"
#include "core/strokes/stroke_geometry.h"

namespace inkline::core {
namespace internal {
class SampleTree;
}

// Strokes move less than this (px) between frames; samples farther apart never match.
// A 3-degree turn of an object filling a 1024 px frame moves its outline by up to ~25 px, but
// most of a stroke moves far less, and the best-overlapping stroke wins.
inline constexpr double kMatchRadiusPx = 12.0;
// Samples along strokes for matching and u propagation, px apart.
inline constexpr double kTraceSpacingPx = 2.0;
// A stroke takes an old id only when they overlap over at least this fraction of the shorter.
inline constexpr double kMinOverlapFraction = 0.25;

// Last frame's strokes along one side of a stroke end are judged from the stroke's points over
// this length (px) next to the end: far enough that the nearest old sample belongs to the side's
// own stroke, not to one across a gap or junction.
inline constexpr double kSideReachPx = 12.0;
// Samples along that reach, px apart.
inline constexpr double kSideSpacingPx = 2.0;

// What the next frame needs of one stroke: not its geometry, a summary of it (its edges as a set,
// samples of its drawn centerline with their u).
struct StrokeTrace {
    uint32_t id = 0;
    LineKind kind = LineKind::kSilhouette;
    bool visible = true;
    bool closed = false;
    double length_px = 0.0;              // drawn length
    std::vector<uint32_t> edges;         // mesh edges, sorted and unique
    std::vector<glm::dvec2> samples_px;  // along the drawn centerline
    std::vector<double> samples_u;       // u at each sample, px
    glm::dvec2 start_px{0.0};            // a loop's start, where u = 0
    bool start_anchored = false;         // the start was anchored this frame, not carried over
};

// A stroke of the current frame before it has an id.
struct StrokeCandidate {
    StrokeGeometry geometry;             // its exact points and mesh edges, kind and visibility
    double length_px = 0.0;              // drawn length
    std::vector<glm::dvec2> samples_px;  // along the drawn centerline, from its start
    std::vector<double> samples_arc;     // arc length of each sample from the start, px
};

// How a candidate continues last frame's stroke (or starts a new one).
struct StrokeMatch {
    uint32_t id = 0;
    bool inherited = false;              // the id was present last frame
    bool reverse = false;                // run the stroke backwards to keep last frame's direction
    double u_offset = 0.0;               // open stroke: u at its start once reversed as asked
    std::optional<glm::dvec2> start_px;  // loop: where on the candidate's samples to start
};

// A stroke of last frame along one side of a stroke end.
struct SideMemory {
    int64_t id = -1;
    double u = 0.0;         // its u at the side's sample nearest the end, px
    double u_far = 0.0;     // its u at the side's sample farthest from the end
    double period = 0.0;    // its length when it was a loop (u wraps), else 0
    double distance = 0.0;  // mean distance (px) of the side's samples nearest it
};

// The points that judge one side of a stroke end: every kSideSpacingPx from the end (`end` 0:
// first point, 1: last) inward over kSideReachPx, the end itself left out; the midpoint of a
// stroke too short for any.
std::vector<glm::dvec2> side_samples(const std::vector<glm::dvec2>& points_px, int end);

// What continuation_fit asks of the ways u runs along two sides, from their ends inward. Where
// two sides continue one stroke, it runs opposite ways; a branch beside one side runs with it.
enum class SideHeadings : uint8_t {
    kAny,
    kOpposite,  // clearly (by more than kSideSpacingPx over the side), and opposite ways
    kSame,      // clearly, and the same way: side by side, both leading on from one place
};

// Whether two sides continue one stroke of last frame, next to each other along it: its u at
// the two differs by at most the path between them (px) plus what the sides' reach allows, and
// runs along them as `headings` asks. How closely they lie along it: the sum of the sides' mean
// distances (px), the least over the strokes both lie along; none where they do not continue one.
std::optional<double> continuation_fit(const std::vector<SideMemory>& a, const std::vector<SideMemory>& b,
                                       double path_px, SideHeadings headings);

class StrokeCoherence {
  public:
    StrokeCoherence();
    // The state after a frame, rebuilt from what that frame remembered and its next free id.
    StrokeCoherence(std::vector<StrokeTrace> traces, uint32_t next_id);

    // Matches this frame's strokes to the last frame's: each candidate takes the id of the
    // stroke it overlaps most (image length along shared mesh edges plus length lying within
    // kMatchRadiusPx), one candidate per id, largest overlaps first, then again over twice and
    // four times the radius for what is left; only then are pairs whose visibility changed
    // matched, in the same rounds. The rest get fresh ids in candidate order.
    // Deterministic for given inputs and state. Does not change the state.
    std::vector<StrokeMatch> match(const std::vector<StrokeCandidate>& candidates) const;

    // Makes a frame's strokes the reference for the next; next_id is the next unused id.
    void remember(std::vector<StrokeTrace> traces, uint32_t next_id);

    // Last frame's visible sample of the kind nearest a point, within kMatchRadiusPx.
    struct Nearest {
        int64_t id = -1;      // its stroke's id; -1 where there is none
        double u = 0.0;       // its u, px
        double period = 0.0;  // its stroke's length when that stroke was a loop (u wraps), else 0
    };
    std::vector<Nearest> nearest_visible(const std::vector<glm::dvec2>& points_px, LineKind kind) const;
    // For each side (its side_samples, and the kind of its stroke): every visible stroke of last
    // frame that is nearest to at least half of the samples, by id. Near a junction a side may
    // lie as near to a neighbour as to its own stroke, so there may be two.
    std::vector<std::vector<SideMemory>> side_memory(const std::vector<std::vector<glm::dvec2>>& sides,
                                                     const std::vector<LineKind>& kinds) const;
    // Only the ids of nearest_visible.
    std::vector<int64_t> nearest_visible_ids(const std::vector<glm::dvec2>& points_px, LineKind kind) const;

    const std::vector<StrokeTrace>& traces() const { return traces_; }
    uint32_t next_id() const { return next_id_; }

  private:
    std::vector<StrokeTrace> traces_;
    uint32_t next_id_ = 0;
    // traces_' samples in a tree per kind and visibility, with their angles: built once with
    // the traces, read by every search of the frame.
    std::shared_ptr<const std::vector<internal::SampleTree>> trees_;
};

}  // namespace inkline::core
