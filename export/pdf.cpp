// SPDX-License-Identifier: MIT
#include "export/pdf.h"

#include "core/error.h"
#include "export/internal/cairo_paint.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <regex>

namespace inkline::output {
namespace {

constexpr double kPointsPerInch = 72.0;
constexpr double kMmPerInch = 25.4;
constexpr double kLabelPoints = 8.0;  // size of the frame label printed in the bottom margin

double mm_to_points(double mm) { return mm / kMmPerInch * kPointsPerInch; }

}  // namespace

PageSize parse_page_size(const std::string& text) {
    std::string lower = text;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    if (lower == "a4") return {210.0, 297.0, true};
    if (lower == "a3") return {297.0, 420.0, true};
    if (lower == "letter") return {215.9, 279.4, true};
    static const std::regex custom(R"(^\s*(\d+(?:\.\d+)?)\s*x\s*(\d+(?:\.\d+)?)\s*mm\s*$)");
    std::smatch m;
    if (std::regex_match(lower, m, custom)) {
        const PageSize p{std::stod(m[1]), std::stod(m[2]), false};
        if (p.width_mm >= 1.0 && p.height_mm >= 1.0 && p.width_mm <= 5000.0 && p.height_mm <= 5000.0) return p;
    }
    throw InputError("--page '" + text + "': expected A4, A3, Letter or WxHmm with sides 1..5000 mm");
}

struct PdfDocument::Impl {
    PdfOptions options;
    std::string bytes;
    cairo_surface_t* surface = nullptr;
    cairo_t* cr = nullptr;
};

PdfDocument::PdfDocument(const PdfOptions& options) : impl_(std::make_unique<Impl>()) {
    impl_->options = options;
    // The real page size is set per page; the first page's is a placeholder.
    impl_->surface = cairo_pdf_surface_create_for_stream(internal::append_to_string, &impl_->bytes, 100, 100);
    cairo_pdf_surface_set_metadata(impl_->surface, CAIRO_PDF_METADATA_TITLE, options.title.c_str());
    cairo_pdf_surface_set_metadata(impl_->surface, CAIRO_PDF_METADATA_CREATOR, "inkline");
    if (!options.creation_date.empty()) {
        cairo_pdf_surface_set_metadata(impl_->surface, CAIRO_PDF_METADATA_CREATE_DATE, options.creation_date.c_str());
    }
    impl_->cr = cairo_create(impl_->surface);
}

PdfDocument::~PdfDocument() {
    if (impl_->cr) cairo_destroy(impl_->cr);
    if (impl_->surface) cairo_surface_destroy(impl_->surface);
}

void PdfDocument::add_page(const Drawing& drawing) {
    const PdfOptions& o = impl_->options;
    const double image_w = drawing.image.width, image_h = drawing.image.height;
    double page_w, page_h, scale, offset_x, offset_y;
    if (o.page) {
        PageSize p = *o.page;
        if (p.named && image_w > image_h) std::swap(p.width_mm, p.height_mm);
        page_w = mm_to_points(p.width_mm);
        page_h = mm_to_points(p.height_mm);
        const double margin = mm_to_points(o.margin_mm);
        const double avail_w = std::max(page_w - 2.0 * margin, 1.0), avail_h = std::max(page_h - 2.0 * margin, 1.0);
        scale = std::min(avail_w / image_w, avail_h / image_h);
        offset_x = (page_w - scale * image_w) / 2.0;
        offset_y = (page_h - scale * image_h) / 2.0;
    } else {
        scale = kPointsPerInch / o.dpi;
        page_w = image_w * scale;
        page_h = image_h * scale;
        offset_x = offset_y = 0.0;
    }
    cairo_pdf_surface_set_size(impl_->surface, page_w, page_h);
    const std::string label = "frame " + std::to_string(drawing.frame);
    cairo_pdf_surface_set_page_label(impl_->surface, label.c_str());

    cairo_t* cr = impl_->cr;
    cairo_save(cr);
    cairo_translate(cr, offset_x, offset_y);
    cairo_scale(cr, scale, scale);
    internal::paint_drawing(cr, drawing);
    cairo_restore(cr);
    if (o.page && o.margin_mm > 0.0) {
        // The frame number in the bottom margin, small and grey.
        cairo_save(cr);
        cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr, kLabelPoints);
        cairo_move_to(cr, mm_to_points(o.margin_mm), page_h - mm_to_points(o.margin_mm) / 2.0);
        cairo_show_text(cr, (o.title + " - " + label).c_str());
        cairo_restore(cr);
    }
    cairo_show_page(cr);
    ++pages_;
}

std::string PdfDocument::finish() {
    cairo_destroy(impl_->cr);
    impl_->cr = nullptr;
    cairo_surface_finish(impl_->surface);
    const cairo_status_t status = cairo_surface_status(impl_->surface);
    cairo_surface_destroy(impl_->surface);
    impl_->surface = nullptr;
    if (status != CAIRO_STATUS_SUCCESS) {
        throw InternalError(std::string("PDF encoding failed: ") + cairo_status_to_string(status));
    }
    return std::move(impl_->bytes);
}

}  // namespace inkline::output
