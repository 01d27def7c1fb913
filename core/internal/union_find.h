// SPDX-License-Identifier: MIT
// Disjoint sets of the indices 0 .. n-1 (union-find with path halving), for grouping things that
// touch and for tracking which item another was merged into.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace inkline::core::internal {

template <typename Index = size_t>  // an unsigned integer type wide enough for n
class UnionFind {
  public:
    explicit UnionFind(size_t n) { reset(n); }
    // Makes each of 0 .. n-1 a set of its own again, keeping the storage.
    void reset(size_t n) {
        parent_.resize(n);
        std::iota(parent_.begin(), parent_.end(), Index(0));
    }

    // The root of x's set.
    Index find(Index x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    // True when x is the root of its set (nothing it was in has been merged into another).
    bool is_root(Index x) const { return parent_[x] == x; }

    // Joins the sets of a and b under the lower of their roots, so a set's root is its least
    // member. False when they were one set already.
    bool unite(Index a, Index b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent_[std::max(a, b)] = std::min(a, b);
        return true;
    }
    // Joins the set of root `from` into the set of root `into`, whose root stays the root.
    void merge_into(Index into, Index from) { parent_[from] = into; }

  private:
    std::vector<Index> parent_;
};

}  // namespace inkline::core::internal
