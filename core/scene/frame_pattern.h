// SPDX-License-Identifier: MIT
// File name patterns with a printf-style frame number: "frame_%04d.svg", "%d.obj".
#pragma once

#include <string>

namespace inkline::core {

// Frame numbers are at most nine digits either way: every stage adds, subtracts and counts
// frames in `int` without overflow, and a pattern's field never needs more than ten characters.
inline constexpr int kMinFrame = -999'999'999;
inline constexpr int kMaxFrame = 999'999'999;

// Throws InputError("<where>: ...") unless kMinFrame <= first <= last <= kMaxFrame.
void check_frame_range(long long first, long long last, const std::string& where);

// True when the pattern holds exactly one %d, %Nd or %0Nd.
bool has_frame_field(const std::string& pattern);

// Substitutes the frame number; a pattern without a field is returned unchanged.
// Throws InputError for a malformed field or more than one field.
std::string format_frame(const std::string& pattern, int frame);

}  // namespace inkline::core
