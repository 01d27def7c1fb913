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
// files are made (drawn, formatted, its PNG encoded) and written on a thread of their own while
// the caller goes on with the next frame, one frame in flight (a frame with very many points has
// them written at once). The next write() or finish() waits for them and throws their error, if
// any, before anything of a later frame is written.
class Writers {
  public:
    // Told, on the caller's thread, of a frame whose files are all written: its stats (with the
    // stages of its files), its number of strokes and of files.
    using Written = std::function<void(const core::FrameStats& stats, size_t strokes, size_t files)>;

    // Refuses, before any file is written, a background, page, margin or dpi that cannot be
    // used and an image Cairo cannot draw (InputError).
    Writers(const Outputs& outputs, const RenderArgs& args, const core::Scene& scene);
    // Waits for the frame still being written (errors ignored: the run is already stopping with
    // another).
    ~Writers();
    Writers(const Writers&) = delete;
    Writers& operator=(const Writers&) = delete;

    // Waits for the previous frame's files (then tells its `written`), and starts making and
    // writing this frame's. Its stats.ms gain "svg", "png" and "pdf" (the times making them; the
    // JSON has these) and "write" (writing its files). Returns the number of files written.
    size_t write(core::FrameResult drawn, Written written = {});

    // Writes the frame's animated SVG of its write-on (--animated-svg), if asked. Returns the
    // number of files written.
    size_t write_animated_svg(const core::FrameResult& drawn, const core::WriteOnSchedule& schedule);

    // Writes the last frame's files (throwing its error, if any, before anything else), then the
    // multi-page PDF with the pages so far, also after a failure, so no drawn frame is lost; but
    // a run that failed never replaces a PDF already there, which may hold more of the sequence
    // (it says so through `warn`). Returns the number of files written.
    size_t finish(bool complete, const std::function<void(const std::string&)>& warn);

  private:
    class FrameFiles;
    class PngThread;
    // Waits for the frame being written and tells its `written`; returns the number of files.
    size_t write_pending();
    // What SVG, PNG and PDF draw of a frame: its strokes over its tone.
    output::Drawing drawing_of(const core::FrameResult& drawn) const;

    const Outputs& outputs_;
    bool centerline_;
    output::SvgOptions svg_options_;
    output::DrawStyle style_;
    core::ToneOptions tone_;  // the scene's, --tone applied
    output::PdfOptions pdf_options_;
    std::unique_ptr<output::PdfDocument> pdf_;  // pages added by the frames' threads, one at a time
    std::unique_ptr<FrameFiles> pending_;       // the frame being made, at most one
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
