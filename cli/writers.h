// SPDX-License-Identifier: MIT
// What a render writes for each drawn frame (SVG, PNG, PDF, polylines JSON), and the progress
// line on a terminal.
#pragma once

#include "cli/outputs.h"
#include "cli/render.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/strokes/write_on.h"
#include "export/drawing.h"
#include "export/pdf.h"
#include "export/svg.h"

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

namespace inkline::cli {

// Writes every per-frame file of a drawn frame; collects pages of a multi-page PDF. A frame's
// PNG is drawn and encoded on a thread of its own while the caller goes on with the next frame;
// its file is written at the next write() or at finish(), and its error, if any, is thrown
// there, before anything of a later frame is written.
class Writers {
  public:
    // Refuses, before any file is written, a background, page, margin or dpi that cannot be
    // used and an image Cairo cannot draw (InputError).
    Writers(const Outputs& outputs, const RenderArgs& args, const core::Scene& scene);
    // Writes the PNG still being made, if its frame got as far as its SVG (errors ignored: the
    // run is already stopping with another).
    ~Writers();
    Writers(const Writers&) = delete;
    Writers& operator=(const Writers&) = delete;

    // Writes the frame's files, and the previous frame's PNG first; adds the "svg", "png" and
    // "pdf" times to its stats.ms ("png": waiting for the previous frame's PNG and writing it).
    // Returns the number of files written.
    size_t write(core::FrameResult& drawn);

    // Writes the frame's animated SVG of its write-on (--animated-svg), if asked. Returns the
    // number of files written.
    size_t write_animated_svg(const core::FrameResult& drawn, const core::WriteOnSchedule& schedule);

    // Writes the last frame's PNG (throwing its error, if any, before anything else), then the
    // multi-page PDF with the pages so far, also after a failure, so no drawn frame is lost; but
    // a run that failed never replaces a PDF already there, which may hold more of the sequence
    // (it says so through `warn`). Returns the number of files written.
    size_t finish(bool complete, const std::function<void(const std::string&)>& warn);

  private:
    class PngThread;
    // Waits for the PNG being made and writes it; returns the number of files written.
    size_t write_pending_png();
    // What SVG, PNG and PDF draw of a frame: its strokes over its tone.
    output::Drawing drawing_of(const core::FrameResult& drawn) const;

    const Outputs& outputs_;
    bool centerline_;
    output::SvgOptions svg_options_;
    output::DrawStyle style_;
    core::ToneOptions tone_;  // the scene's, --tone applied
    output::PdfOptions pdf_options_;
    std::unique_ptr<output::PdfDocument> pdf_;
    std::unique_ptr<PngThread> png_;  // the PNG being made, at most one
};

// A progress line rewritten in place on a terminal: frames done, frames per second, time left.
class Progress {
  public:
    // Prints nothing unless enabled and stderr is a terminal.
    Progress(int total, bool enabled);
    void frame_done();

  private:
    int total_;
    int done_ = 0;
    bool enabled_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace inkline::cli
