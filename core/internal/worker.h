// SPDX-License-Identifier: MIT
// One thread that runs tasks in the order they come, kept for the life of the object: work handed
// off frame after frame runs on the same thread, so its allocations come from one malloc arena
// instead of a new thread's each time.
//
// A process forked after the thread started has no such thread (a Python program forking its
// workers, say): there forked() is true, and the destructor neither waits for the thread nor
// destroys what it shared with it (a condition variable that the thread was waiting on would
// wait for it forever). The tasks it had are lost; their futures never become ready.
#pragma once

#include <unistd.h>

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>

#include "core/internal/parallel.h"

namespace inkline::core::internal {

class Worker {
  public:
    Worker() = default;
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;
    // Finishes the tasks already given, then stops the thread.
    ~Worker() {
        if (!thread_.joinable()) return;
        if (forked()) {
            thread_.detach();
            (void)shared_.release();  // left as the fork copied it
            return;
        }
        {
            const std::lock_guard lock(shared_->mutex);
            shared_->stop = true;
        }
        shared_->wake.notify_one();
        thread_.join();
    }

    // True in a process forked from the one whose thread runs the tasks.
    bool forked() const { return thread_.joinable() && getpid() != owner_; }

    // Queues task() for the thread, started on the first call; its result or exception comes
    // back through the future. Throws std::system_error when the thread cannot be started.
    template <typename Task>
    std::future<std::invoke_result_t<Task&>> submit(Task task) {
        auto job = std::make_shared<std::packaged_task<std::invoke_result_t<Task&>()>>(std::move(task));
        std::future<std::invoke_result_t<Task&>> result = job->get_future();
        {
            const std::lock_guard lock(shared_->mutex);
            if (!thread_.joinable()) {
                thread_ = std::thread([shared = shared_.get()] { serve(*shared); });
                owner_ = getpid();
            }
            shared_->tasks.emplace_back([job] {
                (*job)();
                busy_workers().fetch_sub(1, std::memory_order_relaxed);
            });
            // Busy from now until the task is done (core/internal/parallel.h); the thread takes
            // it only once the lock is let go. (A process forked meanwhile keeps the count.)
            busy_workers().fetch_add(1, std::memory_order_relaxed);
        }
        shared_->wake.notify_one();
        return result;
    }

  private:
    // What the caller and the thread share.
    struct Shared {
        std::mutex mutex;
        std::condition_variable wake;
        std::deque<std::function<void()>> tasks;
        bool stop = false;
    };

    static void serve(Shared& shared) {
        on_worker_thread() = true;
        for (;;) {
            std::function<void()> task;
            {
                std::unique_lock lock(shared.mutex);
                shared.wake.wait(lock, [&] { return shared.stop || !shared.tasks.empty(); });
                if (shared.tasks.empty()) return;  // stopped, nothing left
                task = std::move(shared.tasks.front());
                shared.tasks.pop_front();
            }
            task();
        }
    }

    std::unique_ptr<Shared> shared_ = std::make_unique<Shared>();
    std::thread thread_;
    pid_t owner_ = 0;  // the process the thread runs in
};

}  // namespace inkline::core::internal
