// SPDX-License-Identifier: MIT
// A frame's tone (scene "tone", docs/tone.md): stipples (core/tone/stipple.h) or hatches
// (core/tone/hatch.h) on the visible surface.
#pragma once

#include "core/tone/hatch.h"
#include "core/tone/stipple.h"
#include "core/tone/tone_options.h"

#include <vector>

namespace inkline::core {

struct FrameTone {
    ToneMode mode = ToneMode::kNone;
    std::vector<Dot> dots;        // stipple: ascending by sample
    std::vector<Hatch> hatches;   // hatch, crosshatch: by family, then as traced
    StippleStats stipple_stats;   // with stipple
    HatchStats hatch_stats;       // with hatch and crosshatch
};

}  // namespace inkline::core
