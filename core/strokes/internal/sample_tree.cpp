// SPDX-License-Identifier: MIT
#include "core/strokes/internal/sample_tree.h"

#include <algorithm>
#include <glm/common.hpp>

namespace inkline::core::internal {

double line_angle(const glm::dvec2& d) {
    if (!std::isfinite(d.x) || !std::isfinite(d.y) || (d.x == 0.0 && d.y == 0.0)) return NAN;
    double a = std::atan2(d.y, d.x);
    if (a < 0.0) a += std::numbers::pi;
    if (a >= std::numbers::pi) a -= std::numbers::pi;
    return a;
}

SampleTree::SampleTree(std::vector<TracedSample> samples) {
    std::erase_if(samples, [](const TracedSample& s) { return !std::isfinite(s.p_px.x) || !std::isfinite(s.p_px.y); });
    if (samples.empty()) return;
    // Samples at one position (strokes through one exact point) share a spot, lowest first: a
    // search then reads one distance for all of them.
    std::sort(samples.begin(), samples.end(), [](const TracedSample& a, const TracedSample& b) {
        return std::tie(a.p_px.x, a.p_px.y, a.trace, a.sample) < std::tie(b.p_px.x, b.p_px.y, b.trace, b.sample);
    });
    samples_.reserve(samples.size());
    angles_.reserve(samples.size());
    for (const TracedSample& s : samples) {
        if (spots_.empty() || spots_.back().p != s.p_px) spots_.push_back({s.p_px, samples_.size(), samples_.size()});
        samples_.emplace_back(s.trace, s.sample);
        angles_.push_back(s.angle);
        spots_.back().end = samples_.size();
    }
    glm::dvec2 lo = spots_.front().p, hi = lo;
    for (const Spot& spot : spots_) lo = glm::min(lo, spot.p), hi = glm::max(hi, spot.p);
    nodes_.reserve(2 * (spots_.size() / kLeafSpots + 1));
    node_angles_.reserve(nodes_.capacity());
    build(0, spots_.size(), lo, hi);
}

size_t SampleTree::build(size_t begin, size_t end, glm::dvec2 lo, glm::dvec2 hi) {
    const size_t n = nodes_.size();
    nodes_.push_back({.begin = begin, .end = end});
    node_angles_.emplace_back();
    if (end - begin <= kLeafSpots) {
        Node& leaf = nodes_[n];
        NodeAngles& angles = node_angles_[n];
        leaf.lo = leaf.hi = spots_[begin].p;
        for (size_t k = begin; k < end; ++k) {
            leaf.lo = glm::min(leaf.lo, spots_[k].p);
            leaf.hi = glm::max(leaf.hi, spots_[k].p);
            for (size_t i = spots_[k].begin; i < spots_[k].end; ++i) {
                const double a = angles_[i];
                if (std::isnan(a)) {
                    angles.any = true;
                    continue;
                }
                const double turned = a < std::numbers::pi / 2 ? a + std::numbers::pi / 2 : a - std::numbers::pi / 2;
                angles.lo = {std::min(angles.lo[0], a), std::min(angles.lo[1], turned)};
                angles.hi = {std::max(angles.hi[0], a), std::max(angles.hi[1], turned)};
            }
        }
        return n;
    }
    // Split the region's wider side at the middle spot: spots are distinct, so (x, y) or (y, x)
    // orders them strictly. The node's own box is its children's, found below.
    const int axis = hi.x - lo.x >= hi.y - lo.y ? 0 : 1;
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(spots_.begin() + std::ptrdiff_t(begin), spots_.begin() + std::ptrdiff_t(mid),
                     spots_.begin() + std::ptrdiff_t(end), [axis](const Spot& a, const Spot& b) {
                         return std::tie(a.p[axis], a.p[1 - axis]) < std::tie(b.p[axis], b.p[1 - axis]);
                     });
    glm::dvec2 first_hi = hi, second_lo = lo;
    first_hi[axis] = second_lo[axis] = spots_[mid].p[axis];
    const size_t first = build(begin, mid, lo, first_hi);
    const size_t second = build(mid, end, second_lo, hi);
    Node& node = nodes_[n];
    node.second = second;
    node.lo = glm::min(nodes_[first].lo, nodes_[second].lo);
    node.hi = glm::max(nodes_[first].hi, nodes_[second].hi);
    NodeAngles& angles = node_angles_[n];
    const NodeAngles &a = node_angles_[first], &b = node_angles_[second];
    for (int r = 0; r < 2; ++r) {
        angles.lo[size_t(r)] = std::min(a.lo[size_t(r)], b.lo[size_t(r)]);
        angles.hi[size_t(r)] = std::max(a.hi[size_t(r)], b.hi[size_t(r)]);
    }
    angles.any = a.any || b.any;
    return n;
}

bool SampleTree::outside(const NodeAngles& angles, const AngleCone& cone) {
    if (angles.any) return false;
    // Angles outside the cone form the open arc (angle + w, angle + pi - w), modulo pi. Measured
    // from its start, the node's range must start past 0 and end before its length.
    const double w = cone.half_width + kAngleSlack;
    for (size_t r = 0; r < 2; ++r) {
        const double start = cone.angle + (r == 0 ? 0.0 : std::numbers::pi / 2) + w;
        double s = std::fmod(angles.lo[r] - start, std::numbers::pi);
        if (s < 0.0) s += std::numbers::pi;
        if (s > 0.0 && s + (angles.hi[r] - angles.lo[r]) < std::numbers::pi - 2.0 * w) return true;
    }
    return false;
}

}  // namespace inkline::core::internal
