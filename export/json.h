// SPDX-License-Identifier: MIT
// The polylines JSON of one frame ("format": "inkline.polylines", version 1); see docs/polylines-json.md.
#pragma once

#include "core/frame_lines.h"

#include <string>

namespace inkline::output {

std::string polylines_json(const core::FrameLines& frame);

}  // namespace inkline::output
