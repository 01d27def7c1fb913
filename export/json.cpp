// SPDX-License-Identifier: MIT
#include "export/json.h"

#include "core/strokes/brush.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <span>
#include <string_view>

namespace inkline::output {
namespace {

using nlohmann::json;

// Pixel coordinates are written to 1e-4 px: well below the 1/8 px bisection precision, and it
// keeps files short. World coordinates keep full double precision.
double round_px(double v) { return std::round(v * 1e4) / 1e4; }

json vec3(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

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

json points_json(const std::vector<glm::dvec2>& points) {
    json out = json::array();
    for (const glm::dvec2& p : points) out.push_back({round_px(p.x), round_px(p.y)});
    return out;
}

json world_json(const std::vector<glm::dvec3>& points) {
    json out = json::array();
    for (const glm::dvec3& p : points) out.push_back(vec3(p));
    return out;
}

// Per-point values rounded to `scale` (1e3: thousandths).
json rounded(const std::vector<double>& values, double scale) {
    json out = json::array();
    for (double v : values) out.push_back(std::round(v * scale) / scale);
    return out;
}

// A line's object, when the frame has objects: its name and glTF node.
void add_object(const core::FrameLines& frame, int32_t object, json& r_stroke) {
    if (frame.objects.empty() || object < 0) return;
    const core::MeshObject& o = frame.objects[size_t(object)];
    r_stroke["object"] = o.name;
    if (o.node >= 0) r_stroke["node"] = o.node;
}

json polyline_strokes(const core::FrameLines& frame) {
    json strokes = json::array();
    for (const core::Polyline& line : frame.polylines) {
        strokes.push_back({{"id", line.id},
                           {"kind", core::line_kind_name(line.kind)},
                           {"closed", line.closed},
                           {"visible", line.visible},
                           {"points", points_json(line.points_px)},
                           {"world", world_json(line.points_world)},
                           {"edges", line.faces.empty() ? line.edges : line.faces}});
        add_object(frame, line.object, strokes.back());
    }
    return strokes;
}

// Seconds and pixels of a write-on, to the microsecond and the thousandth of a pixel.
double write_on_number(double v, double scale) { return std::round(v * scale) / scale; }

json brush_strokes(const core::FrameLines& frame, const core::FrameStrokes& frame_strokes) {
    json strokes = json::array();
    for (size_t k = 0; k < frame_strokes.strokes.size(); ++k) {
        const core::Stroke& s = frame_strokes.strokes[k];
        const core::StrokeGeometry& g = s.geometry;
        json outline = json::array();
        for (const core::Ring& ring : s.outline) outline.push_back(points_json(ring));
        strokes.push_back({{"id", s.id},
                           {"kind", core::line_kind_name(g.kind)},
                           {"closed", g.closed},
                           {"visible", g.visible},
                           {"drawn", s.drawn},
                           {"ends", {core::stroke_end_name(g.ends[0]), core::stroke_end_name(g.ends[1])}},
                           {"points", points_json(g.points_px)},
                           {"world", world_json(g.points_world)},
                           {"edges", s.faces.empty() ? g.edges : s.faces},
                           {"u", rounded(s.u, 1e3)},
                           {"intensity", rounded(s.intensity, 1e4)},
                           {"width", rounded(s.width, 1e3)},
                           {"outline", std::move(outline)}});
        if (!g.bridged.empty()) {
            json bridged = json::array();
            for (size_t b = 0; b < g.bridged.size(); ++b) {
                if (g.bridged[b]) bridged.push_back(b);
            }
            strokes.back()["hidden_segments"] = std::move(bridged);
        }
        json& out = strokes.back();
        out["group"] = s.group;
        out["level"] = s.level;
        out["parent"] = s.parent >= 0 ? json(s.parent) : json(nullptr);
        out["order"] = s.order;
        add_object(frame, g.object, strokes.back());
        if (s.style != 0 && s.style < frame_strokes.styles.size()) {
            strokes.back()["style"] = frame_strokes.styles[s.style].name;
        }
        if (frame_strokes.write_on && k < frame_strokes.write_on->strokes.size()) {
            const core::WriteOnFrame::StrokeProgress& p = frame_strokes.write_on->strokes[k];
            const bool timed = p.start_s >= 0.0;
            strokes.back()["write_on"] = {{"start", timed ? json(write_on_number(p.start_s, 1e6)) : json(nullptr)},
                                          {"end", timed ? json(write_on_number(p.end_s, 1e6)) : json(nullptr)},
                                          {"drawn_px", write_on_number(p.drawn_px, 1e3)},
                                          {"length_px", write_on_number(p.length_px, 1e3)}};
        }
    }
    return strokes;
}

// The tone's dots and hatches are written one by one as text and spliced into the document where
// these marks stand: a frame's dots can run to millions, and as one document (nlohmann's objects)
// they would take many times the memory of their text. User text comes before "tone" in the
// sorted document, so the last occurrence of a mark is the tone's own.
struct Mark {
    const char* value;   // the string the document holds there
    const char* dumped;  // as dump() writes it
};
constexpr Mark kDotsMark{"\x01" "inkline-dots", "\"\\u0001inkline-dots\""};
constexpr Mark kHatchesMark{"\x01" "inkline-hatches", "\"\\u0001inkline-hatches\""};

// A dot: where on the surface (sample, face, barycentric coordinates, world point), where in the
// image, how large, the tone asked for there, and with several inks its ink.
json dot_json(const core::Dot& d, bool inks) {
    json out = {{"sample", d.sample},
            {"face", d.face},
            {"barycentric", vec3(d.barycentric)},
            {"point", json::array({round_px(d.point_px.x), round_px(d.point_px.y)})},
            {"world", vec3(d.point_world)},
            {"radius", round_px(d.radius_px)},
            {"tone", std::round(d.tone * 1e4) / 1e4}};
    if (inks) out["ink"] = d.ink;
    return out;
}

// A hatch: family, plane and level, and per point where in the image, the world point, the mesh
// edge it lies on and the width; with several inks its ink.
json hatch_json(const core::Hatch& h, bool inks) {
    json points = json::array(), world = json::array(), width = json::array();
    for (size_t i = 0; i < h.points_px.size(); ++i) {
        points.push_back(json::array({round_px(h.points_px[i].x), round_px(h.points_px[i].y)}));
        world.push_back(vec3(h.points_world[i]));
        width.push_back(round_px(h.width_px[i]));
    }
    json out = {{"family", h.family},
                {"plane", h.plane},
                {"level", h.level},
                {"points", std::move(points)},
                {"world", std::move(world)},
                {"edges", h.edges},
                {"faces", h.faces},
                {"width", std::move(width)}};
    if (inks) out["ink"] = h.ink;
    return out;
}

json stipple_stats_json(const core::StippleStats& s) {
    return {{"samples", s.samples}, {"considered", s.considered}, {"wanted", s.wanted}, {"inked", s.inked},
            {"occluded", s.occluded}};
}

json hatch_stats_json(const core::HatchStats& s) {
    return {{"faces", s.faces}, {"segments", s.segments}, {"points", s.points}, {"occluded", s.occluded},
            {"inked", s.inked}};
}

// The tone object, its dots and hatches as marks. `stats` are the scene's mode's; where objects
// have modes of their own, `modes` lists those drawn and the other kind's stats follow.
json tone_json(const core::FrameTone& tone) {
    const bool stipple = tone.mode == core::ToneMode::kStipple;
    const bool hatched = tone.has(core::ToneMode::kHatch) || tone.has(core::ToneMode::kCrosshatch);
    json out = {{"mode", core::tone_mode_name(tone.mode)}, {"dots", kDotsMark.value}};
    if (!stipple || hatched) out["hatches"] = kHatchesMark.value;
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

// `text` with the quoted mark (its last occurrence) replaced by a JSON array of `items`, each
// written by `write`.
template <typename Item, typename Write>
std::string splice(std::string text, const Mark& mark, std::span<const Item> items, const Write& write) {
    const std::string_view quoted = mark.dumped;
    const size_t at = text.rfind(quoted);
    if (at == std::string::npos) return text;
    std::string out;
    out.reserve(text.size() + 96 * items.size());
    out.append(text, 0, at);
    out += '[';
    for (size_t i = 0; i < items.size(); ++i) {
        if (i > 0) out += ',';
        out += write(items[i]).dump();
    }
    out += ']';
    out.append(text, at + quoted.size(), std::string::npos);
    return out;
}

}  // namespace

std::string polylines_json(const core::FrameLines& frame, const core::FrameStrokes* frame_strokes,
                           const core::FrameTone* tone) {
    json strokes = frame_strokes ? brush_strokes(frame, *frame_strokes) : polyline_strokes(frame);
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
    json doc = {
        {"format", "inkline.polylines"},
        {"version", 1},
        {"frame", frame.frame},
        {"image", {{"width", frame.image.width}, {"height", frame.image.height}}},
        {"camera", camera_json(frame.camera)},
        {"light", light_json(frame.light)},
        {"strokes", std::move(strokes)},
        {"stats", std::move(stats)}};
    if (frame_strokes && frame_strokes->write_on) {
        const core::WriteOnFrame& w = *frame_strokes->write_on;
        doc["write_on"] = {{"time", write_on_number(w.time_s, 1e6)},
                           {"seconds", w.seconds},
                           {"speed_px_per_s", write_on_number(w.speed_px_s, 1e3)}};
    }
    if (!tone || tone->mode == core::ToneMode::kNone) return doc.dump() + "\n";
    doc["tone"] = tone_json(*tone);
    std::string text = doc.dump();
    const bool inks = tone->inks.size() > 1;
    text = splice(std::move(text), kHatchesMark, std::span<const core::Hatch>(tone->hatches),
                  [&](const core::Hatch& h) { return hatch_json(h, inks); });
    text = splice(std::move(text), kDotsMark, std::span<const core::Dot>(tone->dots),
                  [&](const core::Dot& d) { return dot_json(d, inks); });
    return text + "\n";
}

}  // namespace inkline::output
