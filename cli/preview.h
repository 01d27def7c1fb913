// SPDX-License-Identifier: MIT
// `--preview`: each drawn frame through the GL preview (strokes textured with the brush tip),
// written as a PNG.
#pragma once

#include "cli/render.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "gl/context.h"
#include "gl/preview.h"

#include <cstddef>
#include <memory>
#include <string>

namespace inkline::cli {

class Preview {
  public:
    // Sets the preview up before the first frame: on `shared` (the depth pass's context) when
    // not null, else on a context of its own; its framebuffers are allocated at the scene's
    // image size, so a GL that cannot draw it fails the run before anything is written.
    // Throws InputError (bad --preview-underlay or --background, no context, too large).
    Preview(const gl::Context* shared, const RenderArgs& args, const core::Scene& scene);
    ~Preview();

    // Renders a drawn frame and writes it to `pattern`'s file for the frame; adds the "preview"
    // time to its stats.ms.
    void write(core::FrameResult& drawn, const std::string& pattern);

  private:
    std::unique_ptr<gl::Context> own_context_;  // declared first: outlives the renderer
    std::unique_ptr<gl::PreviewRenderer> renderer_;
    core::ToneOptions tone_;  // the scene's: the colour and opacity of the frames' tone
    double crease_angle_deg_ = 180.0;  // where the toon underlay's normals split, as tone's do
};

}  // namespace inkline::cli
