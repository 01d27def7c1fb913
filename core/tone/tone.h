// SPDX-License-Identifier: MIT
// A frame's tone (scene "tone", docs/tone.md): stipples (core/tone/stipple.h) or hatches
// (core/tone/hatch.h) on the visible surface.
#pragma once

#include "core/tone/hatch.h"
#include "core/tone/stipple.h"
#include "core/tone/tone_options.h"

#include <algorithm>
#include <vector>

namespace inkline::core {

struct FrameTone {
    ToneMode mode = ToneMode::kNone;  // the scene's
    // The modes drawn: the scene's alone, or where objects have modes of their own (scene
    // "objects") each mode some object is shaded with, the scene's first. A frame can then have
    // both dots and hatches.
    std::vector<ToneMode> modes;
    // The inks the marks are drawn in (a mark's `ink` indexes it): the scene's tone colour and
    // opacity, or where rules of "objects" and "styles" give objects inks of their own, each ink
    // some shaded object has. Empty: the scene's alone.
    std::vector<ToneInk> inks;
    std::vector<Dot> dots;        // stipple: ascending by sample
    std::vector<Hatch> hatches;   // hatch, crosshatch: by mode, by family, then as traced
    StippleStats stipple_stats;   // with stipple
    HatchStats hatch_stats;       // with hatch and crosshatch (their sum, with both)

    bool has(ToneMode m) const { return std::find(modes.begin(), modes.end(), m) != modes.end(); }
};

}  // namespace inkline::core
