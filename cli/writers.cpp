// SPDX-License-Identifier: MIT
#include "cli/writers.h"

#include "core/error.h"
#include "core/pipeline/stopwatch.h"
#include "core/scene/frame_pattern.h"
#include "export/atomic_file.h"
#include "export/json.h"
#include "export/pdf.h"
#include "export/png.h"
#include "export/svg.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <system_error>
#include <thread>
#include <utility>

#include <signal.h>
#include <unistd.h>

namespace inkline::cli {
namespace fs = std::filesystem;

// One frame's PNG, drawn and encoded on a thread of its own. The file is written by the caller:
// write_file_atomically's interrupt cleanup follows one temporary at a time, and the thread
// takes no SIGINT, SIGTERM or SIGHUP, so the handler always runs where that temporary is known.
class Writers::PngThread {
  public:
    PngThread(fs::path path, std::shared_ptr<const output::Drawing> drawing)
        : path_(std::move(path)), drawing_(std::move(drawing)) {
        sigset_t interrupts, previous;
        sigemptyset(&interrupts);
        for (const int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&interrupts, s);
        // A new thread starts with its creator's signal mask.
        pthread_sigmask(SIG_BLOCK, &interrupts, &previous);
        try {
            thread_ = std::thread([this] { encode(); });
        } catch (const std::system_error&) {
            // No thread to be had (a thread or memory limit): the caller's thread does the work.
            encode();
        }
        pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    }
    ~PngThread() {
        if (thread_.joinable()) thread_.join();
    }
    PngThread(const PngThread&) = delete;
    PngThread& operator=(const PngThread&) = delete;

    const fs::path& path() const { return path_; }

    // Waits for the encoding; returns the file's contents, or throws what stopped it.
    std::string take() {
        if (thread_.joinable()) thread_.join();
        if (error_) std::rethrow_exception(error_);
        return std::move(bytes_);
    }

  private:
    void encode() {
        try {
            bytes_ = output::png_image(*drawing_);
        } catch (...) {
            error_ = std::current_exception();
        }
        drawing_.reset();
    }

    fs::path path_;
    std::shared_ptr<const output::Drawing> drawing_;
    std::string bytes_;
    std::exception_ptr error_;
    std::thread thread_;
};

Writers::Writers(const Outputs& outputs, const RenderArgs& args, const core::Scene& scene)
    : outputs_(outputs), centerline_(args.centerline), tone_(scene.tone) {
    const fs::path& mesh_name = scene.mesh.path;
    style_ = output::brush_draw_style(scene.brush);
    style_.background = args.background.empty() ? std::nullopt : std::optional(args.background);
    if (style_.background) output::parse_color(*style_.background, "--background");
    style_.path_format = output::parse_path_format(args.path_format, "--path-format");
    if (args.layers == "object") {
        svg_options_.layers = output::SvgLayers::kObject;
    } else if (args.layers == "style") {
        svg_options_.layers = output::SvgLayers::kStyle;
    } else if (args.layers != "kind") {
        throw InputError("--layers '" + quote_value(args.layers) + "': expected kind, object or style");
    }
    pdf_options_.layers = svg_options_.layers;
    pdf_options_.page = args.page.empty() ? std::nullopt : std::optional(output::parse_page_size(args.page));
    pdf_options_.margin_mm = args.margin_mm;
    pdf_options_.dpi = args.dpi;
    if (!(args.dpi > 0.0 && args.dpi <= 10000.0)) throw InputError("--dpi: must be between 0 and 10000");
    if (!(args.margin_mm >= 0.0 && args.margin_mm < 1000.0)) throw InputError("--margin: must be 0..1000 mm");
    pdf_options_.title = fs::path(mesh_name).stem().string();
    pdf_options_.creation_date = output::reproducible_creation_date(args.input);
    // What Cairo cannot draw is refused before any file is written.
    if (!outputs_.png.empty() || !outputs_.preview.empty()) {
        output::check_png_size(scene.image.width, scene.image.height);
    }
    if (!outputs_.pdf.empty()) output::check_pdf_page(pdf_options_, scene.image.width, scene.image.height);
    if (!outputs_.pdf.empty() && !outputs_.pdf_per_frame) pdf_ = std::make_unique<output::PdfDocument>(pdf_options_);
}

Writers::~Writers() {
    try {
        write_pending_png();
    } catch (...) {
        // The run is stopping with an error of its own, the one to report.
    }
}

size_t Writers::write_pending_png() {
    if (!png_) return 0;
    const std::unique_ptr<PngThread> pending = std::move(png_);
    output::write_file_atomically(pending->path(), pending->take());
    return 1;
}

output::Drawing Writers::drawing_of(const core::FrameResult& drawn) const {
    output::Drawing drawing = output::brush_drawing(drawn.lines, drawn.strokes, style_, centerline_);
    drawing.tone = output::tone_layer(drawn.tone, tone_);
    return drawing;
}

size_t Writers::write(core::FrameResult& drawn) {
    core::FrameLines& frame = drawn.lines;
    size_t files = 0;
    core::Stopwatch clock;
    // Shared with the PNG thread, which only reads it.
    const auto drawing = std::make_shared<const output::Drawing>(drawing_of(drawn));
    double svg_ms = clock.lap_ms(), png_ms = 0.0;
    if (!outputs_.png.empty()) {
        // The previous frame's PNG first: its file, or its error, comes before this frame's files.
        files += write_pending_png();
        png_ = std::make_unique<PngThread>(core::format_frame(outputs_.png, frame.frame), drawing);
        png_ms = clock.lap_ms();
    }
    if (!outputs_.svg.empty()) {
        try {
            output::write_file_atomically(core::format_frame(outputs_.svg, frame.frame),
                                          output::svg_document(*drawing, svg_options_));
        } catch (...) {
            png_.reset();  // a frame whose SVG failed gets no PNG, as when the PNG followed it
            throw;
        }
        ++files;
    }
    svg_ms += clock.lap_ms();
    frame.stats.ms.emplace_back("svg", svg_ms);
    frame.stats.ms.emplace_back("png", png_ms);
    if (outputs_.pdf_per_frame) {
        output::PdfDocument page(pdf_options_);
        page.add_page(*drawing);
        output::write_file_atomically(core::format_frame(outputs_.pdf, frame.frame), page.finish());
        ++files;
    } else if (pdf_) {
        pdf_->add_page(*drawing);
    }
    frame.stats.ms.emplace_back("pdf", clock.lap_ms());
    if (!outputs_.json.empty()) {
        output::write_file_atomically(core::format_frame(outputs_.json, frame.frame),
                                      output::polylines_json(frame, &drawn.strokes, &drawn.tone));
        ++files;
    }
    return files;
}

size_t Writers::write_animated_svg(const core::FrameResult& drawn, const core::WriteOnSchedule& schedule) {
    if (outputs_.animated_svg.empty()) return 0;
    const output::Drawing drawing = drawing_of(drawn);
    const output::WriteOnAnimation animation = output::write_on_animation(drawn.strokes, schedule);
    output::SvgOptions options = svg_options_;
    options.write_on = &animation;
    output::write_file_atomically(core::format_frame(outputs_.animated_svg, drawn.lines.frame),
                                  output::svg_document(drawing, options));
    return 1;
}

size_t Writers::finish(bool complete, const std::function<void(const std::string&)>& warn) {
    // The last frame's PNG first: its error stops the run before the PDF, as any frame's does.
    size_t files = write_pending_png();
    if (!pdf_ || pdf_->pages() == 0) return files;
    std::unique_ptr<output::PdfDocument> doc = std::move(pdf_);
    std::error_code ec;
    if (!complete && fs::exists(outputs_.pdf, ec)) {
        warn(quote_value(outputs_.pdf, 160) + ": kept as it was; the " + std::to_string(doc->pages()) +
             " page(s) of this failed run are not written over it");
        return files;
    }
    output::write_file_atomically(outputs_.pdf, doc->finish());
    return files + 1;
}

Progress::Progress(int total, bool enabled) : total_(total), enabled_(enabled && ::isatty(STDERR_FILENO)) {}

void Progress::frame_done() {
    if (!enabled_) return;
    ++done_;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double fps = seconds > 0.0 ? done_ / seconds : 0.0;
    const int left = fps > 0.0 ? int((total_ - done_) / fps + 0.5) : 0;
    std::fprintf(stderr, "\rinkline: frame %d/%d  %.1f frames/s  %d:%02d left ", done_, total_, fps, left / 60,
                 left % 60);
    if (done_ == total_) std::fprintf(stderr, "\n");
}

}  // namespace inkline::cli
