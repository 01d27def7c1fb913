// SPDX-License-Identifier: MIT
#include "export/drawing.h"

#include "core/error.h"

#include <cctype>

namespace inkline::output {

Rgb parse_color(const std::string& text, const std::string& what) {
    auto hex = [&](char c) -> int {
        if (std::isdigit(static_cast<unsigned char>(c))) return c - '0';
        const char l = char(std::tolower(static_cast<unsigned char>(c)));
        if (l >= 'a' && l <= 'f') return 10 + l - 'a';
        throw InputError(what + ": '" + text + "' is not a colour (expected #rrggbb or #rgb)");
    };
    if (text.size() == 7 && text[0] == '#') {
        return {(hex(text[1]) * 16 + hex(text[2])) / 255.0, (hex(text[3]) * 16 + hex(text[4])) / 255.0,
                (hex(text[5]) * 16 + hex(text[6])) / 255.0};
    }
    if (text.size() == 4 && text[0] == '#') {
        return {hex(text[1]) * 17 / 255.0, hex(text[2]) * 17 / 255.0, hex(text[3]) * 17 / 255.0};
    }
    throw InputError(what + ": '" + text + "' is not a colour (expected #rrggbb or #rgb)");
}

Drawing centerline_drawing(const core::FrameLines& frame, const DrawStyle& style) {
    Drawing d{frame.frame, frame.image, frame.camera, style, {}};
    d.shapes.reserve(frame.strokes.size());
    for (const core::Polyline& line : frame.strokes) {
        Shape s;
        s.stroke_id = line.id;
        s.kind = line.kind;
        s.hidden = !line.visible;
        s.filled = false;
        s.closed = line.closed;
        s.points = line.points_px;
        if (s.closed && s.points.size() > 1) s.points.pop_back();  // the first point closes it
        d.shapes.push_back(std::move(s));
    }
    return d;
}

std::vector<std::string> layer_names() {
    std::vector<std::string> names;
    for (core::LineKind kind : core::kAllLineKinds) names.emplace_back(core::line_kind_name(kind));
    names.emplace_back("hidden");
    return names;
}

double layer_opacity(const DrawStyle& style, const std::string& layer) {
    return layer == "hidden" ? 0.5 * style.opacity : style.opacity;
}

std::string layer_of(const Shape& shape) { return shape.hidden ? "hidden" : core::line_kind_name(shape.kind); }

}  // namespace inkline::output
