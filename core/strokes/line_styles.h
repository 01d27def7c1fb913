// SPDX-License-Identifier: MIT
// Line styles (scene "styles"): rules that select strokes by kind, object and role and set brush
// keys for them. Rules apply in order, each over what the rules before it set, key by key; a
// stroke's style is named after the last rule that matched it. docs/styles.md describes them.
#pragma once

#include "core/lines/features.h"
#include "core/mesh/mesh.h"
#include "core/scene/camera.h"
#include "core/strokes/brush_style.h"
#include "core/strokes/stroke_path.h"
#include "core/tone/tone_options.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace inkline::core {

// Where a visible line lies in the drawing: on the outer contour, with background beside it, or
// inside the figure.
enum class LineRole : uint8_t { kOuter, kInner };
// "outer" or "inner".
const char* line_role_name(LineRole role);

struct StyleSelector {
    // Bit (1 << kind) per selected line kind, and kSelectHidden; 0 selects every line. A visible
    // line matches when its kind is selected; a hidden line when kSelectHidden is, and either no
    // kind is or its own is ("hidden" alone: every hidden line; with "crease": hidden creases).
    uint8_t kinds = 0;
    std::string object;  // fnmatch(3) glob over object names; empty: every line
    // Visible lines only: a rule with a role never matches a hidden line.
    std::optional<LineRole> role;
};
inline constexpr uint8_t kSelectHidden = uint8_t(1u << kLineKindCount);

// The brush keys a rule sets; the others keep what the rules before it (or the scene's brush) set.
struct BrushPatch {
    std::optional<double> width_min_px, width_max_px, gamma, taper_px, max_width_ratio, min_length_px, opacity,
        line_width_px;
    std::optional<bool> invert;
    std::optional<glm::dvec3> color;
    std::optional<DepthWidth> depth_width;
    std::optional<CurvatureWidth> curvature_width;
    std::optional<std::vector<double>> dash_px;
    std::optional<LineCap> cap;
    std::optional<std::optional<BrushTexture>> texture;  // set: the texture, or none (false)

    void apply_to(BrushStyle& r_style) const;
};

struct StyleRule {
    std::string name;
    StyleSelector select;
    BrushPatch set;
    // "tone": {...}: how the surface of the objects the rule selects is shaded (a rule with a
    // tone selects by object alone; docs/tone.md).
    std::optional<TonePatch> tone;
};

// What a rule can tell about a stroke.
struct StrokeTraits {
    LineKind kind = LineKind::kSilhouette;
    bool visible = true;
    std::string_view object;  // "" without objects
    LineRole role = LineRole::kInner;
};

bool matches(const StyleSelector& select, const StrokeTraits& traits);

// Whether any rule selects by role (roles then need a BackgroundMask).
bool selects_role(std::span<const StyleRule> rules);

// A style as strokes use it: the scene's brush with the matching rules applied.
struct StrokeStyle {
    std::string name;   // the last matching rule's; empty when none matched
    int32_t rule = -1;  // that rule's index; -1 when none matched
    BrushStyle brush;
};

// The distinct styles of one frame's strokes. Entry 0 is the scene's brush (no rule matched).
class StyleSheet {
  public:
    StyleSheet(const BrushStyle& base, std::span<const StyleRule> rules);
    // The style of a stroke with these traits: an index into styles().
    uint32_t resolve(const StrokeTraits& traits);
    const std::vector<StrokeStyle>& styles() const { return styles_; }
    std::vector<StrokeStyle> take() { return std::move(styles_); }

  private:
    std::span<const StyleRule> rules_;
    std::vector<StrokeStyle> styles_;
    std::vector<std::vector<uint32_t>> matched_;  // per style, the rules that made it (ascending)
};

// The image's pixels covered by the mesh (every face in front of the eye, rasterised at pixel
// centres): what is not covered is background.
class BackgroundMask {
  public:
    BackgroundMask(const Mesh& mesh, const Projection& projection);
    // False outside the image.
    bool covered(const glm::dvec2& p_px) const;

  private:
    int width_ = 0, height_ = 0;
    std::vector<uint8_t> covered_;
};

// Probes this far (px) either side of a line tell whether background lies beside it.
inline constexpr double kRoleProbePx = 2.0;

// Outer when at least half of the stroke's drawn length (probed every few pixels) has background
// within kRoleProbePx on one side or the other; inner otherwise.
LineRole role_of(const StrokePath& path, const BackgroundMask& background);

// The dash pattern's "on" intervals [a, b] of u along [u0, u1]: the pattern starts at u = 0 and
// repeats, so the dashes stay where they were on the stroke as u is carried between frames. An
// interval with a == b is a dot.
std::vector<std::pair<double, double>> dash_intervals(std::span<const double> pattern_px, double u0, double u1);

}  // namespace inkline::core
