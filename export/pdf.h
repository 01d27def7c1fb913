// SPDX-License-Identifier: MIT
// PDF through Cairo: vector fills, one page per frame, for print at a physical size.
#pragma once

#include "export/drawing.h"

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
    std::string title = "inkline";
    // ISO 8601 "YYYY-MM-DDThh:mm:ss" written as the document's creation date; empty: Cairo's
    // clock. A fixed date makes the file depend on its input alone.
    std::string creation_date;
};

// A PDF document built page by page in memory; finish() returns the file contents.
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
    size_t pages_ = 0;
};

}  // namespace inkline::output
