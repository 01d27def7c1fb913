// SPDX-License-Identifier: MIT
// Stroke samples in a 2-d tree: the nearest sample to a point within a radius, ties to the lower
// (trace, sample), exactly as a search over every sample would find it, however the samples
// crowd (thousands of strokes through one point of the image cost a grid cell's worth each).
// Based on: J. L. Bentley. Multidimensional Binary Search Trees Used for Associative Searching.
// Communications of the ACM 18(9), 1975; J. H. Friedman, J. L. Bentley, R. A. Finkel. An
// Algorithm for Finding Best Matches in Logarithmic Expected Time. ACM TOMS 3(3), 1977.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <tuple>
#include <utility>
#include <vector>

namespace inkline::core::internal {

// A sample of a stroke: where it lies (px), and which it is.
struct TracedSample {
    glm::dvec2 p_px{0.0};
    size_t trace = 0, sample = 0;
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
    // to the lower (trace, sample). Distances are glm::length(sample - p).
    template <typename Filter>
    Hit nearest(const glm::dvec2& p, double radius, Filter use) const;
    Hit nearest(const glm::dvec2& p, double radius) const {
        return nearest(p, radius, [](size_t, size_t) { return true; });
    }

    bool empty() const { return nodes_.empty(); }

  private:
    // A distinct position and its samples, samples_[begin, end), in (trace, sample) order.
    struct Spot {
        glm::dvec2 p{0.0};
        size_t begin = 0, end = 0;
    };
    // A box over spots_[begin, end); an inner node's children split them at the middle.
    struct Node {
        glm::dvec2 lo{0.0}, hi{0.0};
        size_t begin = 0, end = 0;
        size_t left = 0, right = 0;  // 0: a leaf (the root is never a child)
    };
    // Spots per leaf: a few distance checks cost less than another level of boxes.
    static constexpr size_t kLeafSpots = 8;
    // Box bounds and sample distances are each within a few units in the last place of the exact
    // ones: a box is passed over only when it lies farther than the best by more than that, so
    // that a sample exactly as near as the best (a tie, maybe won by the lower index) is seen.
    static constexpr double kPruneSlack = 1e-12;
    // Nodes pending in a search: at most the depth of the tree plus one, and halving the spots
    // at each level keeps the depth within 64.
    static constexpr size_t kMaxPending = 128;

    // Builds the node over spots_[begin, end) and those below it; returns its index.
    size_t build(size_t begin, size_t end);
    // Squared distance from p to the node's box (0 inside).
    double box_distance2(const Node& node, const glm::dvec2& p) const {
        const double dx = std::max({node.lo.x - p.x, p.x - node.hi.x, 0.0});
        const double dy = std::max({node.lo.y - p.y, p.y - node.hi.y, 0.0});
        return dx * dx + dy * dy;
    }

    std::vector<std::pair<size_t, size_t>> samples_;  // (trace, sample), grouped by spot
    std::vector<Spot> spots_;                          // in tree order
    std::vector<Node> nodes_;                          // nodes_[0] is the root
};

template <typename Filter>
SampleTree::Hit SampleTree::nearest(const glm::dvec2& p, double radius, Filter use) const {
    Hit best;
    if (nodes_.empty() || !std::isfinite(p.x) || !std::isfinite(p.y) || !(radius >= 0.0)) return best;
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
        if (node.left == 0) {
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
        const double dl = box_distance2(nodes_[node.left], p), dr = box_distance2(nodes_[node.right], p);
        const bool left_first = dl <= dr;
        stack[top++] = left_first ? Pending{node.right, dr} : Pending{node.left, dl};
        stack[top++] = left_first ? Pending{node.left, dl} : Pending{node.right, dr};
    }
    return best;
}

}  // namespace inkline::core::internal
