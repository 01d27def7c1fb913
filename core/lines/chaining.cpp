// SPDX-License-Identifier: MIT
#include "core/lines/chaining.h"

#include <algorithm>

namespace inkline::core {
namespace {

constexpr uint8_t kNotFeature = 0xff;

// Vertices with at most this many edges have their feature edges counted by a scan.
constexpr size_t kScanEdges = 32;

class Chainer {
  public:
    Chainer(const FeatureEdges& features, const EdgeTable& table)
        : table_(table), kind_(table.edge_count(), kNotFeature), used_(table.edge_count(), 0) {
        for (const FeatureEdge& fe : features.edges) kind_[fe.edge] = uint8_t(fe.kind);
        // Both ends of every feature edge as (vertex, kind), sorted: a degree is then a count of
        // equal keys, not a scan of all the vertex's edges (a fan's apex may have hundreds of
        // thousands, thousands of them feature edges).
        std::vector<uint32_t> edges;
        edges.reserve(features.edges.size());
        for (const FeatureEdge& fe : features.edges) edges.push_back(fe.edge);
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        ends_.reserve(2 * edges.size());
        for (uint32_t e : edges) {
            ends_.push_back(end_key(table.edge_vertices[e].x, kind_[e]));
            ends_.push_back(end_key(table.edge_vertices[e].y, kind_[e]));
        }
        std::sort(ends_.begin(), ends_.end());
    }

    // Same-kind feature edges meeting at a vertex: counted around it when it has few edges (a
    // lookup in ends_ would miss the cache at every step), else looked up.
    int degree(uint32_t vertex, uint8_t kind) const {
        const auto around = table_.edges_around(vertex);
        if (around.size() <= kScanEdges) {
            int count = 0;
            for (uint32_t e : around) count += kind_[e] == kind;
            return count;
        }
        const auto range = std::equal_range(ends_.begin(), ends_.end(), end_key(vertex, kind));
        return int(range.second - range.first);
    }

    bool available(uint32_t edge) const { return kind_[edge] != kNotFeature && !used_[edge]; }

    // Follows unused same-kind edges from `start` along `first` until an end or a closed loop.
    Chain walk(uint32_t start, uint32_t first) {
        Chain chain;
        const uint8_t kind = kind_[first];
        chain.kind = LineKind(kind);
        chain.vertices.push_back(start);
        uint32_t vertex = start;
        uint32_t edge = first;
        while (true) {
            used_[edge] = 1;
            chain.edges.push_back(edge);
            vertex = table_.other_vertex(edge, vertex);
            chain.vertices.push_back(vertex);
            if (vertex == start || degree(vertex, kind) != 2) break;
            uint32_t next = kNoIndex;
            for (uint32_t e : table_.edges_around(vertex)) {
                if (kind_[e] == kind && !used_[e]) {
                    next = e;
                    break;
                }
            }
            if (next == kNoIndex) break;
            edge = next;
        }
        chain.closed = chain.vertices.size() > 2 && chain.vertices.front() == chain.vertices.back();
        return chain;
    }

    uint8_t kind_of(uint32_t edge) const { return kind_[edge]; }

  private:
    static uint64_t end_key(uint32_t vertex, uint8_t kind) { return uint64_t(vertex) << 8 | kind; }

    const EdgeTable& table_;
    std::vector<uint8_t> kind_;
    std::vector<uint8_t> used_;
    std::vector<uint64_t> ends_;  // end_key of both ends of each feature edge
};

}  // namespace

std::vector<Chain> chain_feature_edges(const FeatureEdges& features, const EdgeTable& table) {
    Chainer chainer(features, table);
    std::vector<Chain> chains;
    // Open chains first: start at every end (a vertex where the count is not 2).
    for (const FeatureEdge& fe : features.edges) {
        for (uint32_t v : {table.edge_vertices[fe.edge].x, table.edge_vertices[fe.edge].y}) {
            if (chainer.available(fe.edge) && chainer.degree(v, uint8_t(fe.kind)) != 2) {
                chains.push_back(chainer.walk(v, fe.edge));
            }
        }
    }
    // What is left lies on closed loops through vertices of count 2.
    for (const FeatureEdge& fe : features.edges) {
        if (chainer.available(fe.edge)) chains.push_back(chainer.walk(table.edge_vertices[fe.edge].x, fe.edge));
    }
    return chains;
}

}  // namespace inkline::core
