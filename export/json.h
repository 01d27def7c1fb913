// SPDX-License-Identifier: MIT
// The polylines JSON of one frame ("format": "inkline.polylines", version 1); see docs/polylines-json.md.
#pragma once

#include "core/pipeline/frame_lines.h"
#include "core/strokes/strokes.h"
#include "core/tone/tone.h"

#include <string>

namespace inkline::output {

// With `strokes`, the strokes are the frame's brush strokes (stable ids, u, intensity, width,
// ends, outline); without, its visible polylines. With a `tone` whose mode is not none, a "tone"
// object lists its dots.
std::string polylines_json(const core::FrameLines& frame, const core::FrameStrokes* strokes = nullptr,
                           const core::FrameTone* tone = nullptr);

}  // namespace inkline::output
