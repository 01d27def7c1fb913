// SPDX-License-Identifier: MIT
// Minimal deterministic parallel loops with std::thread.
//
// Both are safe under memory pressure: a thread that cannot be started leaves its work to the
// calling thread, and an exception thrown by the body on any thread (std::bad_alloc, say) is
// rethrown on the calling thread once every started thread has finished.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <numeric>
#include <span>
#include <system_error>
#include <thread>
#include <vector>

namespace inkline::core::internal {

// Cores this machine has (read once: glibc reads it from sysfs, an open, read and close per call,
// which costs more than a single occlusion query).
inline size_t hardware_threads() {
    static const size_t cores = std::max<size_t>(1, std::thread::hardware_concurrency());
    return cores;
}

// Worker threads (core/internal/worker.h) running a task now: a frame pipeline's next frame's
// lines, found while a frame is drawn.
inline std::atomic<size_t>& busy_workers() {
    static std::atomic<size_t> count{0};
    return count;
}
// Whether the calling thread is a Worker's.
inline bool& on_worker_thread() {
    thread_local bool on = false;
    return on;
}

// Cores left to a loop on the calling thread by the Workers busy beside it (at least one).
inline size_t free_threads() {
    const size_t busy = busy_workers().load(std::memory_order_relaxed) - (on_worker_thread() ? 1 : 0);
    return busy < hardware_threads() ? hardware_threads() - busy : 1;
}

// Runs task(t) for t in [0, count): t = 0 on the calling thread, the others on new threads where
// they can be started, else on the calling thread after its own. The first exception of any task
// is rethrown here after all of them have stopped.
template <typename Task>
void run_tasks(size_t count, const Task& task) {
    std::exception_ptr error;
    std::mutex error_mutex;
    auto guarded = [&](size_t t) {
        try {
            task(t);
        } catch (...) {
            const std::lock_guard lock(error_mutex);
            if (!error) error = std::current_exception();
        }
    };
    std::vector<std::thread> workers;
    size_t started = 1;
    try {
        workers.reserve(count - 1);
        for (; started < count; ++started) workers.emplace_back(guarded, started);
    } catch (const std::system_error&) {
    } catch (const std::bad_alloc&) {
    }
    guarded(0);
    for (size_t t = started; t < count; ++t) guarded(t);
    for (std::thread& w : workers) w.join();
    if (error) std::rethrow_exception(error);
}

// Calls body(begin, end) on contiguous slices of [0, n), one per hardware thread, when n is at
// least min_parallel; otherwise once on the calling thread. Slices never overlap, so writes to
// distinct output elements keep the result independent of scheduling.
template <typename Body>
void parallel_for(size_t n, size_t min_parallel, const Body& body) {
    if (n < min_parallel) {
        body(size_t(0), n);
        return;
    }
    const size_t slices = std::min(hardware_threads(), n);
    if (slices <= 1) {
        body(size_t(0), n);
        return;
    }
    run_tasks(slices, [&](size_t s) { body(n * s / slices, n * (s + 1) / slices); });
}

// Calls body(i) once for every i in [0, n) when the items' costs differ widely (a frame's
// strokes: one long line and many short ones): items are handed out one at a time, the heaviest
// first (by weight, larger first), to as many threads as there are cores that no busy Worker
// holds, when the total weight is at least min_parallel_weight. (On two cores, a frame's strokes
// drawn while the next frame's lines are found run on one: a second thread would only take turns
// with the Worker, and starting it costs more than it gains.) Each item runs alone, so writes to
// its own output element keep the result independent of scheduling.
template <typename Body>
void parallel_for_each(std::span<const double> weight, double min_parallel_weight, const Body& body) {
    const size_t n = weight.size();
    const size_t threads = std::min(free_threads(), n);
    if (threads <= 1 || std::accumulate(weight.begin(), weight.end(), 0.0) < min_parallel_weight) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return weight[a] > weight[b]; });
    std::atomic<size_t> next{0};
    run_tasks(threads, [&](size_t) {
        for (size_t k = next.fetch_add(1); k < n; k = next.fetch_add(1)) body(order[k]);
    });
}

}  // namespace inkline::core::internal
