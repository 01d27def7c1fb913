// SPDX-License-Identifier: MIT
// The floats nearest a double on one side: bounds kept in single precision that must still hold
// the double-precision values they were computed from.
#pragma once

#include <cmath>
#include <limits>

namespace inkline::core::internal {

// The greatest float at or below x.
inline float float_below(double x) {
    const auto f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

// The least float at or above x.
inline float float_above(double x) {
    const auto f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

}  // namespace inkline::core::internal
