// SPDX-License-Identifier: MIT
#include "core/internal/parallel.h"
#include "core/internal/worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

namespace inkline {
namespace {

using core::internal::parallel_for;
using core::internal::parallel_for_each;

TEST(Parallel, ForCoversEveryIndexOnceInDisjointSlices) {
    std::vector<std::atomic<int>> hits(1000);
    parallel_for(hits.size(), 2, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) ++hits[i];
    });
    for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
}

TEST(Parallel, ForEachRunsEveryItemOnceWhateverTheWeights) {
    const std::vector<double> weight = {1.0, 500.0, 0.0, 3.0, 500.0, 2.0, 7.0};
    for (const double min_weight : {0.0, 1e9}) {
        std::vector<std::atomic<int>> hits(weight.size());
        parallel_for_each(weight, min_weight, [&](size_t i) { ++hits[i]; });
        for (const auto& h : hits) EXPECT_EQ(h.load(), 1) << "min weight " << min_weight;
    }
    int calls = 0;
    parallel_for_each(std::vector<double>{}, 0.0, [&](size_t) { ++calls; });
    EXPECT_EQ(calls, 0);
}

TEST(Parallel, AnExceptionOnAnyThreadReachesTheCaller) {
    const std::vector<double> weight(64, 10.0);
    std::atomic<int> done{0};
    EXPECT_THROW(parallel_for_each(weight, 0.0,
                                   [&](size_t i) {
                                       if (i == 63) throw std::runtime_error("item 63");
                                       ++done;
                                   }),
                 std::runtime_error);
    EXPECT_EQ(done.load(), 63);  // the others still ran: no thread is left behind
    EXPECT_THROW(parallel_for(64, 2,
                              [&](size_t begin, size_t end) {
                                  if (end == 64 && begin < end) throw std::bad_alloc();
                              }),
                 std::bad_alloc);
}

TEST(Worker, RunsTasksInOrderOnOneThreadOfItsOwnAndHandsBackResultsAndErrors) {
    core::internal::Worker worker;
    std::vector<int> order;  // written by the worker's thread only
    std::vector<std::future<std::thread::id>> ids;
    for (int i = 0; i < 20; ++i) {
        ids.push_back(worker.submit([&order, i] {
            order.push_back(i);
            return std::this_thread::get_id();
        }));
    }
    std::future<int> failed = worker.submit([]() -> int { throw std::runtime_error("task failed"); });
    const std::thread::id first = ids.front().get();
    EXPECT_NE(first, std::this_thread::get_id());
    for (size_t i = 1; i < ids.size(); ++i) EXPECT_EQ(ids[i].get(), first);
    EXPECT_THROW(failed.get(), std::runtime_error);
    std::vector<int> expected(20);
    for (int i = 0; i < 20; ++i) expected[size_t(i)] = i;
    EXPECT_EQ(order, expected);
}

TEST(Worker, FinishesTheTasksGivenBeforeItGoes) {
    std::atomic<int> done{0};
    {
        core::internal::Worker worker;
        for (int i = 0; i < 50; ++i) {
            (void)worker.submit([&done] {
                std::this_thread::yield();
                ++done;
            });
        }
    }
    EXPECT_EQ(done.load(), 50);
    core::internal::Worker unused;  // never started: nothing to join
}

}  // namespace
}  // namespace inkline
