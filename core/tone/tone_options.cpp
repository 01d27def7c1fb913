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

const char* hatch_space_name(HatchSpace space) { return space == HatchSpace::kScreen ? "screen" : "object"; }

std::optional<ToneMode> tone_mode_from_name(std::string_view name) {
    for (ToneMode mode : {ToneMode::kNone, ToneMode::kStipple, ToneMode::kHatch, ToneMode::kCrosshatch}) {
        if (name == tone_mode_name(mode)) return mode;
    }
    return std::nullopt;
}

double tone_of(double intensity, const ToneCurve& curve) {
    const double x = 1.0 - std::clamp(intensity, 0.0, 1.0);
    double t = curve.gamma == 1.0 ? x : std::pow(x, curve.gamma);
    if (curve.levels > 1) t = std::round(t * (curve.levels - 1)) / double(curve.levels - 1);
    return curve.min + (curve.max - curve.min) * t;
}

void TonePatch::apply_to(ToneCurve& r_curve) const {
    if (gamma) r_curve.gamma = *gamma;
    if (levels) r_curve.levels = *levels;
    if (min) r_curve.min = *min;
    if (max) r_curve.max = *max;
}

}  // namespace inkline::core
