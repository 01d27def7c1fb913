// SPDX-License-Identifier: MIT
// Chaining: feature edges of one kind that meet at a vertex become maximal polylines.
#pragma once

#include "core/lines/features.h"
#include "core/mesh/topology.h"

#include <cstdint>
#include <vector>

namespace inkline::core {

// A polyline through mesh vertices. edges[i] joins vertices[i] and vertices[i+1]; a closed
// chain repeats its first vertex at the end, so edges.size() + 1 == vertices.size() always.
struct Chain {
    LineKind kind = LineKind::kSilhouette;
    bool closed = false;
    std::vector<uint32_t> vertices;
    std::vector<uint32_t> edges;
};

// Links feature edges of the same kind through vertices where exactly two such edges meet;
// chains end at vertices with any other count. Deterministic: depends only on the edge set.
std::vector<Chain> chain_feature_edges(const FeatureEdges& features, const EdgeTable& table);

}  // namespace inkline::core
