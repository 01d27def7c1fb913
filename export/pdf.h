// SPDX-License-Identifier: MIT
// PDF through Cairo: vector fills, one page per frame, for print at a physical size, its line
// layers as PDF layers (put together with qpdf).
#pragma once

#include "export/drawing.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace inkline::output {

struct PageSize {
    double width_mm = 0.0;
    double height_mm = 0.0;
    bool named = false;  // A4, A3, Letter: turned to landscape for landscape images
};

// "A4", "A3", "Letter" or "WxHmm" (e.g. "200x150mm"); throws InputError otherwise.
PageSize parse_page_size(const std::string& text);

struct PdfOptions {
    std::optional<PageSize> page;  // none: the page is the image at `dpi`
    double margin_mm = 10.0;       // with a page size: the image is fitted inside the margins
    double dpi = 96.0;             // without a page size: pixels per inch of the image
    std::string title = "inkline";  // any bytes: what is not UTF-8 is written as U+FFFD
    // ISO 8601 "YYYY-MM-DDThh:mm:ss" written as the document's creation date; empty: Cairo's
    // clock. A fixed date makes the file depend on its input alone.
    std::string creation_date;
    // The line layers as PDF layers (optional content groups, which Acrobat, Illustrator and
    // other PDF tools with a layers panel show as layers), grouped as the SVG's are (--layers),
    // the tone in a layer of its own under them; none: one drawing per page, no layers.
    std::optional<LayerGrouping> layers = LayerGrouping::kKind;
};

// The creation date of a reproducible PDF: SOURCE_DATE_EPOCH when set (the reproducible-builds
// convention), else `input`'s modification time; empty when neither can be had. The same input
// gives byte-identical PDFs, whoever writes them.
std::string reproducible_creation_date(const std::filesystem::path& input);

// PDF pages are 3 to 14400 pt (1/72 in) a side: PDF's own limits (ISO 32000-1, annex C), which
// every reader honours; 14400 pt is 5080 mm.
constexpr double kMinPdfPagePoints = 3.0;
constexpr double kMaxPdfPagePoints = 14400.0;

// Throws InputError when pages of an image of width x height px cannot be made with `options`:
// a page side outside the limits above (naming --dpi or --page) or margins that leave no room
// for the image (naming --margin). Check before anything is written.
void check_pdf_page(const PdfOptions& options, int width, int height);

// A PDF document built page by page in memory; finish() returns the file contents. Cairo
// failures throw std::bad_alloc (out of memory), InputError or OutputError; a document that
// failed cannot be finished, so no partial PDF is written.
class PdfDocument {
  public:
    explicit PdfDocument(const PdfOptions& options);
    ~PdfDocument();
    PdfDocument(const PdfDocument&) = delete;
    PdfDocument& operator=(const PdfDocument&) = delete;

    void add_page(const Drawing& drawing);
    size_t pages() const { return pages_; }
    std::string finish();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    size_t pages_ = 0;  // frames
};

}  // namespace inkline::output
