// SPDX-License-Identifier: MIT
#include "core/scene/frame_pattern.h"

#include "core/error.h"

#include <cctype>
#include <cstdio>

namespace inkline::core {
namespace {

struct Field {
    size_t begin = std::string::npos;  // index of '%'
    size_t end = 0;                    // one past 'd'
    int width = 0;
    bool zero_pad = false;
};

// Finds the single frame field; "%%" is a literal percent sign.
Field find_field(const std::string& pattern) {
    Field field;
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') continue;
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            ++i;
            continue;
        }
        size_t j = i + 1;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        int width = 0;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) {
            width = width * 10 + (pattern[j] - '0');
            if (width > 32) throw InputError("pattern '" + pattern + "': field width too large");
            ++j;
        }
        if (j >= pattern.size() || pattern[j] != 'd') {
            throw InputError("pattern '" + pattern + "': only %d, %Nd or %0Nd may stand for the frame");
        }
        if (field.begin != std::string::npos) {
            throw InputError("pattern '" + pattern + "': more than one frame field");
        }
        field = {i, j + 1, width, zero};
        i = j;
    }
    return field;
}

std::string unescape_percent(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        out += s[i];
        if (s[i] == '%' && i + 1 < s.size() && s[i + 1] == '%') ++i;
    }
    return out;
}

}  // namespace

bool has_frame_field(const std::string& pattern) {
    return find_field(pattern).begin != std::string::npos;
}

std::string format_frame(const std::string& pattern, int frame) {
    const Field field = find_field(pattern);
    if (field.begin == std::string::npos) return unescape_percent(pattern);
    char number[48];
    std::snprintf(number, sizeof number, field.zero_pad ? "%0*d" : "%*d", field.width, frame);
    return unescape_percent(pattern.substr(0, field.begin)) + number +
           unescape_percent(pattern.substr(field.end));
}

void check_frame_range(long long first, long long last, const std::string& where) {
    const auto in_range = [](long long f) { return f >= kMinFrame && f <= kMaxFrame; };
    if (!in_range(first) || !in_range(last)) {
        throw InputError(where + ": frame numbers must be between " + std::to_string(kMinFrame) + " and " +
                         std::to_string(kMaxFrame));
    }
    if (first > last) throw InputError(where + ": first frame is after the last");
}

}  // namespace inkline::core
