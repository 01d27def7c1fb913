// SPDX-License-Identifier: MIT
// core/internal/float_round.h: the floats nearest a double on either side, as std::nextafter
// gives them, across signs, subnormals, zero and the ends of the float range.
#include "core/internal/float_round.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <vector>

namespace inkline {
namespace {

using Float = std::numeric_limits<float>;
using Double = std::numeric_limits<double>;

TEST(FloatRound, NextFloatIsStdNextafter) {
    const float inf = Float::infinity();
    const std::vector<float> values = {0.0f,           -0.0f,          Float::denorm_min(), -Float::denorm_min(),
                                       Float::min(),   -Float::min(),  1.0f,                -1.0f,
                                       0.1f,           -3.5e-3f,       1e30f,               Float::max(),
                                       -Float::max(),  -inf};
    for (const float f : values) {
        SCOPED_TRACE(f);
        EXPECT_EQ(std::bit_cast<uint32_t>(core::internal::next_float(f, false)), std::bit_cast<uint32_t>(std::nextafter(f, inf)));
        if (f != -inf) {
            EXPECT_EQ(std::bit_cast<uint32_t>(core::internal::next_float(f, true)), std::bit_cast<uint32_t>(std::nextafter(f, -inf)));
        }
    }
}

TEST(FloatRound, BoundsHoldTheDoubleAndAreTheNearestFloats) {
    const std::vector<double> values = {0.0,  1.0 / 3.0, -1.0 / 3.0, 1e-42,  -1e-42, 1e-300, -1e-300, 3.4028235e38,
                                        1e38, -7.25,     2.0 / 3.0,  123.456, 1e-45,  Double::denorm_min()};
    for (const double x : values) {
        SCOPED_TRACE(x);
        const float below = core::internal::float_below(x), above = core::internal::float_above(x);
        EXPECT_LE(double(below), x);
        EXPECT_GE(double(above), x);
        EXPECT_GT(double(std::nextafter(below, Float::infinity())), x) << "the greatest float at or below";
        EXPECT_LT(double(std::nextafter(above, -Float::infinity())), x) << "the least float at or above";
    }
    EXPECT_EQ(core::internal::float_above(0.5), 0.5f);
    EXPECT_EQ(core::internal::float_below(0.5), 0.5f);
}

}  // namespace
}  // namespace inkline
