// SPDX-License-Identifier: MIT
#include "export/svg.h"

#include "export/internal/number_text.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace inkline::output {
namespace {

// Text for an XML attribute value: markup characters escaped, control characters (which XML 1.0
// does not allow) replaced by '?'.
std::string xml_escaped(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
        }
    }
    return out;
}

class Writer {
  public:
    explicit Writer(int decimals) : decimals_(decimals) {
        for (int i = 0; i < decimals; ++i) unit_ *= 10;
    }

    Writer& operator<<(std::string_view s) {
        out_ += s;
        return *this;
    }
    Writer& operator<<(long v) {
        out_ += std::to_string(v);
        return *this;
    }
    // A number with bounded decimals and no trailing zeros (internal::append_fixed).
    Writer& number(double v) {
        internal::append_fixed(out_, v, decimals_);
        return *this;
    }
    // A count of units of the last decimal (10^-decimals), written as number() writes that
    // value, or with `short_form` without the 0 before the point (-0.5 as -.5): differences of
    // rounded coordinates stay exact.
    Writer& units(long long u, bool short_form = false) {
        internal::append_units(out_, u, decimals_, short_form);
        return *this;
    }
    // The text written so far ends in a number with a decimal point.
    bool ends_in_fraction() const {
        for (size_t i = out_.size(); i-- > 0;) {
            const char c = out_[i];
            if (c == '.') return true;
            if (c < '0' || c > '9') return false;
        }
        return false;
    }
    // Units of the last decimal in v, rounded.
    long long to_units(double v) const { return std::llround(v * double(unit_)); }
    // Units in 1.
    long long unit() const { return (long long)unit_; }
    std::string take() { return std::move(out_); }

  private:
    std::string out_;
    int decimals_;
    unsigned long long unit_ = 1;  // 10^decimals
};

// A closed run of cubic curves in relative commands, every coordinate rounded once to the
// writer's decimals (so relative steps add up exactly): `c` for a curve, `l` for one whose
// control points lie on its chord (within 0.01 px), the command letter only when it changes,
// no 0 before a decimal point and no space where a sign or a second point separates numbers.
void curve_data(Writer& w, const std::vector<core::CubicBezier>& curves, bool first) {
    struct Units {
        long long x, y;
    };
    const auto units = [&](const glm::dvec2& p) { return Units{w.to_units(p.x), w.to_units(p.y)}; };
    char command = 0;
    bool after_command = false;
    const auto step = [&](const Units& from, const Units& to) {
        for (const long long d : {to.x - from.x, to.y - from.y}) {
            const bool starts_with_point = d != 0 && d > -w.unit() && d < w.unit();
            if (!after_command && d >= 0 && !(starts_with_point && w.ends_in_fraction())) w << " ";
            w.units(d, true);
            after_command = false;
        }
    };
    const auto begin = [&](char c) {
        if (c != command) {
            w << std::string_view(&c, 1);
            command = c;
            after_command = true;
        }
    };
    Units at = units(curves.front().p0);
    w << (first ? "M" : " M");
    w.units(at.x) << " ";
    w.units(at.y);
    for (const core::CubicBezier& c : curves) {
        const Units end = units(c.p3);
        const glm::dvec2 chord = c.p3 - c.p0;
        const double length = glm::length(chord);
        const auto off_chord = [&](const glm::dvec2& p) {
            if (!(length > 0.0)) return glm::length(p - c.p0);
            const double t = glm::dot(p - c.p0, chord) / (length * length);
            if (t < 0.0 || t > 1.0) return HUGE_VAL;
            return std::abs(chord.x * (p.y - c.p0.y) - chord.y * (p.x - c.p0.x)) / length;
        };
        if (off_chord(c.p1) <= 0.01 && off_chord(c.p2) <= 0.01) {
            begin('l');
            step(at, end);
        } else {
            begin('c');
            step(at, units(c.p1));
            step(at, units(c.p2));
            step(at, end);
        }
        at = end;
    }
    w << "Z";
}

void path_data(Writer& w, const Shape& shape) {
    bool first = true;
    for (size_t k = 0; k < shape.paths.size(); ++k) {
        if (k < shape.curves.size() && !shape.curves[k].empty()) {
            curve_data(w, shape.curves[k], first);
            first = false;
            continue;
        }
        const std::vector<glm::dvec2>& path = shape.paths[k];
        for (size_t i = 0; i < path.size(); ++i) {
            w << (i == 0 ? (first ? "M" : " M") : " L");
            w.number(path[i].x) << " ";
            w.number(path[i].y);
            first = false;
        }
        if (shape.filled || shape.closed) w << " Z";
    }
}

void metadata(Writer& w, const Drawing& d) {
    auto vec = [&](const glm::dvec3& v) {
        w << "[";
        w.number(v.x) << ",";
        w.number(v.y) << ",";
        w.number(v.z) << "]";
    };
    w << "  <metadata>\n    <inkline:frame number=\"" << long(d.frame) << "\"/>\n    <inkline:camera eye=\"";
    vec(d.camera.eye);
    w << "\" target=\"";
    vec(d.camera.target);
    w << "\" up=\"";
    vec(d.camera.up);
    if (d.camera.ortho_height) {
        w << "\" ortho_height=\"";
        w.number(*d.camera.ortho_height) << "\" near=\"";
    } else {
        w << "\" fov_y_deg=\"";
        w.number(d.camera.fov_y_deg) << "\" near=\"";
    }
    w.number(d.camera.near) << "\" far=\"";
    w.number(d.camera.far) << "\"/>\n  </metadata>\n";
}

const char* cap_name(core::LineCap cap) {
    switch (cap) {
        case core::LineCap::kRound: return "round";
        case core::LineCap::kButt: return "butt";
        case core::LineCap::kSquare: return "square";
    }
    return "round";
}

// The write-on of an animated SVG (SvgOptions::write_on): a mask per timed stroke whose white
// centerline, dashed with one dash as long as the path, is revealed by moving the dash along it;
// the centerline runs on past both ends to cover their caps.
class WriteOn {
  public:
    WriteOn(const Drawing& d, const WriteOnAnimation* animation) : animation_(animation) {
        if (!animation_) return;
        for (const Shape& s : d.shapes) {
            const double width = s.filled ? 0.0 : line_width_of(d, s);
            auto [it, added] = widest_.emplace(s.stroke_id, width);
            if (!added) it->second = std::max(it->second, width);
        }
        for (size_t k = 0; k < animation_->paths.size(); ++k) path_of_[animation_->paths[k].stroke_id] = k;
    }

    // <defs> with the masks of the drawing's timed strokes.
    void masks(Writer& w, const Drawing& d) const {
        if (!animation_) return;
        w << "  <defs>\n";
        for (const WriteOnPath& p : animation_->paths) {
            const auto shape = widest_.find(p.stroke_id);
            if (shape == widest_.end() || p.centerline.size() < 2) continue;
            const double width = std::max(p.width_px, shape->second) + 2.0;
            const double run = 0.5 * width;  // past each end, for its cap
            std::vector<glm::dvec2> c = p.centerline;
            if (p.closed) c.push_back(c.front());
            const glm::dvec2 start = c.front() - run * direction(c, true);
            if (!p.closed) c.push_back(c.back() + run * direction(c, false));
            const double total = p.length_px + (p.closed ? run : 2.0 * run);
            const long id = long(p.stroke_id);
            w << "    <path id=\"write-on-path-" << id << "\" d=\"M";
            w.number(start.x) << " ";
            w.number(start.y);
            for (const glm::dvec2& q : c) {
                w << " L";
                w.number(q.x) << " ";
                w.number(q.y);
            }
            w << "\" pathLength=\"";
            w.number(total) << "\"/>\n    <mask id=\"write-on-" << id << "\" maskUnits=\"userSpaceOnUse\" x=\"0\" y=\"0\" width=\""
                            << long(d.image.width) << "\" height=\"" << long(d.image.height) << "\">\n";
            // The tip thins over the taper as the frames draw it: the mask runs behind it in
            // three widths, each lagging the one narrower.
            const double lag_share[3] = {0.6, 0.25, 0.0}, width_share[3] = {1.0, 0.65, 0.25};
            for (int k = 0; k < 3; ++k) {
                const double lag = std::min(lag_share[k] * p.taper_px, p.length_px);
                tip_mask(w, p, id, total, run, lag, std::max(0.5, width_share[k] * width));
            }
            w << "    </mask>\n";
        }
        w << "  </defs>\n";
    }

    // The end of a shape's <path> element: its mask when timed, else hidden until the drawing
    // is done; "/>" without a write-on.
    std::string end_of(Writer& w, uint32_t stroke_id) const {
        if (!animation_) return "/>\n";
        if (path_of_.count(stroke_id)) {
            w << " mask=\"url(#write-on-" << long(stroke_id) << ")\"";
            return "/>\n";
        }
        Writer at(3);
        at.number(animation_->seconds);
        return "><set attributeName=\"visibility\" to=\"hidden\" dur=\"" + at.take() + "s\"/></path>\n";
    }

  private:
    // One white stroke of a write-on mask along the stroke's path, `lag` px behind the tip: hidden
    // until the stroke starts, then its start's cap, then running on with the tip, whole once the
    // stroke is done.
    static void tip_mask(Writer& w, const WriteOnPath& p, long id, double total, double run, double lag, double width) {
        const double end_s = p.begin_s + p.duration_s;
        const double span = end_s > 0.0 ? end_s : 1e-3;
        const double begin = p.begin_s / span;
        const double moving = p.duration_s > 0.0 ? std::min(1.0, (p.begin_s + p.duration_s * lag / p.length_px) / span) : begin;
        const double done = std::max(moving, 1.0 - 1e-4);
        w << "      <use href=\"#write-on-path-" << id << "\" fill=\"none\" stroke=\"#fff\" stroke-width=\"";
        w.number(width) << "\" stroke-linecap=\"butt\" stroke-linejoin=\"round\" stroke-dasharray=\"";
        w.number(total) << " ";
        w.number(total + 1.0) << "\"><animate attributeName=\"stroke-dashoffset\" dur=\"";
        w.number(span) << "s\" values=\"";
        for (const double offset : {total, total, total - run, total - run, total - run - (p.length_px - lag)}) {
            w.number(offset) << ";";
        }
        w << "0\" keyTimes=\"0";
        for (const double at : {begin, begin, moving, done}) {
            w << ";";
            w.number(at);
        }
        w << ";1\" fill=\"freeze\"/></use>\n";
    }

    // Unit direction of a polyline at its start (leaving it) or end (arriving), from the nearest
    // distinct point.
    static glm::dvec2 direction(const std::vector<glm::dvec2>& c, bool at_start) {
        const size_t n = c.size();
        for (size_t k = 1; k < n; ++k) {
            const glm::dvec2 d = at_start ? c[k] - c[0] : c[n - 1] - c[n - 1 - k];
            const double len = glm::length(d);
            if (len > 0.0) return d / len;
        }
        return {1.0, 0.0};
    }

    const WriteOnAnimation* animation_;
    std::unordered_map<uint32_t, double> widest_;  // stroke id -> widest stroked centerline of its shapes (0: filled)
    std::unordered_map<uint32_t, size_t> path_of_;  // stroke id -> its path in the animation
};

// A kind layer's group and its paths, each line indented by `indent`, the id prefixed with
// `prefix`.
void kind_layer(Writer& w, const Drawing& d, const WriteOn& write_on, const LineLayer& layer, const std::string& indent,
                const std::string& prefix) {
    const char* name = layer_name(layer.kind);
    w << indent << "<g id=\"" << prefix << name << "\" inkscape:groupmode=\"layer\" inkscape:label=\"" << name << "\"";
    if (layer.opacity < 1.0) {
        w << " opacity=\"";
        w.number(layer.opacity) << "\"";
    }
    w << ">\n";
    for (const uint32_t index : layer.shapes) {
        const Shape& s = d.shapes[index];
        const InkStyle ink = ink_of(d, s);
        w << indent << "  <path id=\"stroke-" << long(s.stroke_id) << "\"";
        if (!s.object.empty()) w << " data-object=\"" << xml_escaped(s.object) << "\"";
        if (!ink.name.empty()) w << " data-style=\"" << xml_escaped(ink.name) << "\"";
        if (d.drawing_order) {
            w << " data-group=\"" << long(s.group) << "\" data-level=\"" << long(s.level) << "\"";
            if (s.parent >= 0) w << " data-parent=\"" << long(s.parent) << "\"";
            w << " data-order=\"" << long(s.order) << "\"";
        }
        w << " d=\"";
        path_data(w, s);
        w << "\"";
        if (const double own = shape_opacity(d, s, layer.opacity); own < 1.0) {
            w << " opacity=\"";
            w.number(own) << "\"";
        }
        const std::string end = write_on.end_of(w, s.stroke_id);
        if (s.filled) {
            w << " fill=\"" << color_of(d, s) << "\" stroke=\"none\"" << end;
            continue;
        }
        w << " fill=\"none\" stroke=\"" << ink.color << "\" stroke-width=\"";
        w.number(line_width_of(d, s)) << "\" stroke-linecap=\"" << cap_name(ink.cap) << "\" stroke-linejoin=\"round\"";
        if (const std::vector<double> dashes = dashes_of(d, s); !dashes.empty()) {
            w << " stroke-dasharray=\"";
            for (size_t k = 0; k < dashes.size(); ++k) {
                if (k > 0) w << " ";
                w.number(dashes[k]);
            }
            w << "\"";
            if (const double offset = dash_offset_of(d, s); offset != 0.0) {
                w << " stroke-dashoffset=\"";
                w.number(offset) << "\"";
            }
        }
        w << end;
    }
    w << indent << "</g>\n";
}

// The line layers as line_layers groups them: the kind layers at the top, or inside one layer
// per object (data-object) or per style (data-style), their ids prefixed with the parent's.
void line_groups(Writer& w, const Drawing& d, const WriteOn& write_on, LayerGrouping grouping) {
    const std::vector<LineLayer> layers = line_layers(d, grouping);
    const char* data = grouping == LayerGrouping::kObject ? "data-object" : "data-style";
    for (size_t i = 0; i < layers.size(); ++i) {
        const LineLayer& layer = layers[i];
        if (layer.parent_id.empty()) {
            kind_layer(w, d, write_on, layer, "  ", "");
            continue;
        }
        const bool opens = i == 0 || layers[i - 1].parent_id != layer.parent_id;
        const bool closes = i + 1 == layers.size() || layers[i + 1].parent_id != layer.parent_id;
        if (opens) {
            const std::string label = xml_escaped(layer.parent_label);
            w << "  <g id=\"" << xml_escaped(layer.parent_id) << "\" inkscape:groupmode=\"layer\" inkscape:label=\""
              << label << "\"";
            if (layer.parent_id != "object-none" && layer.parent_id != "unstyled") w << " " << data << "=\"" << label << "\"";
            w << ">\n";
        }
        kind_layer(w, d, write_on, layer, "    ", xml_escaped(layer.parent_id) + "-");
        if (closes) w << "  </g>\n";
    }
}

// A tone group's fill, opacity and style name, as attributes.
void ink_attributes(Writer& w, const std::string& color, double opacity, const std::string& style) {
    if (!style.empty()) w << " data-style=\"" << xml_escaped(style) << "\"";
    w << " fill=\"" << color << "\"";
    if (opacity < 1.0) {
        w << " opacity=\"";
        w.number(opacity) << "\"";
    }
}

// The marks of one ink (all of them when the layer has one): a circle per dot and a filled path
// per hatch.
void tone_marks(Writer& w, const ToneLayer& tone, size_t ink, const char* indent) {
    for (const ToneDot& dot : tone.dots_of(ink)) {
        w << indent << "<circle data-sample=\"" << long(dot.sample) << "\" cx=\"";
        w.number(dot.center_px.x) << "\" cy=\"";
        w.number(dot.center_px.y) << "\" r=\"";
        w.number(dot.radius_px) << "\"/>\n";
    }
    for (const ToneHatch& hatch : tone.hatches_of(ink)) {
        w << indent << "<path data-family=\"" << long(hatch.family) << "\" data-plane=\"" << std::to_string(hatch.plane)
          << "\" d=\"";
        bool first = true;
        for (const std::vector<glm::dvec2>& ring : hatch.rings) {
            for (size_t i = 0; i < ring.size(); ++i) {
                w << (i == 0 ? (first ? "M" : " M") : " L");
                w.number(ring[i].x) << " ";
                w.number(ring[i].y);
                first = false;
            }
            if (!ring.empty()) w << " Z";
        }
        w << "\"/>\n";
    }
}

// The tone layer, under the lines, in the layer's colour, the layer's opacity on the group
// (overlapping marks do not darken each other); with several inks, a group per ink in it.
void tone_group(Writer& w, const ToneLayer& tone) {
    if (tone.mode == core::ToneMode::kNone) return;
    w << "  <g id=\"tone\" inkscape:groupmode=\"layer\" inkscape:label=\"tone\" data-mode=\""
      << core::tone_mode_name(tone.mode) << "\"";
    if (tone.inks.empty()) {
        ink_attributes(w, tone.color, tone.opacity, tone.style);
        w << ">\n";
        tone_marks(w, tone, 0, "    ");
    } else {
        w << ">\n";
        for (size_t ink = 0; ink < tone.inks.size(); ++ink) {
            w << "    <g id=\"tone-ink-" << long(ink + 1) << "\"";
            ink_attributes(w, tone.inks[ink].color, tone.inks[ink].opacity, tone.inks[ink].style);
            w << ">\n";
            tone_marks(w, tone, ink, "      ");
            w << "    </g>\n";
        }
    }
    w << "  </g>\n";
}

}  // namespace

std::string svg_document(const Drawing& d, const SvgOptions& options) {
    Writer w(options.decimals);
    const long width = d.image.width, height = d.image.height;
    w << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\""
      << " xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\""
      << " xmlns:inkline=\"https://inkline.invalid/ns/1\""
      << " width=\"" << width << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " " << height << "\">\n";
    metadata(w, d);
    const WriteOn write_on(d, options.write_on);
    write_on.masks(w, d);
    if (d.style.background) {
        w << "  <rect id=\"background\" width=\"" << width << "\" height=\"" << height << "\" fill=\""
          << *d.style.background << "\"/>\n";
    }
    tone_group(w, d.tone);
    line_groups(w, d, write_on, options.layers);
    w << "</svg>\n";
    return w.take();
}

}  // namespace inkline::output
