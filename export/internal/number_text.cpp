// SPDX-License-Identifier: MIT
#include "export/internal/number_text.h"

#include "core/error.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace inkline::output::internal {
namespace {

unsigned long long power_of_ten(int decimals) {
    unsigned long long unit = 1;
    for (int i = 0; i < decimals; ++i) unit *= 10;
    return unit;
}

}  // namespace

void append_units(std::string& r_out, long long u, int decimals, bool short_form) {
    const unsigned long long unit = power_of_ten(decimals);
    // A sign, 20 integer digits, a point and 19 decimals at most.
    char buf[48];
    char* end = buf;
    if (u < 0) *end++ = '-';
    const unsigned long long a = u < 0 ? 0ull - (unsigned long long)u : (unsigned long long)u;
    if (!(short_form && a < unit && a != 0)) end = std::to_chars(end, buf + sizeof buf, a / unit).ptr;
    unsigned long long frac = a % unit;
    if (frac != 0) {
        int digits = decimals;
        while (frac % 10 == 0) frac /= 10, --digits;
        *end++ = '.';
        // The fraction's digits, its leading zeros included.
        for (int k = digits - 1; k >= 0; --k, frac /= 10) end[k] = char('0' + frac % 10);
        end += digits;
    }
    r_out.append(buf, size_t(end - buf));
}

void append_fixed(std::string& r_out, double v, int decimals) {
    // Most numbers round to a whole count of units (held exactly below 2^52) whose exact
    // remainder is plainly less than half a unit: fma gives v * unit - k within 2^-53 of its
    // size, so a remainder below 0.5 - 2^-40 is below a half exactly, and k is the count
    // correctly rounded, as to_chars rounds it.
    const auto unit = double(power_of_ten(decimals));
    if (std::abs(v) * unit < 0x1p52) {
        const double k = std::nearbyint(v * unit);
        if (std::abs(std::fma(v, unit, -k)) < 0.5 - 0x1p-40) {
            append_units(r_out, (long long)k, decimals);
            return;
        }
    }
    // Fixed notation writes every integer digit: a far plane of 1e300 takes 301 of them.
    char buf[512];
    const auto [end, error] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
    INKLINE_CHECK(error == std::errc());
    auto n = int(end - buf);
    if (decimals > 0) {
        while (n > 0 && buf[n - 1] == '0') --n;
        if (n > 0 && buf[n - 1] == '.') --n;
    }
    if (n == 2 && buf[0] == '-' && buf[1] == '0') {  // "-0" after rounding
        buf[0] = '0';
        n = 1;
    }
    r_out.append(buf, size_t(n));
}

}  // namespace inkline::output::internal
