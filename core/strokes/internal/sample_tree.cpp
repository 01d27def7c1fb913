// SPDX-License-Identifier: MIT
#include "core/strokes/internal/sample_tree.h"

#include <algorithm>
#include <bit>
#include <glm/common.hpp>

namespace inkline::core::internal {
namespace {

// The bits of v moved to the even bits of the result.
uint64_t spread_bits(uint32_t v) {
    uint64_t x = v;
    x = (x | (x << 16)) & 0x0000FFFF0000FFFFull;
    x = (x | (x << 8)) & 0x00FF00FF00FF00FFull;
    x = (x | (x << 4)) & 0x0F0F0F0F0F0F0F0Full;
    x = (x | (x << 2)) & 0x3333333333333333ull;
    x = (x | (x << 1)) & 0x5555555555555555ull;
    return x;
}

struct Keyed {
    uint64_t key;
    size_t index;
};

// Items below this count are sorted by comparison: a radix sort's passes over 256 buckets cost
// more there.
constexpr size_t kMinRadixSort = 256;

// Sorts by key, keeping the order of equal keys. A pass per byte (least significant first),
// skipping the bytes that every key shares: linear, where a comparison sort's branches cost more
// than the whole search on hundreds of thousands of samples.
void sort_by_key(std::vector<Keyed>& r_items) {
    if (r_items.size() < kMinRadixSort) {
        std::sort(r_items.begin(), r_items.end(),
                  [](const Keyed& a, const Keyed& b) { return std::tie(a.key, a.index) < std::tie(b.key, b.index); });
        return;
    }
    std::vector<Keyed> scratch(r_items.size());
    for (int shift = 0; shift < 64; shift += 8) {
        std::array<size_t, 257> start{};
        for (const Keyed& k : r_items) ++start[((k.key >> shift) & 0xFF) + 1];
        if (std::find(start.begin() + 1, start.end(), r_items.size()) != start.end()) continue;
        for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
        for (const Keyed& k : r_items) scratch[start[(k.key >> shift) & 0xFF]++] = k;
        r_items.swap(scratch);
    }
}

}  // namespace

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
    // Samples in Z order (Morton) of their cell on a 2^32 x 2^32 grid over their square: the
    // samples of any cell of a quadtree over it follow one another.
    glm::dvec2 lo = samples.front().p_px, hi = lo;
    for (const TracedSample& s : samples) lo = glm::min(lo, s.p_px), hi = glm::max(hi, s.p_px);
    const double side = std::max(hi.x - lo.x, hi.y - lo.y);
    constexpr double kLastCell = 4294967295.0;
    const double scale = side > 0.0 ? kLastCell / side : 0.0;
    // A span too wide for a double (inf times a zero scale) puts every sample in cell 0.
    auto cell = [&](double v, double from) {
        const double c = (v - from) * scale;
        return c >= 0.0 ? uint32_t(std::min(c, kLastCell)) : 0u;
    };
    std::vector<Keyed> order(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
        const glm::dvec2 p = samples[i].p_px;
        order[i] = {spread_bits(cell(p.x, lo.x)) | (spread_bits(cell(p.y, lo.y)) << 1), i};
    }
    sort_by_key(order);
    // Samples at one position (strokes through one exact point) share a spot, lowest first: a
    // search then reads one distance for all of them. They share a key, as may a few others.
    auto before = [&](const Keyed& a, const Keyed& b) {
        const TracedSample &s = samples[a.index], &t = samples[b.index];
        return std::tie(s.p_px.x, s.p_px.y, s.trace, s.sample) < std::tie(t.p_px.x, t.p_px.y, t.trace, t.sample);
    };
    for (size_t i = 0, j = 0; i < order.size(); i = j) {
        while (j < order.size() && order[j].key == order[i].key) ++j;
        if (j - i > 1) std::sort(order.begin() + std::ptrdiff_t(i), order.begin() + std::ptrdiff_t(j), before);
    }
    std::vector<uint64_t> keys;  // of each spot
    samples_.reserve(samples.size());
    angles_.reserve(samples.size());
    for (const Keyed& k : order) {
        const TracedSample& s = samples[k.index];
        if (spots_.empty() || spots_.back().p != s.p_px) {
            spots_.push_back({s.p_px, samples_.size(), samples_.size()});
            keys.push_back(k.key);
        }
        samples_.emplace_back(s.trace, s.sample);
        angles_.push_back(s.angle);
        spots_.back().end = samples_.size();
    }
    nodes_.reserve(2 * (spots_.size() / kLeafSpots + 1));
    node_angles_.reserve(nodes_.capacity());
    build(0, spots_.size(), keys);
}

size_t SampleTree::build(size_t begin, size_t end, const std::vector<uint64_t>& keys) {
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
    // Split the smallest quadtree cell that holds the spots into its two halves (at the highest
    // bit where their keys differ), so that boxes stay compact; spots that share one key are
    // halved. The node's box is its children's, found below.
    size_t mid = begin + (end - begin) / 2;
    if (keys[begin] != keys[end - 1]) {
        const int bit = 63 - std::countl_zero(keys[begin] ^ keys[end - 1]);
        const uint64_t second_half = keys[end - 1] & ~((uint64_t(1) << bit) - 1);
        mid = size_t(std::lower_bound(keys.begin() + std::ptrdiff_t(begin), keys.begin() + std::ptrdiff_t(end),
                                      second_half) - keys.begin());
    }
    const size_t first = build(begin, mid, keys);
    const size_t second = build(mid, end, keys);
    Node& node = nodes_[n];
    node.second = second;
    node.lo = glm::min(nodes_[first].lo, nodes_[second].lo);
    node.hi = glm::max(nodes_[first].hi, nodes_[second].hi);
    NodeAngles& angles = node_angles_[n];
    const NodeAngles &a = node_angles_[first], &b = node_angles_[second];
    for (size_t r = 0; r < 2; ++r) {
        angles.lo[r] = std::min(a.lo[r], b.lo[r]);
        angles.hi[r] = std::max(a.hi[r], b.hi[r]);
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
