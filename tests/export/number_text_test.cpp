// SPDX-License-Identifier: MIT
#include "export/internal/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace inkline {
namespace {

// printf's %.*f, trailing zeros and a bare point dropped, "-0" as "0".
std::string printf_fixed(double v, int decimals) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    std::string s = buf;
    if (decimals > 0 && s.find('.') != std::string::npos) {
        while (s.back() == '0') s.pop_back();
        if (s.back() == '.') s.pop_back();
    }
    if (s == "-0") s = "0";
    return s;
}

std::string fixed(double v, int decimals) {
    std::string out;
    output::internal::append_fixed(out, v, decimals);
    return out;
}

// Numbers are written as printf writes them, halves included: 0.125 is exactly a half of a
// hundredth and rounds to even, 2.675 lies just below its half and rounds down, 1.005 too.
TEST(NumberText, FixedWritesThePrintfDigits) {
    std::vector<double> values = {0.0, -0.0, 0.125, 0.375, -0.125, 0.5, 1.5, 2.5, -2.5};  // exact halves
    for (const double v : {2.675, 1.005, 0.005, -0.005, 0.045, 0.0049999, 1023.995, 123456.785}) values.push_back(v);
    for (const double v : {1e-300, -1e-300, 5e-324, 9.1e15, 1e22, 1e300, -1e300}) values.push_back(v);
    values.push_back(4503599627370495.5);  // 2^52 - 0.5
    values.push_back(4503599627370496.0);
    for (const double v : values) {
        for (int decimals = 0; decimals <= 6; ++decimals) {
            EXPECT_EQ(fixed(v, decimals), printf_fixed(v, decimals)) << v << " to " << decimals;
        }
    }
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> coordinate(-3000.0, 3000.0);
    std::uniform_int_distribution<int> exponent(-12, 40);
    for (int i = 0; i < 200000; ++i) {
        const int decimals = i % 7;
        // Coordinates, their values on the grid of the decimals and halfway between, and wide
        // magnitudes.
        double v = coordinate(random);
        if (i % 4 == 1) v = std::round(v * 1000.0) / 1000.0;
        if (i % 4 == 2) v = (std::round(v * std::pow(10.0, decimals)) + 0.5) / std::pow(10.0, decimals);
        if (i % 4 == 3) v = std::ldexp(v, exponent(random));
        ASSERT_EQ(fixed(v, decimals), printf_fixed(v, decimals)) << v << " to " << decimals;
    }
}

TEST(NumberText, UnitsWriteTheirNumber) {
    std::string out;
    output::internal::append_units(out, -5, 2, true);
    out += ' ';
    output::internal::append_units(out, -5, 2);
    out += ' ';
    output::internal::append_units(out, 12340, 2);
    out += ' ';
    output::internal::append_units(out, 0, 2, true);
    out += ' ';
    output::internal::append_units(out, 7, 0);
    EXPECT_EQ(out, "-.05 -0.05 123.4 0 7");
}

}  // namespace
}  // namespace inkline
