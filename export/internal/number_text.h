// SPDX-License-Identifier: MIT
// Decimal text of the numbers an SVG holds: fixed notation, at most a given number of decimals,
// no trailing zeros.
#pragma once

#include <string>

namespace inkline::output::internal {

// Appends u units of 10^-decimals as that number, or with short_form without the 0 before the
// point of a magnitude below 1 (-0.5 as -.5).
void append_units(std::string& r_out, long long u, int decimals, bool short_form = false);

// Appends v rounded to at most `decimals` decimals, trailing zeros (and a point left bare)
// dropped and a rounded "-0" written "0": the digits printf's %.*f gives, which round the
// exact binary value correctly.
void append_fixed(std::string& r_out, double v, int decimals);

}  // namespace inkline::output::internal
