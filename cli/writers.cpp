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
#include <filesystem>
#include <optional>

#include <unistd.h>

namespace inkline::cli {
namespace fs = std::filesystem;

Writers::Writers(const Outputs& outputs, const RenderArgs& args, const core::Scene& scene)
    : outputs_(outputs), centerline_(args.centerline) {
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

size_t Writers::write(core::FrameResult& drawn) {
    core::FrameLines& frame = drawn.lines;
    size_t files = 0;
    core::Stopwatch clock;
    const output::Drawing drawing = output::brush_drawing(frame, drawn.strokes, style_, centerline_);
    if (!outputs_.svg.empty()) {
        output::write_file_atomically(core::format_frame(outputs_.svg, frame.frame), output::svg_document(drawing, svg_options_));
        ++files;
    }
    frame.stats.ms.emplace_back("svg", clock.lap_ms());
    if (!outputs_.png.empty()) {
        output::write_file_atomically(core::format_frame(outputs_.png, frame.frame), output::png_image(drawing));
        ++files;
    }
    frame.stats.ms.emplace_back("png", clock.lap_ms());
    if (outputs_.pdf_per_frame) {
        output::PdfDocument page(pdf_options_);
        page.add_page(drawing);
        output::write_file_atomically(core::format_frame(outputs_.pdf, frame.frame), page.finish());
        ++files;
    } else if (pdf_) {
        pdf_->add_page(drawing);
    }
    frame.stats.ms.emplace_back("pdf", clock.lap_ms());
    if (!outputs_.json.empty()) {
        output::write_file_atomically(core::format_frame(outputs_.json, frame.frame),
                                      output::polylines_json(frame, &drawn.strokes));
        ++files;
    }
    return files;
}

size_t Writers::write_animated_svg(const core::FrameResult& drawn, const core::WriteOnSchedule& schedule) {
    if (outputs_.animated_svg.empty()) return 0;
    const output::Drawing drawing = output::brush_drawing(drawn.lines, drawn.strokes, style_, centerline_);
    const output::WriteOnAnimation animation = output::write_on_animation(drawn.strokes, schedule);
    output::SvgOptions options = svg_options_;
    options.write_on = &animation;
    output::write_file_atomically(core::format_frame(outputs_.animated_svg, drawn.lines.frame),
                                  output::svg_document(drawing, options));
    return 1;
}

size_t Writers::finish(bool complete, const std::function<void(const std::string&)>& warn) {
    if (!pdf_ || pdf_->pages() == 0) return 0;
    std::unique_ptr<output::PdfDocument> doc = std::move(pdf_);
    std::error_code ec;
    if (!complete && fs::exists(outputs_.pdf, ec)) {
        warn(quote_value(outputs_.pdf, 160) + ": kept as it was; the " + std::to_string(doc->pages()) +
             " page(s) of this failed run are not written over it");
        return 0;
    }
    output::write_file_atomically(outputs_.pdf, doc->finish());
    return 1;
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
