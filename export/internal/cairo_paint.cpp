// SPDX-License-Identifier: MIT
#include "export/internal/cairo_paint.h"

#include "core/error.h"

#include <algorithm>
#include <new>
#include <numbers>

namespace inkline::output::internal {
namespace {

void trace_path(cairo_t* cr, const Shape& shape) {
    cairo_new_path(cr);
    for (size_t k = 0; k < shape.paths.size(); ++k) {
        if (k < shape.curves.size() && !shape.curves[k].empty()) {
            cairo_move_to(cr, shape.curves[k].front().p0.x, shape.curves[k].front().p0.y);
            for (const core::CubicBezier& c : shape.curves[k]) cairo_curve_to(cr, c.p1.x, c.p1.y, c.p2.x, c.p2.y, c.p3.x, c.p3.y);
            cairo_close_path(cr);
            continue;
        }
        const std::vector<glm::dvec2>& path = shape.paths[k];
        for (size_t i = 0; i < path.size(); ++i) (i == 0 ? cairo_move_to : cairo_line_to)(cr, path[i].x, path[i].y);
        if (shape.filled || shape.closed) cairo_close_path(cr);
    }
}

// The tone's dots and hatches of one ink (all of them when the layer has one), filled together
// with the nonzero rule (the dots are all turned the same way, so it fills their union) and
// composited as one group, as the SVG's tone layer (or the ink's group in it) is.
void paint_tone_ink(cairo_t* cr, const ToneLayer& tone, size_t ink) {
    const bool all = tone.inks.empty();
    const std::string& color = all ? tone.color : tone.inks[ink].color;
    const Rgb rgb = parse_color(color, "tone color");
    cairo_push_group(cr);
    cairo_set_source_rgb(cr, rgb.r, rgb.g, rgb.b);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
    cairo_new_path(cr);
    for (const ToneDot& dot : tone.dots_of(ink)) {
        if (!(dot.radius_px > 0.0)) continue;
        cairo_new_sub_path(cr);
        cairo_arc(cr, dot.center_px.x, dot.center_px.y, dot.radius_px, 0.0, 2.0 * std::numbers::pi);
    }
    cairo_fill(cr);
    // Each hatch on its own, so that a hatch whose ring turns the other way round than its
    // neighbour's does not cancel it where they overlap.
    for (const ToneHatch& hatch : tone.hatches_of(ink)) {
        for (const std::vector<glm::dvec2>& ring : hatch.rings) {
            for (size_t i = 0; i < ring.size(); ++i) (i == 0 ? cairo_move_to : cairo_line_to)(cr, ring[i].x, ring[i].y);
            cairo_close_path(cr);
        }
        cairo_fill(cr);
    }
    cairo_pop_group_to_source(cr);
    cairo_paint_with_alpha(cr, all ? tone.opacity : tone.inks[ink].opacity);
}

void paint_tone(cairo_t* cr, const ToneLayer& tone) {
    if (tone.mode == core::ToneMode::kNone || (tone.dots.empty() && tone.hatches.empty())) return;
    for (size_t ink = 0; ink < std::max<size_t>(1, tone.inks.size()); ++ink) paint_tone_ink(cr, tone, ink);
}

// Saves the state and sets what every part of a drawing is painted with: clipped to the image,
// round joins, the nonzero rule; the background first where `part` is the background.
void begin_painting(cairo_t* cr, const Drawing& d, Part part) {
    cairo_save(cr);
    cairo_rectangle(cr, 0, 0, d.image.width, d.image.height);
    cairo_clip(cr);
    if (part == Part::kBackground && d.style.background) {
        const Rgb bg = parse_color(*d.style.background, "background");
        cairo_set_source_rgb(cr, bg.r, bg.g, bg.b);
        cairo_paint(cr);
    }
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
}

// A layer's shapes, composited as a group so that its opacity applies to the layer, not per path.
void paint_line_layer(cairo_t* cr, const Drawing& d, const LineLayer& layer) {
    cairo_push_group(cr);
    for (const uint32_t index : layer.shapes) {
        const Shape& s = d.shapes[index];
        const InkStyle ink = ink_of(d, s);
        const Rgb rgb = parse_color(color_of(d, s), "color");
        cairo_set_source_rgba(cr, rgb.r, rgb.g, rgb.b, shape_opacity(d, s, layer.opacity));
        trace_path(cr, s);
        if (s.filled) {
            cairo_fill(cr);
            continue;
        }
        const std::vector<double> dashes = dashes_of(d, s);
        cairo_set_dash(cr, dashes.empty() ? nullptr : dashes.data(), int(dashes.size()), dash_offset_of(d, s));
        cairo_set_line_cap(cr, ink.cap == core::LineCap::kButt     ? CAIRO_LINE_CAP_BUTT
                               : ink.cap == core::LineCap::kSquare ? CAIRO_LINE_CAP_SQUARE
                                                                   : CAIRO_LINE_CAP_ROUND);
        cairo_set_line_width(cr, line_width_of(d, s));
        cairo_stroke(cr);
    }
    cairo_pop_group_to_source(cr);
    cairo_paint_with_alpha(cr, layer.opacity);
}

}  // namespace

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
    try {
        static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    } catch (const std::exception&) {  // no exception may cross Cairo's C frames
        return CAIRO_STATUS_NO_MEMORY;
    }
    return CAIRO_STATUS_SUCCESS;
}

void check_cairo(cairo_status_t status, const std::string& what) {
    switch (status) {
    case CAIRO_STATUS_SUCCESS:
        return;
    case CAIRO_STATUS_NO_MEMORY:
        throw std::bad_alloc();
    case CAIRO_STATUS_INVALID_SIZE:
    case CAIRO_STATUS_INVALID_STRING:
    case CAIRO_STATUS_INVALID_MATRIX:
    case CAIRO_STATUS_INVALID_DASH:
        throw InputError(what + ": " + cairo_status_to_string(status));
    default:
        throw OutputError(what + ": " + cairo_status_to_string(status));
    }
}

void check_cairo(cairo_t* cr, const std::string& what) {
    check_cairo(cairo_status(cr), what);
    check_cairo(cairo_surface_status(cairo_get_target(cr)), what);
}

void paint_drawing(cairo_t* cr, const Drawing& d) {
    begin_painting(cr, d, Part::kBackground);
    paint_tone(cr, d.tone);
    for (const LineLayer& layer : line_layers(d, LayerGrouping::kKind)) paint_line_layer(cr, d, layer);
    cairo_restore(cr);
}

void paint_part(cairo_t* cr, const Drawing& d, Part part, const LineLayer* layer) {
    begin_painting(cr, d, part);
    if (part == Part::kTone) paint_tone(cr, d.tone);
    if (part == Part::kLines && layer != nullptr) paint_line_layer(cr, d, *layer);
    cairo_restore(cr);
}

}  // namespace inkline::output::internal
