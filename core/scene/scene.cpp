// SPDX-License-Identifier: MIT
#include "core/scene/scene.h"

#include "core/error.h"
#include "core/scene/frame_pattern.h"
#include "core/scene/gltf_shot.h"

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtx/rotate_vector.hpp>
#include <nlohmann/json.hpp>

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <set>
#include <span>
#include <sstream>

namespace inkline::core {
namespace {

using nlohmann::json;

// Below this, two unit directions count as parallel (the up vector along the view direction).
constexpr double kParallelSine = 1e-6;

// The eye counts as on the target when their distance is below this fraction of their
// magnitude: the view direction would have fewer than a few significant digits.
constexpr double kCoincidentRatio = 1e-12;

// Characters of a file name an error message keeps (quote_value): enough for a long path.
constexpr size_t kMaxQuotedPathChars = 160;

// The largest coordinate of a camera, rotation centre or light position, world units. Ten times
// the mesh limit (kMaxCoordinate, 1e18): a camera stands back from the mesh it frames (the bare
// mesh turntable puts it at up to about 8e18). The occlusion tests clip their rays to the mesh
// (core/visibility/visibility.h), so no distance reaches Embree's float ray range, and every product the
// camera matrices form stays far inside double and, for the GL pass, float range.
constexpr double kMaxWorldCoordinate = 1e19;

// The narrowest field of view, degrees: 1/tan of half of it (about 1.1e5) times a coordinate at
// the limit keeps clip-space values inside float range for the GL pass.
constexpr double kMinFovDeg = 1e-3;

// The widest orthographic view, world units (the narrowest: kMinOrthoHeight, scene.h).
constexpr double kMaxOrthoHeight = kMaxWorldCoordinate;

// v scaled to unit length without overflow or underflow of its squared length; nullopt for the
// zero vector. Lengths whose square is a normal double are divided directly, so ordinary
// directions normalise to the same bits as glm::normalize.
std::optional<glm::dvec3> unit_direction(const glm::dvec3& v) {
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(largest > 0.0)) return std::nullopt;
    if (largest > 1e-150 && largest < 1e150) return glm::normalize(v);
    return glm::normalize(v / largest);
}

// Shortest decimal form of a value for messages ("1e+20", "0.5").
std::string number_text(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

// Largest accepted brush width or smoothing, px: wider strokes than this are a typo, and the
// stroke stages scale their search windows with these values.
constexpr double kMaxBrushWidthPx = 256.0;

// Reads one JSON object strictly: every key is known, every value has the right type, and
// every error names the file and the dotted key path.
class Reader {
  public:
    Reader(std::string file, const json& value, std::string path)
        : file_(quote_value(file, kMaxQuotedPathChars)), value_(value), path_(std::move(path)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        throw InputError(file_ + ": key '" + join(key) + "': " + message);
    }

    void expect_object() const {
        if (!value_.is_object()) fail("", "expected an object");
    }

    void allow_only(std::initializer_list<const char*> keys) const {
        allow_only(std::span<const char* const>(keys.begin(), keys.size()));
    }
    void allow_only(std::span<const char* const> keys) const {
        expect_object();
        const std::set<std::string> allowed(keys.begin(), keys.end());
        for (const auto& item : value_.items()) {
            if (!allowed.count(item.key())) {
                std::string list;
                for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
                fail(quote_value(item.key()), "unknown key (allowed here: " + list + ")");
            }
        }
    }

    bool has(const std::string& key) const { return value_.contains(key); }
    const json& at(const std::string& key) const {
        if (!value_.contains(key)) fail(key, "is required");
        return value_.at(key);
    }
    Reader child(const std::string& key) const { return Reader(file_, at(key), join(key)); }
    // Element i of an array value.
    Reader item(size_t i) const { return Reader(file_, value_.at(i), path_ + "[" + std::to_string(i) + "]"); }

    double number(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_number()) fail(key, "expected a number, got " + type_name(v));
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail(key, "must be finite");
        return d;
    }
    double number_or(const std::string& key, double fallback) const {
        return has(key) ? number(key) : fallback;
    }
    int integer(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_number_integer()) fail(key, "expected an integer, got " + type_name(v));
        const auto i = v.get<int64_t>();
        if (i < -1000000000 || i > 1000000000) fail(key, "out of range");
        return int(i);
    }
    bool boolean_or(const std::string& key, bool fallback) const {
        if (!has(key)) return fallback;
        const json& v = at(key);
        if (!v.is_boolean()) fail(key, "expected true or false, got " + type_name(v));
        return v.get<bool>();
    }
    std::string string(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_string()) fail(key, "expected a string, got " + type_name(v));
        return v.get<std::string>();
    }
    glm::dvec3 vec3(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers");
        glm::dvec3 out;
        for (int i = 0; i < 3; ++i) {
            if (!v[size_t(i)].is_number()) fail(key, "expected an array of 3 numbers");
            out[i] = v[size_t(i)].get<double>();
            if (!std::isfinite(out[i])) fail(key, "must be finite");
        }
        return out;
    }

    // A point in world space: each coordinate within kMaxWorldCoordinate.
    glm::dvec3 position(const std::string& key) const {
        const glm::dvec3 p = vec3(key);
        for (int i = 0; i < 3; ++i) {
            if (std::abs(p[i]) > kMaxWorldCoordinate) {
                fail(key, "coordinate " + number_text(p[i]) + " exceeds the limit of " + number_text(kMaxWorldCoordinate));
            }
        }
        return p;
    }
    // A direction of any non-zero length, returned as a unit vector.
    glm::dvec3 direction(const std::string& key) const {
        const std::optional<glm::dvec3> unit = unit_direction(vec3(key));
        if (!unit) fail(key, "must not be the zero vector");
        return *unit;
    }
    // A frame number within kMinFrame..kMaxFrame (core/scene/frame_pattern.h).
    int frame(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_number_integer()) fail(key, "expected an integer frame number, got " + type_name(v));
        check_frame_range(frame_value(v), frame_value(v), file_ + ": key '" + join(key) + "'");
        return int(v.get<int64_t>());
    }
    // An integer JSON value as a long long; unsigned values past its range saturate.
    static long long frame_value(const json& v) {
        if (v.is_number_unsigned()) return (long long)std::min<uint64_t>(v.get<uint64_t>(), uint64_t(INT64_MAX));
        return (long long)v.get<int64_t>();
    }

    const json& value() const { return value_; }
    const std::string& file() const { return file_; }
    std::string join(const std::string& key) const {
        if (key.empty()) return path_;
        return path_.empty() ? key : path_ + "." + key;
    }

  private:
    static std::string type_name(const json& v) { return v.type_name(); }

    std::string file_;
    const json& value_;
    std::string path_;
};

Rotation read_rotation(const Reader& r) {
    r.allow_only({"axis", "degrees", "center"});
    Rotation rot;
    rot.axis = r.direction("axis");
    rot.degrees = r.number("degrees");
    if (r.has("center")) rot.center = r.position("center");
    return rot;
}

void check_pose(const Reader& r, const CameraPose& pose) {
    if (!(pose.fov_y_deg >= kMinFovDeg && pose.fov_y_deg < 180.0))
        r.fail("fov_y_deg", "must be at least " + number_text(kMinFovDeg) + " and below 180 degrees");
    if (pose.ortho_height && !(*pose.ortho_height >= kMinOrthoHeight && *pose.ortho_height <= kMaxOrthoHeight)) {
        r.fail("ortho_height",
               "must be between " + number_text(kMinOrthoHeight) + " and " + number_text(kMaxOrthoHeight));
    }
    const glm::dvec3 view = pose.target - pose.eye;
    const double magnitude = std::max({std::abs(pose.eye.x), std::abs(pose.eye.y), std::abs(pose.eye.z),
                                       std::abs(pose.target.x), std::abs(pose.target.y), std::abs(pose.target.z)});
    const std::optional<glm::dvec3> forward = unit_direction(view);
    if (!forward || glm::length(view) <= kCoincidentRatio * magnitude)
        r.fail("eye", "equals the target; the camera has no view direction");
    if (glm::length(glm::cross(*forward, pose.up)) < kParallelSine) r.fail("up", "is parallel to the view direction");
}

CameraPose read_pose(const Reader& r) {
    CameraPose pose;
    pose.eye = r.position("eye");
    pose.target = r.position("target");
    pose.up = r.has("up") ? r.direction("up") : glm::dvec3(0.0, 1.0, 0.0);
    pose.fov_y_deg = r.number_or("fov_y_deg", 35.0);
    if (r.has("ortho_height")) {
        if (r.has("fov_y_deg")) r.fail("ortho_height", "an orthographic camera has no fov_y_deg; give one of the two");
        pose.ortho_height = r.number("ortho_height");
    }
    check_pose(r, pose);
    return pose;
}

CameraSpec read_camera(const Reader& r) {
    CameraSpec spec;
    if (r.has("frames")) {
        r.allow_only({"frames", "near", "far"});
        const json& list = r.at("frames");
        if (!list.is_array() || list.empty()) r.fail("frames", "expected a non-empty array of camera objects");
        for (size_t i = 0; i < list.size(); ++i) {
            const Reader item(r.file(), list[i], r.join("frames") + "[" + std::to_string(i) + "]");
            item.allow_only({"frame", "eye", "target", "up", "fov_y_deg", "ortho_height"});
            const int frame = item.frame("frame");
            if (spec.per_frame.count(frame)) item.fail("frame", "frame " + std::to_string(frame) + " is given twice");
            spec.per_frame[frame] = read_pose(item);
        }
    } else {
        r.allow_only({"eye", "target", "up", "fov_y_deg", "ortho_height", "orbit", "near", "far"});
        spec.pose = read_pose(r);
        if (r.has("orbit")) spec.orbit = read_rotation(r.child("orbit"));
    }
    if (r.has("near")) {
        spec.near = r.number("near");
        if (!(*spec.near > 0.0)) r.fail("near", "must be greater than 0");
    }
    if (r.has("far")) {
        spec.far = r.number("far");
        if (!(*spec.far > spec.near.value_or(0.0))) r.fail("far", "must be greater than near");
    }
    return spec;
}

MeshSource read_mesh(const Reader& r, const std::filesystem::path& base) {
    MeshSource source;
    const json& v = r.at("mesh");
    std::string path;
    if (v.is_string()) {
        path = v.get<std::string>();
    } else if (v.is_object()) {
        const Reader m = r.child("mesh");
        m.allow_only({"sequence"});
        path = m.string("sequence");
        if (!has_frame_field(path)) m.fail("sequence", "needs a frame field such as %04d");
        source.is_sequence = true;
    } else {
        r.fail("mesh", "expected a file path or {\"sequence\": \"pattern\"}");
    }
    if (path.empty()) r.fail("mesh", "is empty");
    source.path = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : base / path;
    return source;
}


// "#rrggbb" or [r, g, b] with components in [0, 1].
glm::dvec3 read_color(const Reader& r, const std::string& key) {
    const json& v = r.at(key);
    if (v.is_string()) {
        const std::string text = v.get<std::string>();
        const bool hex = text.size() == 7 && text[0] == '#' &&
                         std::all_of(text.begin() + 1, text.end(), [](char c) { return std::isxdigit(uint8_t(c)); });
        if (!hex) r.fail(key, "expected a color \"#rrggbb\" or [r, g, b] in 0..1");
        glm::dvec3 color;
        for (int i = 0; i < 3; ++i) {
            color[i] = double(std::stoi(text.substr(size_t(1 + 2 * i), 2), nullptr, 16)) / 255.0;
        }
        return color;
    }
    if (!v.is_array()) r.fail(key, "expected a color \"#rrggbb\" or [r, g, b] in 0..1");
    const glm::dvec3 color = r.vec3(key);
    for (int i = 0; i < 3; ++i) {
        if (!(color[i] >= 0.0 && color[i] <= 1.0)) r.fail(key, "components must be between 0 and 1");
    }
    return color;
}

// The tone curve's keys of a "tone" block, those it has (docs/tone.md), into `r_patch`.
void read_tone_curve(const Reader& r, TonePatch& r_patch) {
    if (r.has("gamma")) {
        r_patch.gamma = r.number_or("gamma", 1.0);
        if (!(*r_patch.gamma > 0.0 && *r_patch.gamma <= 16.0)) r.fail("gamma", "must be above 0 and at most 16");
    }
    if (r.has("levels")) {
        r_patch.levels = r.integer("levels");
        if (*r_patch.levels < 0 || *r_patch.levels > 256) r.fail("levels", "must be between 0 and 256");
    }
    for (const char* key : {"min", "max"}) {
        if (!r.has(key)) continue;
        const double v = r.number_or(key, 0.0);
        if (!(v >= 0.0 && v <= 0.9)) r.fail(key, "must be between 0 and 0.9");
        (std::string_view(key) == "min" ? r_patch.min : r_patch.max) = v;
    }
}

// The "mode" of a "tone" block.
ToneMode read_tone_mode(const Reader& r) {
    const std::optional<ToneMode> mode = tone_mode_from_name(r.string("mode"));
    if (!mode) r.fail("mode", "expected \"stipple\", \"hatch\", \"crosshatch\" or \"none\"");
    return *mode;
}

// The scene's "tone" block (docs/tone.md).
ToneOptions read_tone(const Reader& r) {
    r.allow_only({"mode", "gamma", "levels", "min", "max", "dot_radius_px", "fade", "line_width_px", "direction",
                  "cross_direction", "cross_from", "space", "angle_deg", "cross_angle_deg", "color", "opacity",
                  "seed", "crease_angle_deg", "max_samples"});
    ToneOptions t;
    t.mode = ToneMode::kStipple;
    if (r.has("mode")) t.mode = read_tone_mode(r);
    TonePatch curve;
    read_tone_curve(r, curve);
    curve.apply_to(t.curve);
    t.dot_radius_px = r.number_or("dot_radius_px", t.dot_radius_px);
    if (!(t.dot_radius_px >= 0.25 && t.dot_radius_px <= 64.0)) r.fail("dot_radius_px", "must be between 0.25 and 64");
    t.fade = r.number_or("fade", t.fade);
    if (!(t.fade >= 0.0 && t.fade <= 4.0)) r.fail("fade", "must be between 0 and 4");
    t.line_width_px = r.number_or("line_width_px", t.line_width_px);
    if (!(t.line_width_px >= 0.1 && t.line_width_px <= 64.0)) r.fail("line_width_px", "must be between 0.1 and 64");
    if (r.has("space")) {
        const std::string space = r.string("space");
        if (space == "screen") t.space = HatchSpace::kScreen;
        else if (space != "object") r.fail("space", "expected \"object\" or \"screen\"");
    }
    // Each space has its own way of giving the lines' direction.
    const bool screen = t.space == HatchSpace::kScreen;
    for (const char* key : {"direction", "cross_direction", "angle_deg", "cross_angle_deg"}) {
        const bool screen_key = std::string_view(key).ends_with("angle_deg");
        if (r.has(key) && screen_key != screen) {
            r.fail(key, screen ? "is for \"space\": \"object\" (in screen space the lines take angle_deg)"
                               : "is for \"space\": \"screen\" (on the surface the lines take direction)");
        }
    }
    if (r.has("direction")) t.direction = r.direction("direction");
    if (r.has("cross_direction")) t.cross_direction = r.direction("cross_direction");
    for (const char* key : {"angle_deg", "cross_angle_deg"}) {
        if (!r.has(key)) continue;
        const double angle = r.number_or(key, 0.0);
        if (!(angle >= -360.0 && angle <= 360.0)) r.fail(key, "must be between -360 and 360");
        (std::string_view(key) == "angle_deg" ? t.angle_deg : t.cross_angle_deg) = angle;
    }
    t.cross_from = r.number_or("cross_from", t.cross_from);
    if (!(t.cross_from >= 0.0 && t.cross_from <= 0.9)) r.fail("cross_from", "must be between 0 and 0.9");
    if (r.has("color")) t.color = read_color(r, "color");
    t.opacity = r.number_or("opacity", t.opacity);
    if (!(t.opacity >= 0.0 && t.opacity <= 1.0)) r.fail("opacity", "must be between 0 and 1");
    if (r.has("seed")) {
        const int seed = r.integer("seed");
        if (seed < 0) r.fail("seed", "must be 0 or more");
        t.seed = uint64_t(seed);
    }
    if (r.has("max_samples")) {
        const double most = r.number_or("max_samples", 0.0);
        if (!(most >= 1000.0 && most <= 2e9) || most != std::floor(most)) {
            r.fail("max_samples", "must be a whole number from 1000 to 2000000000");
        }
        t.max_samples = size_t(most);
    }
    if (r.has("crease_angle_deg")) {
        t.crease_angle_deg = r.number_or("crease_angle_deg", 0.0);
        if (!(*t.crease_angle_deg >= 0.0 && *t.crease_angle_deg <= 180.0)) {
            r.fail("crease_angle_deg", "must be between 0 and 180");
        }
    }
    return t;
}

// The "tone" block of an "objects" or "styles" rule: the keys it sets of the scene's tone.
TonePatch read_tone_patch(const Reader& r) {
    r.allow_only({"mode", "gamma", "levels", "min", "max", "color", "opacity"});
    TonePatch patch;
    if (r.has("mode")) patch.mode = read_tone_mode(r);
    read_tone_curve(r, patch);
    if (r.has("color")) patch.color = read_color(r, "color");
    if (r.has("opacity")) {
        patch.opacity = r.number_or("opacity", 1.0);
        if (!(*patch.opacity >= 0.0 && *patch.opacity <= 1.0)) r.fail("opacity", "must be between 0 and 1");
    }
    return patch;
}

// Applies a rule's tone keys to an object's tone.
void apply_tone_patch(const TonePatch& patch, ObjectTone& r_tone) {
    if (patch.mode) r_tone.mode = *patch.mode;
    patch.apply_to(r_tone.curve);
    if (patch.color) r_tone.ink.color = *patch.color;
    if (patch.opacity) r_tone.ink.opacity = *patch.opacity;
}

// The brush keys a style rule may set, as "brush" has them.
constexpr std::initializer_list<const char*> kStyleBrushKeys = {
    "width_min_px", "width_max_px", "gamma", "invert", "taper_px", "max_width_ratio", "min_length_px", "color", "opacity",
    "depth_width", "curvature_width", "dash_px", "cap", "line_width_px", "texture"};

// Most entries of a dash pattern, and its shortest period (px): a pattern finer than that would
// cut a long stroke into millions of pieces.
constexpr size_t kMaxDashEntries = 16;
constexpr double kMinDashPeriodPx = 1.0;

// The keys of kStyleBrushKeys that `r` has, checked one by one.
BrushPatch read_brush_patch(const Reader& r) {
    BrushPatch p;
    const std::string limit = "exceeds the limit of " + std::to_string(int(kMaxBrushWidthPx)) + " px";
    auto non_negative = [&r](const char* key) -> std::optional<double> {
        if (!r.has(key)) return std::nullopt;
        const double v = r.number(key);
        if (v < 0.0) r.fail(key, "must not be negative");
        return v;
    };
    auto width = [&](const char* key) {
        const std::optional<double> v = non_negative(key);
        if (v && *v > kMaxBrushWidthPx) r.fail(key, limit);
        return v;
    };
    p.width_min_px = width("width_min_px");
    p.width_max_px = width("width_max_px");
    if (p.width_min_px && p.width_max_px && *p.width_max_px < *p.width_min_px) {
        r.fail("width_max_px", "must not be less than width_min_px");
    }
    if (r.has("gamma")) {
        p.gamma = r.number("gamma");
        if (!(*p.gamma > 0.0 && *p.gamma <= 100.0)) r.fail("gamma", "must be greater than 0 and at most 100");
    }
    if (r.has("invert")) p.invert = r.boolean_or("invert", false);
    p.taper_px = non_negative("taper_px");
    if (r.has("max_width_ratio")) {
        p.max_width_ratio = r.number("max_width_ratio");
        if (!(*p.max_width_ratio > 0.0 && *p.max_width_ratio <= 1000.0)) {
            r.fail("max_width_ratio", "must be greater than 0 and at most 1000");
        }
    }
    p.min_length_px = non_negative("min_length_px");
    if (r.has("color")) p.color = read_color(r, "color");
    if (r.has("opacity")) {
        p.opacity = r.number("opacity");
        if (!(*p.opacity >= 0.0 && *p.opacity <= 1.0)) r.fail("opacity", "must be between 0 and 1");
    }
    if (r.has("line_width_px")) {
        p.line_width_px = r.number("line_width_px");
        if (!(*p.line_width_px > 0.0)) r.fail("line_width_px", "must be greater than 0");
        if (*p.line_width_px > kMaxBrushWidthPx) r.fail("line_width_px", limit);
    }
    if (r.has("depth_width")) {
        const Reader d = r.child("depth_width");
        d.allow_only({"near", "far", "far_scale"});
        DepthWidth& depth = p.depth_width.emplace();
        if (d.has("near")) depth.near = d.number("near");
        if (d.has("far")) depth.far = d.number("far");
        if (depth.near && depth.far && !(*depth.far > *depth.near)) d.fail("far", "must be greater than near");
        depth.far_scale = d.number_or("far_scale", depth.far_scale);
        if (!(depth.far_scale >= 0.0 && depth.far_scale <= 100.0)) d.fail("far_scale", "must be between 0 and 100");
    }
    if (r.has("curvature_width")) {
        const Reader c = r.child("curvature_width");
        c.allow_only({"radius_px", "scale"});
        CurvatureWidth& curvature = p.curvature_width.emplace();
        curvature.radius_px = c.number_or("radius_px", curvature.radius_px);
        if (!(curvature.radius_px > 0.0 && curvature.radius_px <= 1e6)) {
            c.fail("radius_px", "must be greater than 0 and at most 1e6");
        }
        curvature.scale = c.number_or("scale", curvature.scale);
        if (!(curvature.scale >= 0.0 && curvature.scale <= 100.0)) c.fail("scale", "must be between 0 and 100");
    }
    if (r.has("dash_px")) {
        const json& v = r.at("dash_px");
        const char* expected = "expected an array of lengths in px: [on, off, ...] ([] for a solid line)";
        if (!v.is_array() || v.size() > kMaxDashEntries) r.fail("dash_px", expected);
        std::vector<double>& dash = p.dash_px.emplace();
        double period = 0.0;
        for (const json& x : v) {
            if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < 0.0) r.fail("dash_px", expected);
            dash.push_back(x.get<double>());
            period += dash.back() * (v.size() % 2 == 1 ? 2.0 : 1.0);
        }
        if (!dash.empty() && !(period >= kMinDashPeriodPx)) {
            r.fail("dash_px", "the pattern must repeat after 1 px or more");
        }
        if (!dash.empty() && period > 1e6) r.fail("dash_px", "the pattern must repeat within 1e6 px");
    }
    if (r.has("texture")) {
        const json& v = r.at("texture");
        if (v.is_boolean()) {
            p.texture = v.get<bool>() ? std::optional<BrushTexture>(BrushTexture{}) : std::nullopt;
        } else {
            const Reader t = r.child("texture");
            t.allow_only({"dry", "dry_px", "streaks", "pressure"});
            BrushTexture texture;
            for (const auto& [key, value] : {std::pair("dry", &texture.dry), std::pair("streaks", &texture.streaks),
                                             std::pair("pressure", &texture.pressure)}) {
                *value = t.number_or(key, *value);
                if (!(*value >= 0.0 && *value <= 1.0)) t.fail(key, "must be between 0 and 1");
            }
            texture.dry_px = t.number_or("dry_px", texture.dry_px);
            if (!(texture.dry_px > 0.0 && texture.dry_px <= 10000.0)) t.fail("dry_px", "must be above 0 and at most 10000");
            p.texture = std::optional<BrushTexture>(texture);
        }
    }
    if (r.has("cap")) {
        const std::string cap = r.string("cap");
        if (cap == "round") p.cap = LineCap::kRound;
        else if (cap == "butt") p.cap = LineCap::kButt;
        else if (cap == "square") p.cap = LineCap::kSquare;
        else r.fail("cap", "expected \"round\", \"butt\" or \"square\"");
    }
    return p;
}

BrushStyle read_brush(const Reader& r, const std::filesystem::path& base) {
    std::vector<const char*> keys = {"smooth_px", "max_deviation_px", "turn_angle_deg", "tip"};
    keys.insert(keys.end(), kStyleBrushKeys.begin(), kStyleBrushKeys.end());
    r.allow_only(keys);
    BrushStyle b;
    read_brush_patch(r).apply_to(b);
    if (b.width_max_px < b.width_min_px) r.fail("width_max_px", "must not be less than width_min_px");
    const std::string limit = "exceeds the limit of " + std::to_string(int(kMaxBrushWidthPx)) + " px";
    auto non_negative = [&r](const char* key, double fallback) {
        const double v = r.number_or(key, fallback);
        if (v < 0.0) r.fail(key, "must not be negative");
        return v;
    };
    b.smooth_px = non_negative("smooth_px", b.smooth_px);
    if (b.smooth_px > kMaxBrushWidthPx) r.fail("smooth_px", limit);
    b.max_deviation_px = non_negative("max_deviation_px", b.max_deviation_px);
    b.turn_angle_deg = r.number_or("turn_angle_deg", b.turn_angle_deg);
    if (!(b.turn_angle_deg > 0.0 && b.turn_angle_deg <= 180.0)) {
        r.fail("turn_angle_deg", "must be greater than 0 and at most 180");
    }
    if (r.has("tip")) {
        const std::string tip = r.string("tip");
        if (tip.empty()) r.fail("tip", "is empty");
        b.tip = std::filesystem::path(tip).is_absolute() ? std::filesystem::path(tip) : base / tip;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(b.tip, ec)) {
            r.fail("tip", "no such file: " + quote_value(b.tip.string(), kMaxQuotedPathChars));
        }
    }
    return b;
}

// Most rules in "styles".
constexpr size_t kMaxStyleRules = 64;

// "select": {"kind": "silhouette" | [...], "object": "glob", "role": "outer" | "inner"}.
StyleSelector read_selector(const Reader& r) {
    r.allow_only({"kind", "object", "role"});
    StyleSelector select;
    if (r.has("kind")) {
        const json& v = r.at("kind");
        const char* expected = "expected a line kind or an array of them (silhouette, boundary, crease, intersection, hidden)";
        std::vector<std::string> names;
        if (v.is_string()) {
            names.push_back(v.get<std::string>());
        } else if (v.is_array() && !v.empty()) {
            for (const json& x : v) {
                if (!x.is_string()) r.fail("kind", expected);
                names.push_back(x.get<std::string>());
            }
        } else {
            r.fail("kind", expected);
        }
        for (const std::string& name : names) {
            uint8_t bit = 0;
            if (name == "hidden") bit = kSelectHidden;
            for (const LineKind kind : kAllLineKinds) {
                if (name == line_kind_name(kind)) bit = uint8_t(1u << unsigned(kind));
            }
            if (bit == 0) r.fail("kind", "'" + quote_value(name) + "': " + expected);
            select.kinds |= bit;
        }
    }
    if (r.has("object")) {
        select.object = r.string("object");
        if (select.object.empty()) r.fail("object", "is empty");
    }
    if (r.has("role")) {
        const std::string role = r.string("role");
        if (role == "outer") select.role = LineRole::kOuter;
        else if (role == "inner") select.role = LineRole::kInner;
        else r.fail("role", "expected \"outer\" or \"inner\"");
    }
    return select;
}

// "styles": [{"name": ..., "select": {...}, brush keys...}, ...]
std::vector<StyleRule> read_styles(const Reader& r) {
    if (!r.value().is_array()) r.fail("", "expected an array of style rules");
    if (r.value().size() > kMaxStyleRules) r.fail("", "more than " + std::to_string(kMaxStyleRules) + " rules");
    std::vector<StyleRule> rules;
    std::set<std::string> names;
    for (size_t i = 0; i < r.value().size(); ++i) {
        const Reader item = r.item(i);
        std::vector<const char*> keys = {"name", "select", "tone"};
        keys.insert(keys.end(), kStyleBrushKeys.begin(), kStyleBrushKeys.end());
        item.allow_only(keys);
        StyleRule rule;
        rule.name = item.has("name") ? item.string("name") : "style-" + std::to_string(i + 1);
        const bool name_ok = !rule.name.empty() && rule.name.size() <= 64 &&
                             std::all_of(rule.name.begin(), rule.name.end(), [](char c) {
                                 return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
                             });
        if (!name_ok) item.fail("name", "expected 1 to 64 letters, digits, '-', '_' or '.'");
        if (!names.insert(rule.name).second) item.fail("name", "'" + rule.name + "' names an earlier rule too");
        if (item.has("select")) rule.select = read_selector(item.child("select"));
        rule.set = read_brush_patch(item);
        if (item.has("tone")) {
            if (!item.at("tone").is_object()) {
                item.fail("tone",
                          "expected {\"mode\", \"gamma\", \"levels\", \"min\", \"max\", \"color\", \"opacity\"}");
            }
            // The surface has no line kind and no role: a rule that shades it selects by object.
            if (rule.select.kinds != 0 || rule.select.role) {
                item.fail("tone", "a rule with a tone selects by object only, not by kind or role");
            }
            rule.tone = read_tone_patch(item.child("tone"));
        }
        rules.push_back(std::move(rule));
    }
    return rules;
}

// The radius a camera frames: the bounds' own, or, for a single point, one a millionth of the
// point's distance from the origin (at least 1e-6), so that the camera still stands apart from
// it in double precision.
double framing_radius(const Bounds& bounds) {
    const double radius = bounds.radius();
    if (radius > 0.0) return radius;
    const glm::dvec3 c = bounds.center();
    return 1e-6 * std::max({1.0, std::abs(c.x), std::abs(c.y), std::abs(c.z)});
}

// "objects": {"PATTERN": {"lines": false | true | {"silhouette": b, "boundary": b, "crease": b, "intersection": b}}}.
std::vector<ObjectRule> read_object_rules(const Reader& r) {
    if (!r.value().is_object()) r.fail("", "expected {\"name or glob\": {\"lines\": ...}}");
    std::vector<ObjectRule> globs, exact;
    for (const auto& [pattern, value] : r.value().items()) {
        if (pattern.empty()) r.fail("", "an object pattern is empty");
        const Reader o = r.child(pattern);
        o.allow_only({"lines", "tone"});
        ObjectRule rule;
        rule.pattern = pattern;
        if (o.has("tone") && o.at("tone").is_object()) {
            rule.tone = true;
            rule.tone_set = read_tone_patch(o.child("tone"));
        } else if (o.has("tone")) {
            if (!o.at("tone").is_boolean()) {
                o.fail("tone", "expected true, false or {\"mode\", \"gamma\", \"levels\", \"min\", \"max\", \"color\", "
                               "\"opacity\"}");
            }
            rule.tone = o.boolean_or("tone", true);
        }
        if (o.has("lines")) {
            if (o.at("lines").is_boolean()) {
                rule.lines = o.boolean_or("lines", true);
            } else {
                const Reader l = o.child("lines");
                l.allow_only({"silhouette", "boundary", "crease", "intersection"});
                if (l.has("silhouette")) rule.silhouette = l.boolean_or("silhouette", true);
                if (l.has("boundary")) rule.boundary = l.boolean_or("boundary", true);
                if (l.has("crease")) rule.crease = l.boolean_or("crease", true);
                if (l.has("intersection")) rule.intersection = l.boolean_or("intersection", true);
            }
        }
        (pattern.find_first_of("*?[") == std::string::npos ? exact : globs).push_back(rule);
    }
    globs.insert(globs.end(), exact.begin(), exact.end());
    return globs;
}

}  // namespace

std::array<bool, kLineKindCount> object_line_kinds(const Scene& scene, const std::string& object_name) {
    std::array<bool, kLineKindCount> kinds{};
    kinds[size_t(LineKind::kSilhouette)] = scene.lines.silhouette;
    kinds[size_t(LineKind::kBoundary)] = scene.lines.boundary;
    kinds[size_t(LineKind::kCrease)] = scene.lines.crease;
    kinds[size_t(LineKind::kIntersection)] = scene.lines.intersection;
    bool lines = true;
    for (const ObjectRule& rule : scene.objects) {
        if (::fnmatch(rule.pattern.c_str(), object_name.c_str(), 0) != 0) continue;
        lines = rule.lines;
        if (rule.silhouette) kinds[size_t(LineKind::kSilhouette)] = *rule.silhouette;
        if (rule.boundary) kinds[size_t(LineKind::kBoundary)] = *rule.boundary;
        if (rule.crease) kinds[size_t(LineKind::kCrease)] = *rule.crease;
        if (rule.intersection) kinds[size_t(LineKind::kIntersection)] = *rule.intersection;
    }
    if (!lines) kinds.fill(false);
    return kinds;
}

ObjectTone object_tone(const Scene& scene, std::optional<std::string_view> object_name) {
    ObjectTone t;
    t.mode = scene.tone.mode;
    t.curve = scene.tone.curve;
    t.ink = {scene.tone.color, scene.tone.opacity, ""};
    const std::string name(object_name.value_or(""));
    const auto matches = [&](const std::string& pattern) {
        return object_name && ::fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
    };
    bool lines = true;
    for (const ObjectRule& rule : scene.objects) {
        if (!matches(rule.pattern)) continue;
        lines = rule.lines;
        if (rule.tone) t.shaded = *rule.tone;
        apply_tone_patch(rule.tone_set, t);
    }
    for (const StyleRule& rule : scene.styles) {
        if (!rule.tone || (!rule.select.object.empty() && !matches(rule.select.object))) continue;
        apply_tone_patch(*rule.tone, t);
        t.ink.style = rule.name;
    }
    t.shaded = t.shaded && lines;
    if (!t.shaded || scene.tone.mode == ToneMode::kNone) t.mode = ToneMode::kNone;
    return t;
}

Scene parse_scene(std::string_view json_text, const std::filesystem::path& scene_file, int max_image_side) {
    const std::string name = scene_file.string();
    json root;
    try {
        root = json::parse(json_text);
    } catch (const json::exception& e) {
        // Syntax errors and numbers beyond double range; nlohmann's message after its
        // "[json.exception...]" prefix is one line and names the byte offset.
        std::string what = e.what();
        const auto prefix_end = what.find("] ");
        // Its "last read" part quotes the input, so it is cut like any quoted value.
        throw InputError(quote_value(name, kMaxQuotedPathChars) + ": not valid JSON: " +
                         quote_value(prefix_end == std::string::npos ? what : what.substr(prefix_end + 2), kMaxQuotedPathChars));
    }
    const Reader r(name, root, "");
    r.allow_only({"version", "mesh", "gltf", "fps", "write_on", "frames", "image", "camera", "object", "objects", "light",
                  "lines", "brush", "styles", "tone"});

    Scene scene;
    scene.file = scene_file;
    if (r.has("version") && r.integer("version") != 1) r.fail("version", "only version 1 is supported");
    scene.mesh = read_mesh(r, scene_file.parent_path());
    if (is_gltf_path(scene.mesh.path)) {
        if (scene.mesh.is_sequence) r.fail("mesh", "a glTF file holds its own animation; name it as a plain path");
        GltfSettings& g = scene.gltf.emplace();
        if (r.has("gltf")) {
            const Reader gr = r.child("gltf");
            gr.allow_only({"scene", "animation", "camera"});
            if (gr.has("scene")) {
                g.scene = gr.integer("scene");
                if (g.scene < 0) gr.fail("scene", "must be 0 or more");
            }
            if (gr.has("animation")) g.animation = gr.string("animation");
            if (gr.has("camera")) g.camera = gr.string("camera");
        }
    } else if (r.has("gltf")) {
        r.fail("gltf", "applies only when mesh names a .gltf or .glb file");
    }
    if (r.has("fps")) {
        scene.fps = r.number("fps");
        if (!(scene.fps > 0.0 && scene.fps <= 1e6)) r.fail("fps", "must be above 0 and at most 1e6");
    }
    if (r.has("write_on")) {
        scene.write_on_s = r.number("write_on");
        if (!(scene.write_on_s > 0.0 && scene.write_on_s <= kMaxWriteOnSeconds))
            r.fail("write_on", "must be above 0 and at most " + std::to_string(int(kMaxWriteOnSeconds)) + " seconds");
    }
    scene.given = {r.has("frames"), r.has("image"), r.has("camera")};

    if (r.has("frames")) {
        const json& f = r.at("frames");
        if (!f.is_array() || f.size() != 2 || !f[0].is_number_integer() || !f[1].is_number_integer())
            r.fail("frames", "expected [first, last] as two integers");
        check_frame_range(Reader::frame_value(f[0]), Reader::frame_value(f[1]), r.file() + ": key 'frames'");
        scene.first_frame = int(f[0].get<int64_t>());
        scene.last_frame = int(f[1].get<int64_t>());
    }
    if (r.has("image")) {
        const Reader img = r.child("image");
        img.allow_only({"width", "height"});
        scene.image = {img.integer("width"), img.integer("height")};
        for (const char* key : {"width", "height"}) {
            const int side = std::string(key) == "width" ? scene.image.width : scene.image.height;
            if (side <= 0) img.fail(key, "must be a positive number of pixels");
            if (side > max_image_side) {
                img.fail(key, "exceeds the limit of " + std::to_string(max_image_side) + " px (see --max-image-side)");
            }
        }
    }
    // A glTF shot brings its own camera unless the scene gives one.
    if (!scene.gltf || r.has("camera")) scene.camera = read_camera(r.child("camera"));
    if (r.has("object")) {
        const Reader obj = r.child("object");
        obj.allow_only({"rotate"});
        if (obj.has("rotate")) scene.object_rotation = read_rotation(obj.child("rotate"));
    }
    if (r.has("light")) {
        const Reader l = r.child("light");
        l.allow_only({"direction", "position"});
        if (l.has("direction") == l.has("position")) l.fail("", "give exactly one of direction or position");
        if (l.has("direction")) {
            scene.light.direction = l.direction("direction");
        } else {
            scene.light.is_point = true;
            scene.light.position = l.position("position");
        }
    }
    if (r.has("lines")) {
        const Reader l = r.child("lines");
        l.allow_only({"silhouette", "contour", "boundary", "crease", "intersection", "self_intersection",
                      "crease_angle_deg", "hidden"});
        scene.lines.silhouette = l.boolean_or("silhouette", true);
        if (l.has("contour")) {
            const std::optional<ContourMode> mode = contour_mode_from_name(l.string("contour"));
            if (!mode) l.fail("contour", "expected \"mesh\" or \"smooth\"");
            scene.lines.contour = *mode;
        }
        scene.lines.boundary = l.boolean_or("boundary", true);
        scene.lines.crease = l.boolean_or("crease", true);
        scene.lines.intersection = l.boolean_or("intersection", true);
        scene.lines.self_intersection = l.boolean_or("self_intersection", false);
        scene.lines.crease_angle_deg = l.number_or("crease_angle_deg", 60.0);
        if (!(scene.lines.crease_angle_deg >= 0.0 && scene.lines.crease_angle_deg <= 180.0))
            l.fail("crease_angle_deg", "must be between 0 and 180");
        scene.lines.hidden = l.boolean_or("hidden", false);
    }
    if (r.has("brush")) scene.brush = read_brush(r.child("brush"), scene_file.parent_path());
    if (r.has("objects")) scene.objects = read_object_rules(r.child("objects"));
    if (r.has("styles")) scene.styles = read_styles(r.child("styles"));
    if (r.has("tone")) scene.tone = read_tone(r.child("tone"));
    return scene;
}

Scene load_scene(const std::filesystem::path& scene_file, int max_image_side) {
    std::ifstream in(scene_file, std::ios::binary);
    if (!in) {
        throw InputError(quote_value(scene_file.string(), kMaxQuotedPathChars) + ": cannot read: " + std::strerror(errno));
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parse_scene(text.str(), scene_file, max_image_side);
}

Scene default_turntable_scene(const std::filesystem::path& mesh_file, const Bounds& bounds) {
    Scene scene;
    scene.mesh.path = mesh_file;
    scene.first_frame = 1;
    scene.last_frame = 48;
    const glm::dvec3 center = bounds.center();
    const double radius = framing_radius(bounds);
    constexpr double kFovDeg = 35.0;
    constexpr double kElevationDeg = 20.0;
    // Fit the bounding sphere in the vertical field of view with a 10% margin.
    const double distance = 1.1 * radius / std::sin(glm::radians(kFovDeg / 2.0));
    const double elevation = glm::radians(kElevationDeg);
    scene.camera.pose.target = center;
    scene.camera.pose.eye = center + distance * glm::dvec3(0.0, std::sin(elevation), std::cos(elevation));
    scene.camera.pose.up = {0.0, 1.0, 0.0};
    scene.camera.pose.fov_y_deg = kFovDeg;
    scene.camera.orbit = Rotation{{0.0, 1.0, 0.0}, 360.0, center};
    return scene;
}

double motion_fraction(const Scene& scene, int frame) {
    const double count = double(scene.last_frame) - double(scene.first_frame) + 1.0;
    return (double(frame) - double(scene.first_frame)) / count;
}

glm::dmat4 world_from_object_at(const Scene& scene, int frame) {
    if (!scene.object_rotation) return glm::dmat4(1.0);
    const Rotation& r = *scene.object_rotation;
    const double angle = glm::radians(r.degrees * motion_fraction(scene, frame));
    return glm::translate(glm::dmat4(1.0), r.center) * glm::rotate(glm::dmat4(1.0), angle, r.axis) *
           glm::translate(glm::dmat4(1.0), -r.center);
}

namespace {
[[noreturn]] void no_camera_for(const Scene& scene, int frame) {
    throw InputError(quote_value(scene.file.string(), kMaxQuotedPathChars) +
                     ": key 'camera.frames': no camera for frame " + std::to_string(frame));
}
}  // namespace

void check_cameras(const Scene& scene, int first, int last) {
    const std::map<int, CameraPose>& per_frame = scene.camera.per_frame;
    if (per_frame.empty()) return;
    // The keys in [first, last] are sorted: the first frame that is not the next key is missing.
    long long expected = first;
    for (auto it = per_frame.lower_bound(first); it != per_frame.end() && it->first <= last; ++it, ++expected) {
        if (it->first != expected) no_camera_for(scene, int(expected));
    }
    if (expected <= last) no_camera_for(scene, int(expected));
}

Camera camera_at(const Scene& scene, int frame, const Bounds& world_bounds) {
    const CameraSpec& spec = scene.camera;
    CameraPose pose = spec.pose;
    if (!spec.per_frame.empty()) {
        const auto it = spec.per_frame.find(frame);
        if (it == spec.per_frame.end()) no_camera_for(scene, frame);
        pose = it->second;
    } else if (spec.orbit) {
        const Rotation& orbit = *spec.orbit;
        const double angle = glm::radians(orbit.degrees * motion_fraction(scene, frame));
        pose.eye = pose.target + glm::rotate(pose.eye - pose.target, angle, orbit.axis);
        pose.up = glm::rotate(pose.up, angle, orbit.axis);
    }
    Camera camera{pose.eye, pose.target, pose.up, pose.fov_y_deg, 0.0, 0.0, pose.ortho_height};

    const double radius = framing_radius(world_bounds);
    if (camera.orthographic()) {
        // An orthographic view sees the whole bounding sphere, also behind the eye: near may be
        // negative. The planes keep a millionth of the eye's distance clear of the sphere, so
        // that they stay apart (and the sphere between them) however far the eye stands.
        const glm::dvec3 forward = glm::normalize(camera.target - camera.eye);
        const double along = glm::dot(world_bounds.center() - camera.eye, forward);
        const double slack = std::max(1.1 * radius + 1e-6 * std::abs(along), 1e-300);
        camera.near = spec.near.value_or(along - slack);
        camera.far = spec.far.value_or(along + slack);
    } else {
        // Fit near/far to the bounding sphere; a camera inside it gets a small positive near.
        const double distance = glm::length(world_bounds.center() - camera.eye);
        camera.near = spec.near.value_or(std::max(0.9 * (distance - radius), 1e-3 * radius));
        camera.far = spec.far.value_or(std::max(1.1 * (distance + radius), camera.near * 2.0));
    }
    // The scene's limits keep every value here finite; a NaN would be a bug, not a bad key.
    INKLINE_CHECK(std::isfinite(camera.near) && std::isfinite(camera.far) && std::isfinite(glm::length(camera.eye)));
    if (!(camera.far > camera.near)) {
        throw InputError(quote_value(scene.file.string(), kMaxQuotedPathChars) +
                         ": key 'camera.far': must be greater than near (" + number_text(camera.near) +
                         ", fitted to the mesh at frame " + std::to_string(frame) + ")");
    }
    return camera;
}

}  // namespace inkline::core
