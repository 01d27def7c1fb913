// SPDX-License-Identifier: MIT
// The GL preview (`--preview`): a frame's brush strokes drawn as quad strips textured with a
// brush-tip image used as alpha, offscreen and multisampled, read back as RGBA pixels. It is fed
// by the same strokes as the SVG/PDF (centerline, width, u), so it shows what they show, with
// ink texture on top; export/png.h's png_from_rgba() writes the pixels out.
// Strokes as textured strips: J. D. Northrup, L. Markosian. Artistic Silhouettes: A Hybrid
// Approach. NPAR 2000.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_lines.h"
#include "core/strokes/brush_style.h"
#include "core/strokes/strokes.h"
#include "core/tone/tone.h"
#include "gl/brush_tip.h"
#include "gl/context.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace inkline::gl {

// The mesh under the strokes, shaded with the frame's light.
enum class Underlay : uint8_t {
    kNone,  // strokes only
    kFlat,  // one shade per face, Lambert
    kToon,  // smooth normals (split at creases, with the mesh's edge table), three flat bands
};

struct PreviewOptions {
    // Samples per pixel, lowered to what the context allows (Mesa's llvmpipe: 4): antialiased
    // edges, as Cairo's, for the thin strokes of the lit side.
    int samples = 8;
    std::optional<glm::dvec3> background;  // sRGB in [0, 1], filled first; none: transparent
    Underlay underlay = Underlay::kNone;
    // Ink at full pressure (width_max_px) is this much darker than at width_min_px: colour times
    // (1 - pressure_darkening * pressure).
    double pressure_darkening = 0.35;
    // Length along the stroke of the whole tip image, px; 0: the image's aspect ratio times the
    // style's width_max_px, so the image keeps its proportions on the widest strokes.
    double tip_length_px = 0.0;
    // Hidden lines (`lines.hidden`) are plain dashed lines this wide where their style sets no
    // line_width_px, as the vector outputs' centerlines (export/drawing.h).
    double centerline_width_px = 1.5;
};

// The mesh drawn under the strokes with PreviewOptions::underlay: the frame's mesh (not owned;
// alive during render()) and its object motion. The camera and light come from the frame.
struct PreviewSurface {
    const core::Mesh* mesh = nullptr;
    glm::dmat4 world_from_object{1.0};
    // With the mesh's edge table (not owned), the toon underlay's normals are split where faces
    // meet at more than crease_angle_deg, one per smooth piece around a vertex as tone reads them
    // (core/lines/smooth_pieces.h): a box's faces are flat. Without, vertex normals throughout.
    const core::EdgeTable* table = nullptr;
    double crease_angle_deg = 180.0;
};

// The tone drawn under the strokes (docs/tone.md): the frame's dots and hatches, each sample
// of the image inked once however they overlap, as the vector outputs fill them.
struct PreviewTone {
    const core::FrameTone* tone = nullptr;  // not owned; alive during render(); none: no tone
    glm::dvec3 color{0.0};                  // sRGB in [0, 1]
    double opacity = 1.0;
};

// Straight-alpha RGBA pixels, sRGB, rows from the top: what png_from_rgba() takes.
struct PreviewImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // #width*height*4

    const uint8_t* pixel(int x, int y) const { return &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4]; }
};

// Sizes and timings of the last render().
struct PreviewStats {
    size_t strokes = 0;        // drawn
    size_t triangles = 0;      // strips and caps
    size_t tone_triangles = 0; // dots and hatches
    int samples = 0;           // per pixel, as used
    double geometry_ms = 0.0;  // strips built and uploaded
    double render_ms = 0.0;    // clear, underlay, strokes, resolve, finish
    double readback_ms = 0.0;  // pixels copied to the CPU and un-premultiplied
};

// Renders frames with one style and tip; holds the GL objects between frames.
class PreviewRenderer {
  public:
    // `context` must be current on this thread and outlive this object. Throws ContextError when
    // the context cannot run the pass, InputError when the tip exceeds GL's texture size.
    PreviewRenderer(const Context& context, const core::BrushStyle& style, const BrushTip& tip,
                    const PreviewOptions& options = {});
    ~PreviewRenderer();
    PreviewRenderer(const PreviewRenderer&) = delete;
    PreviewRenderer& operator=(const PreviewRenderer&) = delete;

    // Checks that images of `image` size can be drawn and allocates their framebuffers, so a
    // run can fail before it writes anything. Throws InputError beyond GL's framebuffer size
    // limit, ContextError when the framebuffers cannot be made. render() does the same.
    void prepare(core::ImageSize image);

    // Draws the visible, drawn strokes of one frame at frame.image, over the underlay when the
    // options ask for one (then `surface.mesh` is required), and the hidden lines above them as
    // the vector outputs draw them: dashed, at half the ink's opacity, in their style's colour.
    // Strokes overlap like layers of ink; a stroke never darkens itself where it folds over.
    // Throws InputError when the image exceeds GL's framebuffer size limit.
    PreviewImage render(const core::FrameLines& frame, const core::FrameStrokes& strokes,
                        const PreviewSurface& surface = {}, const PreviewTone& tone = {});

    const PreviewStats& last_render() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace inkline::gl
