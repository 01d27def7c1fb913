// SPDX-License-Identifier: MIT
// File name patterns with a printf-style frame number: "frame_%04d.svg", "%d.obj".
#pragma once

#include <string>

namespace inkline::core {

// True when the pattern holds exactly one %d, %Nd or %0Nd.
bool has_frame_field(const std::string& pattern);

// Substitutes the frame number; a pattern without a field is returned unchanged.
// Throws InputError for a malformed field or more than one field.
std::string format_frame(const std::string& pattern, int frame);

}  // namespace inkline::core
