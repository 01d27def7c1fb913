// SPDX-License-Identifier: MIT
// One thread that runs tasks in the order they come, kept for the life of the object: work handed
// off frame after frame runs on the same thread, so its allocations come from one malloc arena
// instead of a new thread's each time.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>

namespace inkline::core::internal {

class Worker {
  public:
    Worker() = default;
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;
    // Finishes the tasks already given, then stops the thread.
    ~Worker() {
        if (!thread_.joinable()) return;
        {
            const std::lock_guard lock(mutex_);
            stop_ = true;
        }
        wake_.notify_one();
        thread_.join();
    }

    // Queues task() for the thread, started on the first call; its result or exception comes
    // back through the future. Throws std::system_error when the thread cannot be started.
    template <typename Task>
    std::future<std::invoke_result_t<Task&>> submit(Task task) {
        auto job = std::make_shared<std::packaged_task<std::invoke_result_t<Task&>()>>(std::move(task));
        std::future<std::invoke_result_t<Task&>> result = job->get_future();
        {
            const std::lock_guard lock(mutex_);
            if (!thread_.joinable()) thread_ = std::thread([this] { serve(); });
            tasks_.emplace_back([job] { (*job)(); });
        }
        wake_.notify_one();
        return result;
    }

  private:
    void serve() {
        for (;;) {
            std::function<void()> task;
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [this] { return stop_ || !tasks_.empty(); });
                if (tasks_.empty()) return;  // stopped, nothing left
                task = std::move(tasks_.front());
                tasks_.pop_front();
            }
            task();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> tasks_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace inkline::core::internal
