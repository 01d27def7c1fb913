// SPDX-License-Identifier: MIT
// What Cairo and PDF cannot take is refused before drawing: PNG sides, PDF page sizes, margins;
// a title that is not UTF-8 still makes a PDF.
#include "export/pdf.h"
#include "export/png.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace inkline {
namespace {

output::Drawing blank(int width, int height) {
    output::Drawing d;
    d.image = {width, height};
    return d;
}

// The message of the InputError `f` throws, or "" (and a failure) when it throws none.
template <typename F>
std::string input_error(F f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return "";
}

TEST(CairoLimits, PngSideOverCairosLimitIsAnInputError) {
    EXPECT_NO_THROW(output::check_png_size(output::kMaxPngSide, 1));
    EXPECT_NE(input_error([] { output::check_png_size(32768, 16); }).find("32768x16 px"), std::string::npos);
    EXPECT_NE(input_error([] { output::check_png_size(16, 40000); }).find("at most 32767 px"), std::string::npos);
    EXPECT_NE(input_error([] { output::png_image(blank(32768, 4)); }).find("32768x4"), std::string::npos);
}

TEST(CairoLimits, PdfPageOutsidePdfsLimitsIsRefusedNamingDpi) {
    output::PdfOptions o;
    EXPECT_NO_THROW(output::check_pdf_page(o, 19200, 4));  // 14400 x 3 pt at 96 dpi
    o.dpi = 1e-300;
    const std::string huge = input_error([&] { output::check_pdf_page(o, 1024, 1024); });
    EXPECT_EQ(huge.rfind("--dpi 1e-300: ", 0), 0u) << huge;
    EXPECT_NE(huge.find("3 to 14400 pt"), std::string::npos) << huge;
    o.dpi = 96.0;
    EXPECT_NE(input_error([&] { output::check_pdf_page(o, 19201, 100); }).find("--dpi 96"), std::string::npos);
    EXPECT_NE(input_error([&] { output::check_pdf_page(o, 100, 3); }).find("--dpi 96"), std::string::npos);
    output::PdfDocument doc(o);
    EXPECT_THROW(doc.add_page(blank(20000, 10)), InputError);
    EXPECT_EQ(doc.pages(), 0u);
}

TEST(CairoLimits, MarginThatLeavesNoRoomIsRefusedNamingMargin) {
    output::PdfOptions o;
    o.page = output::parse_page_size("A4");
    o.margin_mm = 104.0;
    EXPECT_NO_THROW(output::check_pdf_page(o, 1024, 768));
    o.margin_mm = 105.0;  // landscape A4 is 210 mm high
    const std::string message = input_error([&] { output::check_pdf_page(o, 1024, 768); });
    EXPECT_EQ(message, "--margin 105 mm leaves no room for the image on a 297x210 mm page");
    o.page = output::parse_page_size("1x1mm");
    o.margin_mm = 0.0;
    EXPECT_NE(input_error([&] { output::check_pdf_page(o, 10, 10); }).find("--page 1x1mm"), std::string::npos);
}

TEST(CairoLimits, TitleThatIsNotUtf8StillMakesAPdf) {
    output::PdfOptions o;
    o.title = "bad\xff\xfe name";
    o.page = output::parse_page_size("A4");
    output::PdfDocument doc(o);
    doc.add_page(blank(64, 64));
    const std::string pdf = doc.finish();
    EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
    EXPECT_NE(pdf.find("%%EOF"), std::string::npos);
}

}  // namespace
}  // namespace inkline
