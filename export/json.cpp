// SPDX-License-Identifier: MIT
#include "export/json.h"

#include <nlohmann/json.hpp>

#include <cmath>

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

json per_kind(const auto& values, auto transform) {
    json out = json::object();
    for (core::LineKind kind : core::kAllLineKinds) {
        out[core::line_kind_name(kind)] = transform(values[size_t(kind)]);
    }
    return out;
}

}  // namespace

std::string polylines_json(const core::FrameLines& frame) {
    json strokes = json::array();
    for (const core::Polyline& line : frame.strokes) {
        json points = json::array();
        for (const glm::dvec2& p : line.points_px) points.push_back({round_px(p.x), round_px(p.y)});
        json world = json::array();
        for (const glm::dvec3& p : line.points_world) world.push_back(vec3(p));
        strokes.push_back({{"id", line.id},
                           {"kind", core::line_kind_name(line.kind)},
                           {"closed", line.closed},
                           {"visible", line.visible},
                           {"points", std::move(points)},
                           {"world", std::move(world)},
                           {"edges", line.edges}});
    }
    json ms = json::object();
    for (const auto& [stage, value] : frame.stats.ms) ms[stage] = std::round(value * 1000.0) / 1000.0;

    const core::FrameStats& s = frame.stats;
    const json doc = {
        {"format", "inkline.polylines"},
        {"version", 1},
        {"frame", frame.frame},
        {"image", {{"width", frame.image.width}, {"height", frame.image.height}}},
        {"camera",
         {{"eye", vec3(frame.camera.eye)},
          {"target", vec3(frame.camera.target)},
          {"up", vec3(frame.camera.up)},
          {"fov_y_deg", frame.camera.fov_y_deg},
          {"near", frame.camera.near},
          {"far", frame.camera.far}}},
        {"light", light_json(frame.light)},
        {"strokes", std::move(strokes)},
        {"stats",
         {{"faces", s.faces},
          {"edges", s.edges},
          {"edges_tested", s.edges_tested},
          {"faces_tested", s.faces_tested},
          {"feature_edges", per_kind(s.feature_edges, [](size_t n) { return n; })},
          {"visible_length_px", per_kind(s.visible_length_px, [](double v) { return std::round(v * 1000.0) / 1000.0; })},
          {"ms", std::move(ms)}}}};
    return doc.dump() + "\n";
}

}  // namespace inkline::output
