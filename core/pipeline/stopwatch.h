// SPDX-License-Identifier: MIT
// Wall-clock laps for the stage times of a frame (FrameStats::ms): the pipeline's stages, and
// what a program adds after them (its writers).
#pragma once

#include <chrono>

namespace inkline::core {

class Stopwatch {
  public:
    // Milliseconds since the last lap (or since construction).
    double lap_ms() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
        last_ = now;
        return ms;
    }

  private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace inkline::core
