// SPDX-License-Identifier: MIT
#include "export/json.h"

#include "core/strokes/brush.h"

#include <nlohmann/json.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <concepts>
#include <string>
#include <string_view>
#include <vector>

namespace inkline::output {
namespace {

using nlohmann::json;

// Pixel coordinates are written to 1e-4 px: well below the 1/8 px bisection precision, and it
// keeps files short. World coordinates keep full double precision.
double round_px(double v) { return std::round(v * 1e4) / 1e4; }

json vec3(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

// Appends JSON text exactly as nlohmann::json::dump() writes the same values: no spaces, integers
// in decimal, doubles as nlohmann's own shortest round-trip digits (not finite: null), strings
// with its escaping. A frame's strokes and tone marks, most of a file, are written this way
// rather than built as nlohmann values first: the same bytes in a fraction of the time and memory.
// The digits come from nlohmann::detail::to_chars, the function dump() itself calls (a detail
// of the library, not its interface: tests/export/json_test.cpp checks the text against dump()).
class Text {
  public:
    explicit Text(std::string& out) : out_(out) {}

    Text& raw(std::string_view s) {
        out_ += s;
        return *this;
    }
    Text& number(double v) {
        if (!std::isfinite(v)) return raw("null");
        std::array<char, 64> digits;  // as nlohmann's serializer's buffer
        const char* end = nlohmann::detail::to_chars(digits.data(), digits.data() + digits.size(), v);
        out_.append(digits.data(), size_t(end - digits.data()));
        return *this;
    }
    template <std::integral T>
    Text& number(T v) {
        std::array<char, 24> digits;
        const char* end = std::to_chars(digits.data(), digits.data() + digits.size(), v).ptr;
        out_.append(digits.data(), size_t(end - digits.data()));
        return *this;
    }
    Text& boolean(bool v) { return raw(v ? "true" : "false"); }
    Text& string(std::string_view v) { return raw(json(std::string(v)).dump()); }
    // [x,y] rounded as image coordinates are.
    Text& px(const glm::dvec2& p) { return raw("[").number(round_px(p.x)).raw(",").number(round_px(p.y)).raw("]"); }
    Text& vec3(const glm::dvec3& v) {
        return raw("[").number(v.x).raw(",").number(v.y).raw(",").number(v.z).raw("]");
    }
    // [each(item),...]
    template <typename Items, typename Each>
    Text& array(const Items& items, Each each) {
        raw("[");
        bool first = true;
        for (const auto& item : items) {
            if (!first) raw(",");
            first = false;
            each(item);
        }
        return raw("]");
    }
    template <typename T>
    Text& numbers(const std::vector<T>& values) {
        return array(values, [&](const T& v) { number(v); });
    }
    // Per-point values rounded to `scale` (1e3: thousandths).
    Text& rounded(const std::vector<double>& values, double scale) {
        return array(values, [&](double v) { number(std::round(v * scale) / scale); });
    }
    Text& points(const std::vector<glm::dvec2>& points) {
        return array(points, [&](const glm::dvec2& p) { px(p); });
    }
    Text& world(const std::vector<glm::dvec3>& points) {
        return array(points, [&](const glm::dvec3& p) { vec3(p); });
    }

  private:
    std::string& out_;
};

json light_json(const core::Light& light) {
    if (light.is_point) return {{"position", vec3(light.position)}};
    return {{"direction", vec3(light.direction)}};
}

// An orthographic camera gives its view height instead of a field of view.
json camera_json(const core::Camera& camera) {
    json out = {{"eye", vec3(camera.eye)},
                {"target", vec3(camera.target)},
                {"up", vec3(camera.up)},
                {"near", camera.near},
                {"far", camera.far}};
    if (camera.ortho_height) {
        out["ortho_height"] = *camera.ortho_height;
    } else {
        out["fov_y_deg"] = camera.fov_y_deg;
    }
    return out;
}

// Per line kind; intersection only when the frame traced intersection lines.
json per_kind(const auto& values, bool intersections, auto transform) {
    json out = json::object();
    for (core::LineKind kind : core::kAllLineKinds) {
        if (kind == core::LineKind::kIntersection && !intersections) continue;
        out[core::line_kind_name(kind)] = transform(values[size_t(kind)]);
    }
    return out;
}

// A line's object, when the frame has objects: its glTF node and name (the keys in order).
void add_object(const core::FrameLines& frame, int32_t object, Text& out) {
    if (frame.objects.empty() || object < 0) return;
    const core::MeshObject& o = frame.objects[size_t(object)];
    if (o.node >= 0) out.raw(",\"node\":").number(o.node);
    out.raw(",\"object\":").string(o.name);
}

void polyline_strokes(const core::FrameLines& frame, Text& out) {
    out.array(frame.polylines, [&](const core::Polyline& line) {
        out.raw("{\"closed\":").boolean(line.closed);
        out.raw(",\"edges\":").numbers(line.faces.empty() ? line.edges : line.faces);
        out.raw(",\"id\":").number(line.id);
        out.raw(",\"kind\":").string(core::line_kind_name(line.kind));
        add_object(frame, line.object, out);
        out.raw(",\"points\":").points(line.points_px);
        out.raw(",\"visible\":").boolean(line.visible);
        out.raw(",\"world\":").world(line.points_world).raw("}");
    });
}

// Seconds and pixels of a write-on, to the microsecond and the thousandth of a pixel.
double write_on_number(double v, double scale) { return std::round(v * scale) / scale; }

void brush_strokes(const core::FrameLines& frame, const core::FrameStrokes& frame_strokes, Text& out) {
    const std::vector<core::Stroke>& strokes = frame_strokes.strokes;
    out.raw("[");
    for (size_t k = 0; k < strokes.size(); ++k) {
        const core::Stroke& s = strokes[k];
        const core::StrokeGeometry& g = s.geometry;
        if (k > 0) out.raw(",");
        out.raw("{\"closed\":").boolean(g.closed);
        out.raw(",\"drawn\":").boolean(s.drawn);
        out.raw(",\"edges\":").numbers(s.faces.empty() ? g.edges : s.faces);
        out.raw(",\"ends\":[").string(core::stroke_end_name(g.ends[0])).raw(",");
        out.string(core::stroke_end_name(g.ends[1])).raw("]");
        out.raw(",\"group\":").number(s.group);
        if (!g.bridged.empty()) {
            out.raw(",\"hidden_segments\":[");
            bool first = true;
            for (size_t b = 0; b < g.bridged.size(); ++b) {
                if (!g.bridged[b]) continue;
                if (!first) out.raw(",");
                first = false;
                out.number(b);
            }
            out.raw("]");
        }
        out.raw(",\"id\":").number(s.id);
        out.raw(",\"intensity\":").rounded(s.intensity, 1e4);
        out.raw(",\"kind\":").string(core::line_kind_name(g.kind));
        out.raw(",\"level\":").number(s.level);
        add_object(frame, g.object, out);
        out.raw(",\"order\":").number(s.order);
        out.raw(",\"outline\":").array(s.outline, [&](const core::Ring& ring) { out.points(ring); });
        out.raw(",\"parent\":");
        if (s.parent >= 0) {
            out.number(s.parent);
        } else {
            out.raw("null");
        }
        out.raw(",\"points\":").points(g.points_px);
        if (s.style != 0 && s.style < frame_strokes.styles.size()) {
            out.raw(",\"style\":").string(frame_strokes.styles[s.style].name);
        }
        out.raw(",\"u\":").rounded(s.u, 1e3);
        out.raw(",\"visible\":").boolean(g.visible);
        out.raw(",\"width\":").rounded(s.width, 1e3);
        out.raw(",\"world\":").world(g.points_world);
        if (frame_strokes.write_on && k < frame_strokes.write_on->strokes.size()) {
            const core::WriteOnFrame::StrokeProgress& p = frame_strokes.write_on->strokes[k];
            const bool timed = p.start_s >= 0.0;
            const auto time = [&](double seconds) -> Text& {
                return timed ? out.number(write_on_number(seconds, 1e6)) : out.raw("null");
            };
            out.raw(",\"write_on\":{\"drawn_px\":").number(write_on_number(p.drawn_px, 1e3));
            out.raw(",\"end\":");
            time(p.end_s).raw(",\"length_px\":").number(write_on_number(p.length_px, 1e3)).raw(",\"start\":");
            time(p.start_s).raw("}");
        }
        out.raw("}");
    }
    out.raw("]");
}

// A dot: where on the surface (sample, face, barycentric coordinates, world point), where in the
// image, how large, the tone asked for there, and with several inks its ink.
void dot_text(const core::Dot& d, bool inks, Text& out) {
    out.raw("{\"barycentric\":").vec3(d.barycentric);
    out.raw(",\"face\":").number(d.face);
    if (inks) out.raw(",\"ink\":").number(d.ink);
    out.raw(",\"point\":").px(d.point_px);
    out.raw(",\"radius\":").number(round_px(d.radius_px));
    out.raw(",\"sample\":").number(d.sample);
    out.raw(",\"tone\":").number(std::round(d.tone * 1e4) / 1e4);
    out.raw(",\"world\":").vec3(d.point_world).raw("}");
}

// A hatch: family, plane and level, and per point where in the image, the world point, the mesh
// edge it lies on and the width; with several inks its ink.
void hatch_text(const core::Hatch& h, bool inks, Text& out) {
    const size_t n = h.points_px.size();
    out.raw("{\"edges\":").numbers(h.edges);
    out.raw(",\"faces\":").numbers(h.faces);
    out.raw(",\"family\":").number(h.family);
    if (inks) out.raw(",\"ink\":").number(h.ink);
    out.raw(",\"level\":").number(h.level);
    out.raw(",\"plane\":").number(h.plane);
    out.raw(",\"points\":").points(h.points_px);
    out.raw(",\"width\":[");
    for (size_t i = 0; i < n; ++i) (i > 0 ? out.raw(",") : out).number(round_px(h.width_px[i]));
    out.raw("],\"world\":[");
    for (size_t i = 0; i < n; ++i) (i > 0 ? out.raw(",") : out).vec3(h.points_world[i]);
    out.raw("]}");
}

json stipple_stats_json(const core::StippleStats& s) {
    return {{"samples", s.samples}, {"considered", s.considered}, {"wanted", s.wanted}, {"inked", s.inked},
            {"occluded", s.occluded}};
}

json hatch_stats_json(const core::HatchStats& s) {
    return {{"faces", s.faces}, {"segments", s.segments}, {"points", s.points}, {"occluded", s.occluded},
            {"inked", s.inked}};
}

// The tone object without its dots and hatches (null where they stand). `stats` are the scene's
// mode's; where objects have modes of their own, `modes` lists those drawn and the other kind's
// stats follow.
json tone_json(const core::FrameTone& tone) {
    const bool stipple = tone.mode == core::ToneMode::kStipple;
    const bool hatched = tone.has(core::ToneMode::kHatch) || tone.has(core::ToneMode::kCrosshatch);
    json out = {{"mode", core::tone_mode_name(tone.mode)}, {"dots", nullptr}};
    if (!stipple || hatched) out["hatches"] = nullptr;
    out["stats"] = stipple ? stipple_stats_json(tone.stipple_stats) : hatch_stats_json(tone.hatch_stats);
    if (tone.modes.size() > 1 || (tone.modes.size() == 1 && tone.modes.front() != tone.mode)) {
        json modes = json::array();
        for (const core::ToneMode m : tone.modes) modes.push_back(core::tone_mode_name(m));
        out["modes"] = std::move(modes);
        if (stipple && hatched) out["hatch_stats"] = hatch_stats_json(tone.hatch_stats);
        if (!stipple && tone.has(core::ToneMode::kStipple)) {
            out["stipple_stats"] = stipple_stats_json(tone.stipple_stats);
        }
    }
    if (!tone.inks.empty()) {
        json inks = json::array();
        for (const core::ToneInk& ink : tone.inks) {
            inks.push_back({{"color", core::color_hex(ink.color)}, {"opacity", ink.opacity}, {"style", ink.style}});
        }
        out["inks"] = std::move(inks);
    }
    return out;
}

// An object's members in dump() order (by key), each as dump() writes it, except those `write`
// writes itself (it returns false for the rest).
template <typename Write>
void write_object(const json& object, Text& out, const Write& write) {
    out.raw("{");
    bool first = true;
    for (const auto& [key, value] : object.items()) {
        out.raw(first ? "" : ",").string(key).raw(":");
        first = false;
        if (!write(key, out)) out.raw(value.dump());
    }
    out.raw("}");
}

}  // namespace

std::string polylines_json(const core::FrameLines& frame, const core::FrameStrokes* frame_strokes,
                           const core::FrameTone* tone) {
    json ms = json::object();
    for (const auto& [stage, value] : frame.stats.ms) ms[stage] = std::round(value * 1000.0) / 1000.0;

    const core::FrameStats& s = frame.stats;
    json stats = {{"faces", s.faces},
                  {"edges", s.edges},
                  {"edges_tested", s.edges_tested},
                  {"faces_tested", s.faces_tested},
                  {"silhouette_edges", s.silhouette_edges},
                  {"feature_edges", per_kind(s.feature_edges, s.intersections, [](size_t n) { return n; })},
                  {"visible_length_px", per_kind(s.visible_length_px, s.intersections, [](double v) { return std::round(v * 1000.0) / 1000.0; })},
                  {"ms", std::move(ms)}};
    if (!s.tracker.empty()) stats["tracker"] = s.tracker;
    if (!s.visibility.empty()) stats["visibility"] = {{"mode", s.visibility}, {"reason", s.visibility_reason}};
    if (!s.gl_context.empty()) stats["gl_context"] = s.gl_context;
    if (frame_strokes) {
        const core::StrokeStats& t = frame_strokes->stats;
        stats["strokes"] = {{"pure_strokes", t.pure_strokes},
                            {"drawn", t.drawn},
                            {"bridges", t.bridges},
                            {"inherited_ids", t.inherited},
                            {"inherited_length_fraction",
                             t.visible_length_px > 0.0 ? std::round(1e4 * t.inherited_length_px / t.visible_length_px) / 1e4 : 1.0},
                            {"max_deviation_px", std::round(t.max_deviation_px * 1e4) / 1e4}};
    }
    // The strokes and the tone stand as null here and are written as text in their place.
    json doc = {
        {"format", "inkline.polylines"},
        {"version", 1},
        {"frame", frame.frame},
        {"image", {{"width", frame.image.width}, {"height", frame.image.height}}},
        {"camera", camera_json(frame.camera)},
        {"light", light_json(frame.light)},
        {"strokes", nullptr},
        {"stats", std::move(stats)}};
    if (frame_strokes && frame_strokes->write_on) {
        const core::WriteOnFrame& w = *frame_strokes->write_on;
        doc["write_on"] = {{"time", write_on_number(w.time_s, 1e6)},
                           {"seconds", w.seconds},
                           {"speed_px_per_s", write_on_number(w.speed_px_s, 1e3)}};
    }
    const bool toned = tone && tone->mode != core::ToneMode::kNone;
    if (toned) doc["tone"] = nullptr;

    std::string text;
    Text out(text);
    write_object(doc, out, [&](const std::string& key, Text& o) {
        if (key == "strokes") {
            if (frame_strokes) {
                brush_strokes(frame, *frame_strokes, o);
            } else {
                polyline_strokes(frame, o);
            }
            return true;
        }
        if (key != "tone") return false;
        const bool inks = tone->inks.size() > 1;
        write_object(tone_json(*tone), o, [&](const std::string& tone_key, Text& t) {
            if (tone_key == "dots") {
                t.array(tone->dots, [&](const core::Dot& d) { dot_text(d, inks, t); });
                return true;
            }
            if (tone_key == "hatches") {
                t.array(tone->hatches, [&](const core::Hatch& h) { hatch_text(h, inks, t); });
                return true;
            }
            return false;
        });
        return true;
    });
    return text + "\n";
}

}  // namespace inkline::output
