// SPDX-License-Identifier: MIT
// A minimal deterministic parallel loop over index ranges with std::thread.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <numeric>
#include <span>
#include <thread>
#include <vector>

namespace inkline::core::internal {

// Calls body(begin, end) on contiguous slices of [0, n), one per hardware thread, when n is at
// least min_parallel; otherwise once on the calling thread. Slices never overlap, so writes to
// distinct output elements keep the result independent of scheduling.
template <typename Body>
void parallel_for(size_t n, size_t min_parallel, const Body& body) {
    // Small calls return before asking for the thread count: glibc reads it from sysfs (an
    // open, read and close per call), which costs more than a single occlusion query.
    if (n < min_parallel) {
        body(size_t(0), n);
        return;
    }
    const size_t threads = std::max<size_t>(1, std::thread::hardware_concurrency());
    if (threads == 1) {
        body(size_t(0), n);
        return;
    }
    const size_t slices = std::min(threads, n);
    std::vector<std::thread> workers;
    workers.reserve(slices - 1);
    for (size_t s = 1; s < slices; ++s) {
        workers.emplace_back([&, s] { body(n * s / slices, n * (s + 1) / slices); });
    }
    body(0, n / slices);
    for (std::thread& w : workers) w.join();
}

// Calls body(i) once for every i in [0, n) when the items' costs differ widely (a frame's strokes:
// one long line and many short ones): items are handed out one at a time, the heaviest first (by
// weight, larger first), to as many threads as there are cores, when the total weight is at
// least min_parallel_weight. Each item runs alone, so writes to its own output element keep the
// result independent of scheduling.
template <typename Body>
void parallel_for_each(std::span<const double> weight, double min_parallel_weight, const Body& body) {
    const size_t n = weight.size();
    const double total = std::accumulate(weight.begin(), weight.end(), 0.0);
    if (n < 2 || total < min_parallel_weight) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    static const size_t cores = std::max<size_t>(1, std::thread::hardware_concurrency());
    const size_t threads = std::min(cores, n);
    if (threads == 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return weight[a] > weight[b]; });
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t k = next.fetch_add(1); k < n; k = next.fetch_add(1)) body(order[k]);
    };
    std::vector<std::thread> workers;
    workers.reserve(threads - 1);
    for (size_t t = 1; t < threads; ++t) workers.emplace_back(work);
    work();
    for (std::thread& w : workers) w.join();
}

}  // namespace inkline::core::internal
