// SPDX-License-Identifier: MIT
// Tone options (scene "tone", docs/tone.md): how dark the surface is shaded from the light, and
// with what marks.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace inkline::core {

enum class ToneMode : uint8_t {
    kNone,
    kStipple,     // dots (core/tone/stipple.h)
    kHatch,       // parallel lines (core/tone/hatch.h)
    kCrosshatch,  // parallel lines, and a second family across them for darker tones
};

// "none", "stipple", "hatch" or "crosshatch".
const char* tone_mode_name(ToneMode mode);

// Where hatch lines are laid (scene "tone" "space").
enum class HatchSpace : uint8_t {
    kObject,  // on the surface: sections by planes across an object-space direction
    kScreen,  // on the image: straight lines at an angle on the page
};
// "object" or "screen".
const char* hatch_space_name(HatchSpace space);

// How dark the surface is shaded at a light intensity I in [0, 1]: t = x^gamma with x = 1 - I,
// rounded to `levels` steps (0 or 1: not rounded), then tone = min + (max - min) t.
struct ToneCurve {
    double gamma = 1.0;
    int levels = 0;
    double min = 0.0;
    double max = 0.4;
    bool operator==(const ToneCurve&) const = default;
};

// The scene's "tone" block.
struct ToneOptions {
    ToneMode mode = ToneMode::kNone;
    // Tone (the share of the surface covered by ink) from the light intensity at a point.
    ToneCurve curve;
    double dot_radius_px = 1.0;  // radius of a dot that has faded in fully
    // A dot fades in while the density asked for grows by this share past its threshold (0: it
    // pops in at full size).
    double fade = 0.5;
    // Hatching: lines of this width (px) where they have faded in fully, the surface's sections
    // by planes across `direction` (object space), and with crosshatch a second family across
    // `cross_direction` once the tone passes `cross_from`.
    double line_width_px = 0.8;
    glm::dvec3 direction{0.0, 1.0, 0.0};
    glm::dvec3 cross_direction{1.0, 0.0, 0.0};
    double cross_from = 0.25;
    // Where the hatch lines are laid: on the surface (object space, across `direction`), or on
    // the image (screen space: straight lines at `angle_deg` on the page).
    HatchSpace space = HatchSpace::kObject;
    // Screen space: the lines' direction on the image, degrees anticlockwise from its x axis,
    // and crosshatch's second family's.
    double angle_deg = 45.0;
    double cross_angle_deg = -45.0;
    glm::dvec3 color{0.09, 0.08, 0.07};  // sRGB in [0, 1]
    double opacity = 1.0;
    uint64_t seed = 1;
    // The most surface samples kept: bounds memory when a camera comes very close (then the
    // density there stops growing).
    size_t max_samples = 8'000'000;
    // The light is read from normals split at edges whose faces meet at more than this
    // (degrees, 0..180; core/lines/smooth_pieces.h); unset: the lines' crease_angle_deg.
    std::optional<double> crease_angle_deg{};
};

// The keys of a tone that a rule sets: an object's ("objects": {"NAME": {"tone": {...}}}) or a
// style's ("styles": [{"tone": {...}}]). The keys it does not set stay as they were.
struct TonePatch {
    std::optional<ToneMode> mode;
    std::optional<double> gamma, min, max;
    std::optional<int> levels;
    std::optional<glm::dvec3> color;  // sRGB in [0, 1]
    std::optional<double> opacity;

    void apply_to(ToneCurve& r_curve) const;
};

// The ink marks are drawn in: the scene's tone colour and opacity, or those a rule gives objects.
struct ToneInk {
    glm::dvec3 color{0.09, 0.08, 0.07};  // sRGB in [0, 1]
    double opacity = 1.0;
    std::string style;  // the last style rule that set the object's tone; empty: none did
    bool operator==(const ToneInk&) const = default;
};

// The mode of that name; nullopt for any other text.
std::optional<ToneMode> tone_mode_from_name(std::string_view name);

// Tone at a light intensity on a curve (the options' own curve).
double tone_of(double intensity, const ToneCurve& curve);
inline double tone_of(double intensity, const ToneOptions& options) { return tone_of(intensity, options.curve); }

// Which tone curve each face is shaded with (per-object tone, scene "objects"): curve_of_face[f]
// is 0 for a face left unshaded, else 1 + its index in `curves`. Empty: every face is shaded
// with the options' own curve.
struct FaceTones {
    std::span<const uint16_t> curve_of_face;
    std::span<const ToneCurve> curves;
    bool empty() const { return curve_of_face.empty(); }
};

}  // namespace inkline::core
