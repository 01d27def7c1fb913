// SPDX-License-Identifier: MIT
#include "cli/parse.h"

#include "core/error.h"
#include "core/scene/frame_pattern.h"

#include <cstdlib>
#include <regex>

namespace inkline::cli {

FrameRange parse_frames(const std::string& text) {
    static const std::regex range(R"(^\s*(-?\d{1,18})\s*(?::\s*(-?\d{1,18}))?\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, range)) throw InputError("--frames '" + quote_value(text) + "': expected A:B");
    const long long first = std::stoll(m[1]), last = m[2].matched ? std::stoll(m[2]) : first;
    core::check_frame_range(first, last, "--frames '" + quote_value(text) + "'");
    return {int(first), int(last)};
}

core::ImageSize parse_size(const std::string& text, int max_side) {
    static const std::regex size(R"(^\s*(\d{1,9})\s*[xX]\s*(\d{1,9})\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, size)) throw InputError("--size '" + quote_value(text) + "': expected WxH");
    const core::ImageSize image{std::stoi(m[1]), std::stoi(m[2])};
    if (image.width <= 0 || image.height <= 0 || image.width > max_side || image.height > max_side) {
        throw InputError("--size '" + quote_value(text) + "': each side must be 1.." + std::to_string(max_side) +
                         " px (see --max-image-side)");
    }
    return image;
}

std::pair<int, int> parse_chunk(const std::string& text) {
    if (text == "slurm") {
        auto env = [](const char* name) -> long {
            const char* v = std::getenv(name);
            if (!v || !*v) throw InputError(std::string("--chunk slurm: ") + name + " is not set (not inside a Slurm job array?)");
            static const std::regex number(R"(^\s*\d{1,9}\s*$)");
            if (!std::regex_match(v, number)) {
                throw InputError(std::string("--chunk slurm: ") + name + " is not a task number");
            }
            return std::strtol(v, nullptr, 10);
        };
        const long id = env("SLURM_ARRAY_TASK_ID"), lo = env("SLURM_ARRAY_TASK_MIN"), hi = env("SLURM_ARRAY_TASK_MAX");
        if (id < lo || id > hi || hi - lo > 1000000) throw InputError("--chunk slurm: task id outside the array's bounds");
        return {int(id - lo + 1), int(hi - lo + 1)};
    }
    static const std::regex chunk(R"(^\s*(\d{1,7})\s*/\s*(\d{1,7})\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, chunk)) throw InputError("--chunk '" + quote_value(text) + "': expected K/N or slurm");
    const int k = std::stoi(m[1]), n = std::stoi(m[2]);
    if (n < 1) throw InputError("--chunk '" + quote_value(text) + "': N must be at least 1");
    if (k < 1 || k > n) throw InputError("--chunk '" + quote_value(text) + "': K must be 1.." + std::to_string(n));
    return {k, n};
}

core::ToneMode parse_tone(const std::string& text) {
    if (const std::optional<core::ToneMode> mode = core::tone_mode_from_name(text)) return *mode;
    throw InputError("--tone '" + quote_value(text) + "': expected stipple, hatch, crosshatch or none");
}

}  // namespace inkline::cli
