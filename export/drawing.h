// SPDX-License-Identifier: MIT
// What a frame looks like on paper, independent of the file format: shapes grouped by line kind,
// each a filled outline or a stroked centerline. SVG, PDF and PNG all draw from this.
#pragma once

#include "core/pipeline/frame_lines.h"
#include "core/strokes/bezier_fit.h"
#include "core/strokes/strokes.h"
#include "core/strokes/write_on.h"
#include "core/tone/tone.h"

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace inkline::output {

struct Rgb {
    double r = 0.0, g = 0.0, b = 0.0;  // 0..1
};

// Parses "#rrggbb" or "#rgb"; throws InputError naming `what` otherwise.
Rgb parse_color(const std::string& text, const std::string& what);

// How filled outlines are written: as the polygons of the stroke stage, or as cubic Bézier
// curves fitted to them (`--path-format`).
enum class PathFormat : uint8_t { kPolygon, kBezier };
// "polygon" or "bezier".
const char* path_format_name(PathFormat format);
// The format of that name; throws InputError "KEY 'TEXT': expected polygon or bezier".
PathFormat parse_path_format(const std::string& text, const char* key);

struct DrawStyle {
    std::string color = "#000000";          // ink
    double opacity = 1.0;
    double centerline_width_px = 1.5;       // stroked centerlines (and hidden dashes)
    std::optional<std::string> background;  // a colour fills the page first; none: transparent
    PathFormat path_format = PathFormat::kPolygon;
    double bezier_tolerance_px = 0.5;       // the curves stay this close to the polygons
};

// The writers' style for a scene's brush: its colour and opacity, Bézier curves within its
// max_deviation_px.
DrawStyle brush_draw_style(const core::BrushStyle& brush);

// How a style inks its shapes (core::StrokeStyle as the writers use it).
struct InkStyle {
    std::string name;       // the style's (its last rule's) name; empty: the scene's brush
    int32_t rule = -1;      // index of that rule in the scene's styles; -1 for the scene's brush
    std::string color;      // "#rrggbb"
    double opacity = 1.0;
    // Stroked centerlines: the dash pattern along u (px); empty: solid, or for hidden lines the
    // writers' dash of 3 and 2 line widths.
    std::vector<double> dash_px;
    core::LineCap cap = core::LineCap::kRound;
    std::optional<double> line_width_px;  // unset: DrawStyle::centerline_width_px
};

struct Shape {
    uint32_t stroke_id = 0;  // written as the element id stroke-<id>
    core::LineKind kind = core::LineKind::kSilhouette;
    bool hidden = false;  // occluded line: dashed centerline in the "hidden" layer
    bool filled = false;  // paths are closed rings filled together (nonzero rule); else stroked
    bool closed = false;  // a stroked centerline that closes on itself
    std::vector<std::vector<glm::dvec2>> paths;  // px, origin top-left, y down
    // With PathFormat::kBezier, per filled path its curves, which replace it (empty: the path
    // is written as a polygon); else empty.
    std::vector<std::vector<core::CubicBezier>> curves = {};
    std::string object = {};  // the line's object (written as data-object); empty without objects
    int32_t object_index = -1;  // its index among the frame's objects; -1 without objects
    uint32_t style = 0;         // index into Drawing::styles
    double u_start = 0.0;       // u at the first point of a stroked centerline: where its dashes start
    double darkening = 0.0;     // the ink drawn this much darker (a textured brush's pressure), in [0, 1]
    // The stroke's drawing order (core::Stroke): group, level, parent (-1 at level 0), order.
    uint32_t group = 0;
    uint32_t level = 0;
    int64_t parent = -1;
    uint32_t order = 0;
};

// How an animated SVG writes on one stroke (core/strokes/write_on.h): its drawn centerline is
// revealed from its start, at the schedule's speed.
struct WriteOnPath {
    uint32_t stroke_id = 0;
    double begin_s = 0.0;                 // when its tip sets off
    double duration_s = 0.0;              // how long it takes
    std::vector<glm::dvec2> centerline;   // px; a loop's last sample does not repeat its first
    bool closed = false;
    double length_px = 0.0;               // the centerline's length, a loop's closing segment included
    double width_px = 0.0;                // its widest
    double taper_px = 0.0;                // its brush's taper: the moving tip thins over it
};
struct WriteOnAnimation {
    double seconds = 0.0;  // the drawing is complete from then on
    std::vector<WriteOnPath> paths;  // one per timed stroke; a stroke without one appears at `seconds`
};
// The animation of a frame's write-on.
WriteOnAnimation write_on_animation(const core::FrameStrokes& strokes, const core::WriteOnSchedule& schedule);

// A dot of tone (core::Dot as the writers draw it): a filled circle.
struct ToneDot {
    uint64_t sample = 0;  // the surface sample it stands for (written as data-sample)
    glm::dvec2 center_px{0.0};
    double radius_px = 0.0;
    uint16_t ink = 0;  // index in ToneLayer::inks, when it has several
};

// A hatch of tone (core::Hatch as the writers draw it): its filled outline.
struct ToneHatch {
    uint32_t family = 0;  // written as data-family
    uint64_t plane = 0;   // written as data-plane
    std::vector<std::vector<glm::dvec2>> rings;  // px, filled together (nonzero)
    uint16_t ink = 0;  // index in ToneLayer::inks, when it has several
};

// An ink of the tone layer (core::ToneInk as the writers draw it).
struct ToneLayerInk {
    std::string color = "#000000";  // "#rrggbb"
    double opacity = 1.0;           // of the ink's marks together
    std::string style;              // the style rule that gave it; empty: none
};

// The frame's tone, drawn under the lines as one layer ("tone"): in one ink, or where objects
// have inks of their own (scene "objects" and "styles"), a group of marks per ink.
struct ToneLayer {
    core::ToneMode mode = core::ToneMode::kNone;  // kNone: no tone layer at all
    // With one ink: its colour, opacity (of the whole layer: overlapping marks do not add up)
    // and style; with several, ink 0's.
    std::string color = "#000000";  // "#rrggbb"
    double opacity = 1.0;
    std::string style;
    std::vector<ToneLayerInk> inks;  // two or more, or empty: every mark in `color`
    std::vector<ToneDot> dots;       // with inks, by ink (in their order within one)
    std::vector<ToneHatch> hatches;  // the same

    // The marks of one ink: all of them where the layer has no inks.
    std::span<const ToneDot> dots_of(size_t ink) const;
    std::span<const ToneHatch> hatches_of(size_t ink) const;
};

// The tone layer of a frame's tone, in its inks, else in `options`' colour and opacity.
ToneLayer tone_layer(const core::FrameTone& tone, const core::ToneOptions& options);

struct Drawing {
    int frame = 0;
    core::ImageSize image;
    core::Camera camera;
    DrawStyle style;
    std::vector<Shape> shapes;
    // The styles of the shapes; styles[0] is DrawStyle's ink (no rule matched).
    std::vector<InkStyle> styles;
    // The shapes are strokes with a drawing order (group, level, parent, order): brush_drawing's.
    bool drawing_order = false;
    // Drawn first, under every line; none unless set (tone_layer).
    ToneLayer tone = {};
};

// The ink of a shape (DrawStyle's when the drawing lists no styles).
InkStyle ink_of(const Drawing& drawing, const Shape& shape);
// "#rrggbb" a shape is drawn in: its style's colour, darkened as the shape says.
std::string color_of(const Drawing& drawing, const Shape& shape);
// Width of a stroked centerline.
double line_width_of(const Drawing& drawing, const Shape& shape);
// Dash pattern (px) of a stroked centerline: its style's, else 3 and 2 line widths for a hidden
// line; empty: solid.
std::vector<double> dashes_of(const Drawing& drawing, const Shape& shape);
// Where a stroked centerline's dash pattern starts: u at its start for a style's pattern (the
// dashes stay anchored to the stroke), 0 for the hidden lines' own.
double dash_offset_of(const Drawing& drawing, const Shape& shape);

// Every polyline as a constant-width centerline, one shape per polyline.
Drawing centerline_drawing(const core::FrameLines& frame, const DrawStyle& style);

// Brush strokes: each drawn visible stroke as its filled outline, or with `centerline` as its
// drawn centerline at constant width (pen plotters, cutters); hidden strokes as dashed
// centerlines. Strokes too short to draw are left out.
Drawing brush_drawing(const core::FrameLines& frame, const core::FrameStrokes& strokes, const DrawStyle& style,
                      bool centerline);

// "#rrggbb" of an sRGB colour with components in [0, 1] (core::color_hex).
std::string hex_color(const glm::dvec3& rgb);

// The line layers of a drawing: one per line kind, then the hidden lines (above the tone layer,
// when there is one).
enum class Layer : uint8_t { kSilhouette, kBoundary, kCrease, kIntersection, kHidden };
// In drawing order.
inline constexpr std::array<Layer, 5> kAllLayers = {Layer::kSilhouette, Layer::kBoundary, Layer::kCrease,
                                                    Layer::kIntersection, Layer::kHidden};
// "silhouette", "boundary", "crease" (the line kinds' names) or "hidden": the SVG layer's id.
const char* layer_name(Layer layer);
// Opacity of a whole layer (halved for hidden lines) of the shapes `selected` picks: their
// styles' opacity when they share one (or DrawStyle's without shapes), else 1 and each shape
// carries its own (shape_opacity).
template <typename Selected>
double layer_opacity(const Drawing& drawing, Layer layer, Selected selected);
// The opacity a shape carries itself inside a layer of that opacity: 1 when the layer carries it.
double shape_opacity(const Drawing& drawing, const Shape& shape, double layer_opacity);
// The layer a shape belongs to.
Layer layer_of(const Shape& shape);

// How line layers are grouped (--layers): by line kind; one layer per object with its kind
// layers inside; one layer per style with its kind layers inside.
enum class LayerGrouping : uint8_t { kKind, kObject, kStyle };

// A kind layer of lines as the writers group them: under kObject and kStyle grouping inside its
// object's or style's layer (`parent_id`, `parent_label`), else at the top (both empty).
struct LineLayer {
    std::string parent_id;     // "object-N", "object-none", "style-NAME" or "unstyled"
    std::string parent_label;  // the object's or style's name ("none", "unstyled" without one)
    Layer kind = Layer::kSilhouette;
    std::vector<uint32_t> shapes;  // indices into Drawing::shapes, in drawing order
    double opacity = 1.0;          // layer_opacity of those shapes
};

// The drawing's line layers in drawing order (the tone layer, when there is one, comes under
// them all). By kind: every kind, the intersection and hidden layers only when they hold lines.
// By object (a drawing without objects is grouped by kind): the objects in index order, the
// shapes without one ("none") first. By style: the styles in the order of their rules, the
// unstyled shapes first. Inside an object or a style, only the kinds that hold lines.
std::vector<LineLayer> line_layers(const Drawing& drawing, LayerGrouping grouping);

template <typename Selected>
double layer_opacity(const Drawing& drawing, Layer layer, Selected selected) {
    const double factor = layer == Layer::kHidden ? 0.5 : 1.0;
    bool any = false;
    double shared = drawing.style.opacity;
    for (const Shape& s : drawing.shapes) {
        if (layer_of(s) != layer || !selected(s)) continue;
        const double opacity = ink_of(drawing, s).opacity;
        if (any && opacity != shared) return factor;
        shared = opacity;
        any = true;
    }
    return factor * shared;
}

}  // namespace inkline::output
