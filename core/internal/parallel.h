// SPDX-License-Identifier: MIT
// A minimal deterministic parallel loop over index ranges with std::thread.
#pragma once

#include <algorithm>
#include <cstddef>
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

}  // namespace inkline::core::internal
