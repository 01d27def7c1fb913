// SPDX-License-Identifier: MIT
// The render options that are more than a word: frame ranges, image sizes, chunks, the input
// kind, the tone mode.
#pragma once

#include "core/scene/camera.h"
#include "core/tone/tone_options.h"

#include <string>
#include <utility>

namespace inkline::cli {

struct FrameRange {
    int first = 1;
    int last = 1;
    int count() const { return last - first + 1; }
};

// "A:B" or "A" -> inclusive frame range, within core's frame numbers. Throws InputError.
FrameRange parse_frames(const std::string& text);

// "WxH" -> image size, each side 1..max_side px. Throws InputError.
core::ImageSize parse_size(const std::string& text, int max_side);

// "K/N" or "slurm" (SLURM_ARRAY_TASK_ID within SLURM_ARRAY_TASK_MIN..SLURM_ARRAY_TASK_MAX) ->
// (K, N), 1 <= K <= N. Throws InputError.
std::pair<int, int> parse_chunk(const std::string& text);

// "stipple" or "none" -> the tone mode --tone asks for. Throws InputError.
core::ToneMode parse_tone(const std::string& text);

}  // namespace inkline::cli
