// SPDX-License-Identifier: MIT
#include "core/error.h"

#include <cstdint>

namespace inkline {
namespace {

// Index of the UTF-8 character boundary at or before i (continuation bytes are 10xxxxxx).
size_t boundary_before(std::string_view text, size_t i) {
    while (i > 0 && i < text.size() && (uint8_t(text[i]) & 0xC0) == 0x80) --i;
    return i;
}

}  // namespace

std::string quote_value(std::string_view value, size_t max_chars) {
    std::string out;
    if (value.size() <= max_chars) {
        out = value;
    } else {
        const size_t half = max_chars / 2;
        const size_t head = boundary_before(value, half);
        const size_t tail = boundary_before(value, value.size() - (max_chars - half - 3));
        out = std::string(value.substr(0, head)) + "..." + std::string(value.substr(tail));
    }
    for (char& c : out) {
        if (uint8_t(c) < 0x20 || c == 0x7F) c = '?';
    }
    return out;
}

}  // namespace inkline

namespace inkline::detail {

void check_failed(const char* file, int line, const std::string& message) {
    std::ostringstream out;
    out << "internal check failed at " << file << ":" << line << ": " << message;
    throw InternalError(out.str());
}

}  // namespace inkline::detail
