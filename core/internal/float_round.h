// SPDX-License-Identifier: MIT
// The floats nearest a double on one side: bounds kept in single precision that must still hold
// the double-precision values they were computed from.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace inkline::core::internal {

// The float after f towards +infinity (towards -infinity with `down`): std::nextafter without a
// call into the maths library, for finite f and the infinity on the other side.
inline float next_float(float f, bool down) {
    if (f == 0.0f) return down ? -std::numeric_limits<float>::denorm_min() : std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<uint32_t>(f);
    // Away from zero the magnitude grows by one unit in the last place, towards it it shrinks.
    return std::bit_cast<float>((f > 0.0f) != down ? bits + 1 : bits - 1);
}

// The greatest float at or below x.
inline float float_below(double x) {
    const auto f = float(x);
    return double(f) > x ? next_float(f, true) : f;
}

// The least float at or above x.
inline float float_above(double x) {
    const auto f = float(x);
    return double(f) < x ? next_float(f, false) : f;
}

}  // namespace inkline::core::internal
