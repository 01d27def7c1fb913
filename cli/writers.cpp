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
#include <functional>
#include <optional>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <signal.h>
#include <unistd.h>

namespace inkline::cli {
namespace fs = std::filesystem;

namespace {

// Work on a thread of its own that takes no SIGINT, SIGTERM or SIGHUP, so that interrupts are
// handled on the thread that started the run (the handler removes the temporaries of every
// thread; write_file_atomically); on the caller's thread when no thread is to be had (a thread or
// memory limit). What the work throws is kept for wait().
class Job {
  public:
    explicit Job(std::function<void()> work) : work_(std::move(work)) {
        sigset_t interrupts, previous;
        sigemptyset(&interrupts);
        for (const int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&interrupts, s);
        // A new thread starts with its creator's signal mask.
        pthread_sigmask(SIG_BLOCK, &interrupts, &previous);
        try {
            thread_ = std::thread([this] { run(); });
        } catch (const std::system_error&) {
            // No thread to be had: the work runs below, on this one.
        } catch (...) {
            pthread_sigmask(SIG_SETMASK, &previous, nullptr);
            throw;
        }
        pthread_sigmask(SIG_SETMASK, &previous, nullptr);
        if (!thread_.joinable()) run();
    }
    ~Job() {
        if (thread_.joinable()) thread_.join();
    }
    Job(const Job&) = delete;
    Job& operator=(const Job&) = delete;

    // Waits for the work; throws what it threw.
    void wait() {
        if (thread_.joinable()) thread_.join();
        if (error_) std::rethrow_exception(error_);
    }

  private:
    void run() {
        try {
            work_();
        } catch (...) {
            error_ = std::current_exception();
        }
        work_ = nullptr;
    }

    std::function<void()> work_;
    std::exception_ptr error_;
    std::thread thread_;
};

// A frame whose files hold more points than this (dots, hatch points, stroke and outline points:
// some 100 MB of SVG and JSON text) has them written before the next frame is drawn.
constexpr size_t kPointsInFlight = 1'000'000;

size_t points_in_files(const core::FrameResult& drawn) {
    size_t points = drawn.tone.dots.size();
    for (const core::Hatch& h : drawn.tone.hatches) points += h.points_px.size();
    for (const core::Polyline& line : drawn.lines.polylines) points += line.points_px.size();
    for (const core::Stroke& s : drawn.strokes.strokes) {
        points += s.geometry.points_px.size();
        for (const core::Ring& ring : s.outline) points += ring.size();
    }
    return points;
}

}  // namespace

// One frame's PNG, drawn and encoded on a thread of its own beside the frame's other files.
class Writers::PngThread {
  public:
    explicit PngThread(std::shared_ptr<const output::Drawing> drawing)
        : job_([this, drawing = std::move(drawing)] { bytes_ = output::png_image(*drawing); }) {}

    // Waits for the encoding; returns the file's contents, or throws what stopped it.
    std::string take() {
        job_.wait();
        return std::move(bytes_);
    }

  private:
    std::string bytes_;
    Job job_;  // last: it starts once the rest is there
};

// One frame's files, made and written on a thread of their own.
class Writers::FrameFiles {
  public:
    FrameFiles(const Writers& writers, core::FrameResult drawn, Written written)
        : drawn_(without_mesh(std::move(drawn))), strokes_(drawn_.strokes.strokes.size()),
          written_(std::move(written)), writers_(writers), job_([this] { make_and_write(); }) {}

    // Waits for the files to be written and tells `written`; returns how many, or throws what
    // stopped them.
    size_t wait() {
        job_.wait();
        if (written_) written_(stats_, strokes_, files_);
        return files_;
    }

  private:
    // The mesh is valid only until the pipeline's next frame.
    static core::FrameResult without_mesh(core::FrameResult drawn) {
        drawn.mesh = nullptr;
        return drawn;
    }

    // Makes the frame's files and writes each once made, in order: SVG, PNG, PDF, JSON (so a
    // frame whose SVG cannot be written gets no PNG, and one file's text is held at a time).
    void make_and_write() {
        const Outputs& outputs = writers_.outputs_;
        const int frame = drawn_.lines.frame;
        core::Stopwatch clock;
        double write_ms = 0.0;
        const auto put = [&](const std::string& pattern, std::string bytes) {
            clock.lap_ms();
            output::write_file_atomically(core::format_frame(pattern, frame), bytes);
            ++files_;
            write_ms += clock.lap_ms();
        };
        // Shared with the PNG's thread, which only reads it.
        const auto drawing = std::make_shared<const output::Drawing>(writers_.drawing_of(drawn_));
        std::optional<PngThread> png;
        if (!outputs.png.empty()) png.emplace(drawing);
        std::string svg = outputs.svg.empty() ? std::string() : output::svg_document(*drawing, writers_.svg_options_);
        const double svg_ms = clock.lap_ms();
        if (!outputs.svg.empty()) put(outputs.svg, std::move(svg));
        double png_ms = 0.0;
        if (png) {
            std::string bytes = png->take();
            png_ms = clock.lap_ms();
            put(outputs.png, std::move(bytes));
        }
        double pdf_ms = 0.0;
        if (outputs.pdf_per_frame) {
            output::PdfDocument page(writers_.pdf_options_);
            page.add_page(*drawing);
            std::string bytes = page.finish();
            pdf_ms = clock.lap_ms();
            put(outputs.pdf, std::move(bytes));
        } else if (writers_.pdf_) {
            writers_.pdf_->add_page(*drawing);
            pdf_ms = clock.lap_ms();
        }
        core::FrameStats& stats = drawn_.lines.stats;
        stats.ms.emplace_back("svg", svg_ms);
        stats.ms.emplace_back("png", png_ms);
        stats.ms.emplace_back("pdf", pdf_ms);
        if (!outputs.json.empty()) {
            std::string json = output::polylines_json(drawn_.lines, &drawn_.strokes, &drawn_.tone);
            put(outputs.json, std::move(json));
        }
        stats_ = std::move(stats);
        stats_.ms.emplace_back("write", write_ms);
        drawn_ = {};  // only its stats are needed from here on
    }

    core::FrameResult drawn_;  // until its files are written
    size_t strokes_;
    core::FrameStats stats_;   // once they are
    Written written_;
    const Writers& writers_;
    size_t files_ = 0;  // written
    Job job_;           // last: it starts once the rest is there
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
        write_pending();
    } catch (...) {
        // The run is stopping with an error of its own, the one to report.
    }
}

size_t Writers::write_pending() {
    if (!pending_) return 0;
    const std::unique_ptr<FrameFiles> pending = std::move(pending_);
    return pending->wait();
}

output::Drawing Writers::drawing_of(const core::FrameResult& drawn) const {
    output::Drawing drawing = output::brush_drawing(drawn.lines, drawn.strokes, style_, centerline_);
    drawing.tone = output::tone_layer(drawn.tone, tone_);
    return drawing;
}

size_t Writers::write(core::FrameResult drawn, Written written) {
    // The previous frame's files first: its files, or its error, come before this frame's.
    size_t files = write_pending();
    const bool large = points_in_files(drawn) > kPointsInFlight;
    pending_ = std::make_unique<FrameFiles>(*this, std::move(drawn), std::move(written));
    // Two such frames are not held at once: this one's files are written before the next frame.
    if (large) files += write_pending();
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
    // The last frame's files first: their error stops the run before the PDF, as any frame's does.
    size_t files = write_pending();
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
