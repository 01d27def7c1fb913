// SPDX-License-Identifier: MIT
// Stroke samples in a tree of boxes: the nearest sample to a point within a radius, ties to the
// lower (trace, sample), exactly as a search over every sample would find it, however the
// samples crowd (thousands of strokes through one point of the image cost a few boxes each). A
// search may also ask only for samples of strokes running within a cone of directions, and then
// passes over whole boxes of strokes that run across it.
// Based on: C. Lauterbach, M. Garland, S. Sengupta, D. Luebke, D. Manocha. Fast BVH Construction
// on GPUs. Eurographics 2009 (boxes over points sorted in Z order, split as a quadtree splits);
// J. H. Friedman, J. L. Bentley, R. A. Finkel. An Algorithm for Finding Best Matches in
// Logarithmic Expected Time. ACM TOMS 3(3), 1977 (the nearest first, boxes farther passed over).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

namespace inkline::core::internal {

// A sample of a stroke: where it lies (px), which it is, and the way its stroke runs there.
struct TracedSample {
    glm::dvec2 p_px{0.0};
    size_t trace = 0, sample = 0;
    double angle = NAN;  // radians in [0, pi), the stroke either way; NaN where it has none
};

// The angle (radians in [0, pi)) of a direction taken either way; NaN for a zero or non-finite
// vector.
double line_angle(const glm::dvec2& d);

// Directions within half_width (radians, at most pi/2) of `angle`, either way.
struct AngleCone {
    double angle = 0.0;
    double half_width = std::numbers::pi / 2;
};

class SampleTree {
  public:
    SampleTree() = default;
    // Samples with a non-finite coordinate are left out: no point lies within a radius of them.
    explicit SampleTree(std::vector<TracedSample> samples);

    struct Hit {
        size_t trace = size_t(-1), sample = 0;  // trace size_t(-1): none
        double distance = HUGE_VAL;             // px
    };

    // The sample nearest p within radius (px) among those use(trace, sample) accepts; ties go
    // to the lower (trace, sample). Distances are glm::length(sample - p). With a cone, samples
    // whose angle lies outside it (by more than kAngleSlack) may be passed over without asking
    // `use`, which must then refuse every such sample itself; samples without an angle are
    // always asked.
    template <typename Filter>
    Hit nearest(const glm::dvec2& p, double radius, Filter use, std::optional<AngleCone> cone = {}) const;
    Hit nearest(const glm::dvec2& p, double radius) const {
        return nearest(p, radius, [](size_t, size_t) { return true; });
    }

    bool empty() const { return nodes_.empty(); }

    // Angles are within a few units in the last place of the exact ones: a box is passed over
    // only when its samples lie outside the cone by more than this (radians).
    static constexpr double kAngleSlack = 1e-9;

  private:
    // A distinct position and its samples, samples_[begin, end), in (trace, sample) order.
    struct Spot {
        glm::dvec2 p{0.0};
        size_t begin = 0, end = 0;
    };
    // A box over spots_[begin, end), laid out depth first: an inner node's first child comes
    // next, its second at `second`.
    struct Node {
        glm::dvec2 lo{0.0}, hi{0.0};
        size_t begin = 0, end = 0;
        size_t second = 0;  // 0: a leaf (the root is never a child)
    };
    // The angles of a node's samples lie within [lo[r], hi[r]], measured from 0 (r = 0) and
    // turned by pi/2 (r = 1), so that lines near either way of the x axis have a narrow range in
    // one of the two.
    struct NodeAngles {
        std::array<double, 2> lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
        bool any = false;  // it holds a sample without an angle
    };
    // Spots per leaf: a few distance checks cost less than another level of boxes.
    static constexpr size_t kLeafSpots = 8;
    // Box bounds and sample distances are each within a few units in the last place of the exact
    // ones: a box is passed over only when it lies farther than the best by more than that, so
    // that a sample exactly as near as the best (a tie, maybe won by the lower index) is seen.
    static constexpr double kPruneSlack = 1e-12;
    // Nodes pending in a search: at most the depth of the tree plus one. Each level splits the
    // spots' shared cell of a 2^32 x 2^32 grid in two (64 levels at most), then halves spots of
    // one cell (64 more at most).
    static constexpr size_t kMaxPending = 130;

    // Builds the node over spots_[begin, end) and those below it; returns its index. keys: the
    // Z-order key of each spot, ascending.
    size_t build(size_t begin, size_t end, const std::vector<uint64_t>& keys);
    // Squared distance from p to the node's box (0 inside).
    static double box_distance2(const Node& node, const glm::dvec2& p) {
        const double dx = std::max({node.lo.x - p.x, p.x - node.hi.x, 0.0});
        const double dy = std::max({node.lo.y - p.y, p.y - node.hi.y, 0.0});
        return dx * dx + dy * dy;
    }
    // Whether every sample of a node runs outside the cone by more than kAngleSlack.
    static bool outside(const NodeAngles& angles, const AngleCone& cone);

    std::vector<std::pair<size_t, size_t>> samples_;  // (trace, sample), grouped by spot
    std::vector<double> angles_;                       // of each of samples_
    std::vector<Spot> spots_;                          // in Z order
    std::vector<Node> nodes_;                          // nodes_[0] is the root
    std::vector<NodeAngles> node_angles_;              // of each of nodes_
};

template <typename Filter>
SampleTree::Hit SampleTree::nearest(const glm::dvec2& p, double radius, Filter use,
                                    std::optional<AngleCone> cone) const {
    Hit best;
    if (nodes_.empty() || !std::isfinite(p.x) || !std::isfinite(p.y) || !(radius >= 0.0)) return best;
    if (cone && !(cone->half_width < std::numbers::pi / 2 && std::isfinite(cone->angle))) cone.reset();
    // Nodes still to search, nearest last; a node is passed over once no sample in its box can
    // be as near as the best so far.
    struct Pending {
        size_t node;
        double distance2;  // to its box
    };
    Pending stack[kMaxPending];  // uninitialized: filled before read
    size_t top = 0;
    stack[top++] = {0, box_distance2(nodes_[0], p)};
    auto limit2 = [&] {
        const double limit = std::min(radius, best.distance) * (1.0 + kPruneSlack);
        return limit * limit;
    };
    while (top > 0) {
        const auto [n, d2] = stack[--top];
        if (d2 > limit2()) continue;
        const Node& node = nodes_[n];
        if (cone && outside(node_angles_[n], *cone)) continue;
        if (node.second == 0) {
            for (size_t k = node.begin; k < node.end; ++k) {
                const Spot& spot = spots_[k];
                const double d = glm::length(spot.p - p);
                if (!(d <= radius) || d > best.distance) continue;
                // The first sample here that the filter accepts is the lowest of this spot.
                for (size_t i = spot.begin; i < spot.end; ++i) {
                    const auto [trace, sample] = samples_[i];
                    if (!use(trace, sample)) continue;
                    if (d < best.distance || std::tie(trace, sample) < std::tie(best.trace, best.sample))
                        best = {trace, sample, d};
                    break;
                }
            }
            continue;
        }
        const size_t a = n + 1, b = node.second;
        const double da = box_distance2(nodes_[a], p), db = box_distance2(nodes_[b], p);
        const bool a_first = da <= db;
        stack[top++] = a_first ? Pending{b, db} : Pending{a, da};
        stack[top++] = a_first ? Pending{a, da} : Pending{b, db};
    }
    return best;
}

}  // namespace inkline::core::internal
