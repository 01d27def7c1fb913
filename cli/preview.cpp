// SPDX-License-Identifier: MIT
#include "cli/preview.h"

#include "core/error.h"
#include "core/pipeline/stopwatch.h"
#include "core/scene/frame_pattern.h"
#include "export/atomic_file.h"
#include "export/drawing.h"
#include "export/png.h"
#include "gl/brush_tip.h"

namespace inkline::cli {

Preview::Preview(const gl::Context* shared, const RenderArgs& args, const core::Scene& scene) {
    const gl::Context* context = shared;
    if (!context) {
        try {
            own_context_ = gl::create_context(gl::parse_backend(args.gl_backend));
        } catch (const gl::ContextError& e) {
            throw InputError(std::string("--preview: no OpenGL context: ") + e.what());
        }
        context = own_context_.get();
    }
    gl::PreviewOptions options;
    const std::string& underlay = args.preview_underlay;
    if (underlay == "flat") {
        options.underlay = gl::Underlay::kFlat;
    } else if (underlay == "toon") {
        options.underlay = gl::Underlay::kToon;
    } else if (underlay != "none") {
        throw InputError("--preview-underlay '" + quote_value(underlay) + "': expected none, flat or toon");
    }
    if (!args.background.empty()) {
        const output::Rgb bg = output::parse_color(args.background, "--background");
        options.background = glm::dvec3(bg.r, bg.g, bg.b);
    }
    const gl::BrushTip tip = scene.brush.tip.empty() ? gl::default_brush_tip() : gl::load_brush_tip(scene.brush.tip);
    renderer_ = std::make_unique<gl::PreviewRenderer>(*context, scene.brush, tip, options);
    tone_ = scene.tone;
    crease_angle_deg_ = core::tone_crease_angle_deg(scene);
    renderer_->prepare(scene.image);
}

Preview::~Preview() = default;

void Preview::write(core::FrameResult& drawn, const std::string& pattern) {
    core::Stopwatch clock;
    const gl::PreviewTone tone{.tone = drawn.tone.mode == core::ToneMode::kNone ? nullptr : &drawn.tone,
                               .color = tone_.color,
                               .opacity = tone_.opacity};
    const gl::PreviewImage image = renderer_->render(
        drawn.lines, drawn.strokes,
        {.mesh = drawn.mesh, .world_from_object = drawn.world_from_object, .table = drawn.table,
         .crease_angle_deg = crease_angle_deg_},
        tone);
    output::write_file_atomically(core::format_frame(pattern, drawn.lines.frame),
                                  output::png_from_rgba(image.width, image.height, image.rgba));
    drawn.lines.stats.ms.emplace_back("preview", clock.lap_ms());
}

}  // namespace inkline::cli
