// SPDX-License-Identifier: MIT
#include "core/internal/union_find.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace inkline {
namespace {

using core::internal::UnionFind;

TEST(UnionFind, EveryIndexStartsAlone) {
    UnionFind<uint32_t> sets(4);
    for (uint32_t i = 0; i < 4; ++i) {
        EXPECT_EQ(sets.find(i), i);
        EXPECT_TRUE(sets.is_root(i));
    }
}

TEST(UnionFind, UniteKeepsTheLeastMemberAsRoot) {
    UnionFind<size_t> sets(6);
    EXPECT_TRUE(sets.unite(4, 2));
    EXPECT_TRUE(sets.unite(5, 4));
    EXPECT_TRUE(sets.unite(3, 1));
    EXPECT_FALSE(sets.unite(2, 5));  // one set already
    for (size_t i : {2, 4, 5}) EXPECT_EQ(sets.find(i), 2u);
    for (size_t i : {1, 3}) EXPECT_EQ(sets.find(i), 1u);
    EXPECT_EQ(sets.find(0), 0u);
    EXPECT_TRUE(sets.unite(5, 3));
    for (size_t i : {1, 2, 3, 4, 5}) EXPECT_EQ(sets.find(i), 1u);
    EXPECT_FALSE(sets.is_root(2));
}

TEST(UnionFind, MergeIntoKeepsTheGivenRoot) {
    // A stroke merged into another: the one it was merged into stays the owner, whatever the order.
    UnionFind<size_t> owner(5);
    owner.merge_into(3, 1);
    owner.merge_into(3, 4);
    owner.merge_into(0, 3);
    for (size_t i : {0, 1, 3, 4}) EXPECT_EQ(owner.find(i), 0u);
    EXPECT_TRUE(owner.is_root(2));
    EXPECT_FALSE(owner.is_root(3));
}

TEST(UnionFind, ResetSeparatesEverySetAgain) {
    UnionFind<uint32_t> sets(3);
    sets.unite(0, 2);
    sets.reset(5);
    for (uint32_t i = 0; i < 5; ++i) EXPECT_EQ(sets.find(i), i);
}

TEST(UnionFind, LongChainsStayShallow) {
    // Path halving: finds over a chain of a million merges finish (and agree).
    const size_t n = 1000000;
    UnionFind<size_t> sets(n);
    for (size_t i = 1; i < n; ++i) sets.merge_into(i, i - 1);  // 0 -> 1 -> 2 -> ... -> n-1
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(sets.find(i), n - 1);
}

}  // namespace
}  // namespace inkline
