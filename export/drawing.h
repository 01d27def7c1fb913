// SPDX-License-Identifier: MIT
// What a frame looks like on paper, independent of the file format: shapes grouped by line kind,
// each a filled outline or a stroked centerline. SVG, PDF and PNG all draw from this.
#pragma once

#include "core/pipeline/frame_lines.h"
#include "core/strokes/bezier_fit.h"
#include "core/strokes/strokes.h"

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <optional>
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
};

struct Drawing {
    int frame = 0;
    core::ImageSize image;
    core::Camera camera;
    DrawStyle style;
    std::vector<Shape> shapes;
};

// Every polyline as a constant-width centerline, one shape per polyline.
Drawing centerline_drawing(const core::FrameLines& frame, const DrawStyle& style);

// Brush strokes: each drawn visible stroke as its filled outline, or with `centerline` as its
// drawn centerline at constant width (pen plotters, cutters); hidden strokes as dashed
// centerlines. Strokes too short to draw are left out.
Drawing brush_drawing(const core::FrameLines& frame, const core::FrameStrokes& strokes, const DrawStyle& style,
                      bool centerline);

// "#rrggbb" of an sRGB colour with components in [0, 1] (core::color_hex).
std::string hex_color(const glm::dvec3& rgb);

// The layers of a drawing: one per line kind, then the hidden lines.
enum class Layer : uint8_t { kSilhouette, kBoundary, kCrease, kIntersection, kHidden };
// In drawing order.
inline constexpr std::array<Layer, 5> kAllLayers = {Layer::kSilhouette, Layer::kBoundary, Layer::kCrease,
                                                    Layer::kIntersection, Layer::kHidden};
// "silhouette", "boundary", "crease" (the line kinds' names) or "hidden": the SVG layer's id.
const char* layer_name(Layer layer);
// Opacity of a whole layer: the style's, halved for hidden lines.
double layer_opacity(const DrawStyle& style, Layer layer);
// The layer a shape belongs to.
Layer layer_of(const Shape& shape);

}  // namespace inkline::output
