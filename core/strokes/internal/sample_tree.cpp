// SPDX-License-Identifier: MIT
#include "core/strokes/internal/sample_tree.h"

#include <algorithm>
#include <glm/common.hpp>

namespace inkline::core::internal {

SampleTree::SampleTree(std::vector<TracedSample> samples) {
    std::erase_if(samples, [](const TracedSample& s) { return !std::isfinite(s.p_px.x) || !std::isfinite(s.p_px.y); });
    if (samples.empty()) return;
    // Samples at one position (strokes through one exact point) share a spot, lowest first: a
    // search then reads one distance for all of them.
    std::sort(samples.begin(), samples.end(), [](const TracedSample& a, const TracedSample& b) {
        return std::tie(a.p_px.x, a.p_px.y, a.trace, a.sample) < std::tie(b.p_px.x, b.p_px.y, b.trace, b.sample);
    });
    samples_.reserve(samples.size());
    for (const TracedSample& s : samples) {
        if (spots_.empty() || spots_.back().p != s.p_px) spots_.push_back({s.p_px, samples_.size(), samples_.size()});
        samples_.emplace_back(s.trace, s.sample);
        spots_.back().end = samples_.size();
    }
    nodes_.reserve(2 * (spots_.size() / kLeafSpots + 1));
    build(0, spots_.size());
}

size_t SampleTree::build(size_t begin, size_t end) {
    const size_t n = nodes_.size();
    Node node{.lo = spots_[begin].p, .hi = spots_[begin].p, .begin = begin, .end = end};
    for (size_t k = begin + 1; k < end; ++k) {
        node.lo = glm::min(node.lo, spots_[k].p);
        node.hi = glm::max(node.hi, spots_[k].p);
    }
    nodes_.push_back(node);
    if (end - begin <= kLeafSpots) return n;
    // Split the wider side at the median spot: spots are distinct, so (x, y) or (y, x) orders
    // them strictly and the halves are the same for any input order.
    const int axis = node.hi.x - node.lo.x >= node.hi.y - node.lo.y ? 0 : 1;
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(spots_.begin() + std::ptrdiff_t(begin), spots_.begin() + std::ptrdiff_t(mid),
                     spots_.begin() + std::ptrdiff_t(end), [axis](const Spot& a, const Spot& b) {
                         return std::tie(a.p[axis], a.p[1 - axis]) < std::tie(b.p[axis], b.p[1 - axis]);
                     });
    const size_t left = build(begin, mid);
    const size_t right = build(mid, end);
    nodes_[n].left = left;
    nodes_[n].right = right;
    return n;
}

}  // namespace inkline::core::internal
