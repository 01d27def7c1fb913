// SPDX-License-Identifier: MIT
#include "core/tone/tone_options.h"

#include <algorithm>
#include <cmath>

namespace inkline::core {

const char* tone_mode_name(ToneMode mode) {
    switch (mode) {
        case ToneMode::kNone: return "none";
        case ToneMode::kStipple: return "stipple";
        case ToneMode::kHatch: return "hatch";
        case ToneMode::kCrosshatch: return "crosshatch";
    }
    return "none";
}

std::optional<ToneMode> tone_mode_from_name(std::string_view name) {
    for (ToneMode mode : {ToneMode::kNone, ToneMode::kStipple, ToneMode::kHatch, ToneMode::kCrosshatch}) {
        if (name == tone_mode_name(mode)) return mode;
    }
    return std::nullopt;
}

double tone_of(double intensity, const ToneOptions& options) {
    const double x = 1.0 - std::clamp(intensity, 0.0, 1.0);
    double t = options.gamma == 1.0 ? x : std::pow(x, options.gamma);
    if (options.levels > 1) t = std::round(t * (options.levels - 1)) / double(options.levels - 1);
    return options.min + (options.max - options.min) * t;
}

}  // namespace inkline::core
