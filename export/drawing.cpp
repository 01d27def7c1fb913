// SPDX-License-Identifier: MIT
#include "export/drawing.h"

#include "core/error.h"
#include "core/strokes/brush.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

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

namespace {

// A constant-width stroked centerline; a closed one drops its repeated first point (Z closes it).
Shape stroked_shape(uint32_t id, core::LineKind kind, bool visible, bool closed, std::vector<glm::dvec2> points) {
    if (closed && points.size() > 2 && points.front() == points.back()) points.pop_back();
    Shape s;
    s.stroke_id = id;
    s.kind = kind;
    s.hidden = !visible;
    s.closed = closed;
    s.paths.push_back(std::move(points));
    return s;
}

}  // namespace

// The name of a line's object, or "" without objects.
std::string object_name(const core::FrameLines& frame, int32_t object) {
    return object >= 0 && size_t(object) < frame.objects.size() ? frame.objects[size_t(object)].name : std::string();
}

// The ink of the writer's own style.
InkStyle base_ink(const DrawStyle& style) {
    InkStyle ink;
    ink.color = style.color;
    ink.opacity = style.opacity;
    return ink;
}

Drawing centerline_drawing(const core::FrameLines& frame, const DrawStyle& style) {
    Drawing d{frame.frame, frame.image, frame.camera, style, {}, {base_ink(style)}, true};
    d.shapes.reserve(frame.polylines.size());
    for (const core::Polyline& line : frame.polylines) {
        d.shapes.push_back(stroked_shape(line.id, line.kind, line.visible, line.closed, line.points_px));
        d.shapes.back().object = object_name(frame, line.object);
        d.shapes.back().object_index = line.object;
    }
    return d;
}

const char* path_format_name(PathFormat format) { return format == PathFormat::kBezier ? "bezier" : "polygon"; }

PathFormat parse_path_format(const std::string& text, const char* key) {
    for (const PathFormat format : {PathFormat::kPolygon, PathFormat::kBezier}) {
        if (text == path_format_name(format)) return format;
    }
    throw InputError(std::string(key) + " '" + quote_value(text) + "': expected polygon or bezier");
}

namespace {

// The shape carries its stroke's drawing order.
void set_order(const core::Stroke& stroke, Shape& r_shape) {
    r_shape.group = stroke.group;
    r_shape.level = stroke.level;
    r_shape.parent = stroke.parent;
    r_shape.order = stroke.order;
}

}  // namespace

Drawing brush_drawing(const core::FrameLines& frame, const core::FrameStrokes& strokes, const DrawStyle& style,
                      bool centerline) {
    Drawing d{frame.frame, frame.image, frame.camera, style, {}, {base_ink(style)}};
    for (size_t k = 1; k < strokes.styles.size(); ++k) {
        const core::StrokeStyle& st = strokes.styles[k];
        InkStyle ink;
        ink.name = st.name;
        ink.rule = st.rule;
        ink.color = hex_color(st.brush.color);
        ink.opacity = st.brush.opacity;
        ink.dash_px = st.brush.dash_px;
        ink.cap = st.brush.cap;
        ink.line_width_px = st.brush.line_width_px;
        d.styles.push_back(std::move(ink));
    }
    d.shapes.reserve(strokes.strokes.size());
    for (const core::Stroke& stroke : strokes.strokes) {
        const core::StrokeGeometry& g = stroke.geometry;
        if (g.visible && !stroke.drawn) continue;
        if (g.visible && !centerline) {
            if (stroke.outline.empty()) continue;
            Shape s;
            s.stroke_id = stroke.id;
            s.kind = g.kind;
            s.closed = g.closed;
            s.filled = true;
            s.paths.assign(stroke.outline.begin(), stroke.outline.end());
            if (style.path_format == PathFormat::kBezier) {
                for (const core::Ring& ring : stroke.outline) s.curves.push_back(core::fit_cubics(ring, style.bezier_tolerance_px));
            }
            s.object = object_name(frame, g.object);
            s.object_index = g.object;
            s.style = stroke.style;
            s.darkening = stroke.darkening;
            set_order(stroke, s);
            d.shapes.push_back(std::move(s));
            continue;
        }
        // Hidden lines and plotter output follow the drawn centerline when there is one.
        const bool on_centerline = stroke.centerline_px.size() >= 2;
        d.shapes.push_back(stroked_shape(stroke.id, g.kind, g.visible, g.closed,
                                         on_centerline ? stroke.centerline_px : g.points_px));
        Shape& s = d.shapes.back();
        s.object = object_name(frame, g.object);
        s.object_index = g.object;
        s.style = stroke.style;
        const std::vector<double>& u = on_centerline ? stroke.centerline_u : stroke.u;
        s.u_start = u.empty() ? 0.0 : u.front();
        set_order(stroke, s);
    }
    return d;
}

WriteOnAnimation write_on_animation(const core::FrameStrokes& strokes, const core::WriteOnSchedule& schedule) {
    WriteOnAnimation animation;
    animation.seconds = schedule.seconds;
    for (const core::WriteOnSchedule::Entry& e : schedule.entries) {
        const core::Stroke& s = strokes.strokes[e.stroke];
        WriteOnPath path;
        path.stroke_id = s.id;
        path.begin_s = e.start_s;
        path.duration_s = schedule.end_s(e) - e.start_s;
        path.centerline = s.centerline_px;
        path.closed = s.geometry.closed;
        path.length_px = e.length_px;
        for (const double w : s.centerline_width) path.width_px = std::max(path.width_px, w);
        if (s.style < strokes.styles.size()) path.taper_px = strokes.styles[s.style].brush.taper_px;
        animation.paths.push_back(std::move(path));
    }
    return animation;
}

std::string hex_color(const glm::dvec3& rgb) { return core::color_hex(rgb); }

ToneLayer tone_layer(const core::FrameTone& tone, const core::ToneOptions& options) {
    ToneLayer layer;
    layer.mode = tone.mode;
    layer.color = hex_color(options.color);
    layer.opacity = options.opacity;
    if (!tone.inks.empty()) {
        layer.color = hex_color(tone.inks.front().color);
        layer.opacity = tone.inks.front().opacity;
        layer.style = tone.inks.front().style;
    }
    if (tone.inks.size() > 1) {
        for (const core::ToneInk& ink : tone.inks) layer.inks.push_back({hex_color(ink.color), ink.opacity, ink.style});
    }
    layer.dots.reserve(tone.dots.size());
    for (const core::Dot& dot : tone.dots) layer.dots.push_back({dot.sample, dot.point_px, dot.radius_px, dot.ink});
    layer.hatches.reserve(tone.hatches.size());
    for (const core::Hatch& hatch : tone.hatches) {
        layer.hatches.push_back({hatch.family, hatch.plane, hatch.outline, hatch.ink});
    }
    if (!layer.inks.empty()) {
        const auto by_ink = [](const auto& a, const auto& b) { return a.ink < b.ink; };
        std::stable_sort(layer.dots.begin(), layer.dots.end(), by_ink);
        std::stable_sort(layer.hatches.begin(), layer.hatches.end(), by_ink);
    }
    return layer;
}

namespace {
// The run of marks of one ink in marks sorted by ink; all of them without inks.
template <typename Mark>
std::span<const Mark> marks_of(const std::vector<Mark>& marks, bool inks, size_t ink) {
    if (!inks) return marks;
    const auto begin = std::partition_point(marks.begin(), marks.end(), [&](const Mark& m) { return m.ink < ink; });
    const auto end = std::partition_point(begin, marks.end(), [&](const Mark& m) { return m.ink <= ink; });
    return {begin, end};
}
}  // namespace

std::span<const ToneDot> ToneLayer::dots_of(size_t ink) const { return marks_of(dots, !inks.empty(), ink); }
std::span<const ToneHatch> ToneLayer::hatches_of(size_t ink) const { return marks_of(hatches, !inks.empty(), ink); }

DrawStyle brush_draw_style(const core::BrushStyle& brush) {
    DrawStyle style;
    style.color = hex_color(brush.color);
    style.opacity = brush.opacity;
    style.bezier_tolerance_px = brush.max_deviation_px;
    return style;
}

const char* layer_name(Layer layer) {
    switch (layer) {
        case Layer::kSilhouette: return core::line_kind_name(core::LineKind::kSilhouette);
        case Layer::kBoundary: return core::line_kind_name(core::LineKind::kBoundary);
        case Layer::kCrease: return core::line_kind_name(core::LineKind::kCrease);
        case Layer::kIntersection: return core::line_kind_name(core::LineKind::kIntersection);
        case Layer::kHidden: return "hidden";
    }
    return "";
}

InkStyle ink_of(const Drawing& d, const Shape& shape) {
    if (shape.style < d.styles.size()) return d.styles[shape.style];
    return d.styles.empty() ? base_ink(d.style) : d.styles.front();
}

std::string color_of(const Drawing& d, const Shape& shape) {
    const InkStyle ink = ink_of(d, shape);
    if (!(shape.darkening > 0.0)) return ink.color;
    const Rgb rgb = parse_color(ink.color, "color");
    const double k = 1.0 - std::clamp(shape.darkening, 0.0, 1.0);
    return hex_color(glm::dvec3(rgb.r, rgb.g, rgb.b) * k);
}

double line_width_of(const Drawing& d, const Shape& shape) {
    return ink_of(d, shape).line_width_px.value_or(d.style.centerline_width_px);
}

std::vector<double> dashes_of(const Drawing& d, const Shape& shape) {
    const InkStyle ink = ink_of(d, shape);
    if (!ink.dash_px.empty()) return ink.dash_px;
    if (!shape.hidden) return {};
    const double w = line_width_of(d, shape);
    return {3.0 * w, 2.0 * w};
}

double dash_offset_of(const Drawing& d, const Shape& shape) {
    return ink_of(d, shape).dash_px.empty() ? 0.0 : shape.u_start;
}

double shape_opacity(const Drawing& d, const Shape& shape, double layer_opacity) {
    const double factor = layer_of(shape) == Layer::kHidden ? 0.5 : 1.0;
    const double own = ink_of(d, shape).opacity;
    return layer_opacity == factor * own ? 1.0 : own;
}

Layer layer_of(const Shape& shape) {
    if (shape.hidden) return Layer::kHidden;
    switch (shape.kind) {
        case core::LineKind::kSilhouette: return Layer::kSilhouette;
        case core::LineKind::kBoundary: return Layer::kBoundary;
        case core::LineKind::kCrease: return Layer::kCrease;
        case core::LineKind::kIntersection: return Layer::kIntersection;
    }
    return Layer::kSilhouette;
}

std::vector<LineLayer> line_layers(const Drawing& d, LayerGrouping grouping) {
    // The kind layers of the shapes `selected` picks, empty ones too where `keep_empty` says.
    std::vector<LineLayer> layers;
    auto add_kinds = [&](const std::string& parent_id, const std::string& parent_label, auto selected, auto keep_empty) {
        for (const Layer kind : kAllLayers) {
            LineLayer layer{parent_id, parent_label, kind, {}, 1.0};
            for (uint32_t i = 0; i < d.shapes.size(); ++i) {
                if (layer_of(d.shapes[i]) == kind && selected(d.shapes[i])) layer.shapes.push_back(i);
            }
            if (layer.shapes.empty() && !keep_empty(kind)) continue;
            layer.opacity = layer_opacity(d, kind, selected);
            layers.push_back(std::move(layer));
        }
    };
    const bool any_object = std::any_of(d.shapes.begin(), d.shapes.end(), [](const Shape& s) { return s.object_index >= 0; });
    if (grouping == LayerGrouping::kObject && any_object) {
        std::vector<std::pair<int32_t, std::string>> objects;  // (index, name)
        for (const Shape& s : d.shapes) objects.emplace_back(s.object_index, s.object_index >= 0 ? s.object : std::string());
        std::sort(objects.begin(), objects.end());
        objects.erase(std::unique(objects.begin(), objects.end(),
                                  [](const auto& a, const auto& b) { return a.first == b.first; }),
                      objects.end());
        for (const auto& [index, name] : objects) {
            const std::string id = index >= 0 ? "object-" + std::to_string(index) : std::string("object-none");
            add_kinds(id, index >= 0 ? name : std::string("none"), [index](const Shape& s) { return s.object_index == index; },
                      [](Layer) { return false; });
        }
    } else if (grouping == LayerGrouping::kStyle) {
        std::vector<std::pair<int32_t, std::string>> styles;  // (rule, name)
        for (const Shape& s : d.shapes) {
            const InkStyle ink = ink_of(d, s);
            styles.emplace_back(ink.rule, ink.name);
        }
        std::sort(styles.begin(), styles.end());
        styles.erase(std::unique(styles.begin(), styles.end()), styles.end());
        for (const auto& [rule, name] : styles) {
            add_kinds(name.empty() ? std::string("unstyled") : "style-" + name, name.empty() ? std::string("unstyled") : name,
                      [&d, &name](const Shape& s) { return ink_of(d, s).name == name; }, [](Layer) { return false; });
        }
    } else {
        add_kinds("", "", [](const Shape&) { return true; },
                  [](Layer kind) { return kind != Layer::kHidden && kind != Layer::kIntersection; });
    }
    return layers;
}

}  // namespace inkline::output
