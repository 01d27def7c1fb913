// SPDX-License-Identifier: MIT
// What Cairo and PDF cannot take is refused before drawing: PNG sides, PDF page sizes, margins;
// a title that is not UTF-8 still makes a PDF; Cairo running out of memory while drawing is
// std::bad_alloc, never a blank or half-drawn image.
#include "export/pdf.h"
#include "export/png.h"
#include "tests/support/run.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <new>
#include <string>

#include <malloc.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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

// Runs `f` in a child process whose address space may grow by `headroom` bytes only; returns
// its exit status: 0 done, 4 std::bad_alloc, 2 InputError, 3 OutputError, 1 anything else.
template <typename F>
int exit_code_with_memory_headroom(size_t headroom, F f) {
    const pid_t child = ::fork();
    if (child == 0) {
        ::malloc_trim(0);  // memory freed earlier is not headroom
        long pages = 0;
        if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
            if (std::fscanf(statm, "%ld", &pages) != 1) pages = 0;
            std::fclose(statm);
        }
        if (pages <= 0) ::_exit(9);
        const rlim_t limit = rlim_t(pages) * rlim_t(::sysconf(_SC_PAGESIZE)) + headroom;
        const rlimit r{limit, limit};
        if (::setrlimit(RLIMIT_AS, &r) != 0) ::_exit(9);
        try {
            f();
        } catch (const std::bad_alloc&) {
            ::_exit(4);
        } catch (const InputError&) {
            ::_exit(2);
        } catch (const OutputError&) {
            ::_exit(3);
        } catch (...) {
            ::_exit(1);
        }
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A 4096x4096 drawing with one filled square per layer: each layer is drawn in a group of its
// own, a second image as large as the first.
output::Drawing squares() {
    output::Drawing d = blank(4096, 4096);
    d.shapes.push_back({.stroke_id = 1, .filled = true, .paths = {{{100, 100}, {4000, 100}, {4000, 4000}, {100, 4000}}}});
    return d;
}

TEST(CairoStatus, PngThatRunsOutOfMemoryWhileDrawingIsBadAlloc) {
    if (test::kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer reserves its shadow memory beyond any RLIMIT_AS";
    const output::Drawing d = squares();
    EXPECT_EQ(exit_code_with_memory_headroom(size_t(1) << 32, [&] { output::png_image(d); }), 0);
    // Room for the image (64 MiB) but not for a layer's group as well.
    EXPECT_EQ(exit_code_with_memory_headroom(size_t(80) << 20, [&] { output::png_image(d); }), 4);
    // No room for the image.
    EXPECT_EQ(exit_code_with_memory_headroom(size_t(16) << 20, [&] { output::png_image(d); }), 4);
}

TEST(CairoStatus, PdfThatRunsOutOfMemoryIsBadAlloc) {
    if (test::kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer reserves its shadow memory beyond any RLIMIT_AS";
    // One stroke of 400000 scattered points: page content that does not compress, MiBs of it.
    output::Drawing d = blank(4096, 4096);
    output::Shape s;
    s.paths.emplace_back();
    uint32_t state = 12345;
    auto next = [&] { return double((state = state * 1664525u + 1013904223u) >> 8) / double(1 << 24) * 4000.0; };
    for (int i = 0; i < 400'000; ++i) s.paths.back().push_back({next(), next()});
    d.shapes.push_back(std::move(s));
    auto pdf = [&] {
        output::PdfDocument doc({});
        doc.add_page(d);
        doc.finish();
    };
    EXPECT_EQ(exit_code_with_memory_headroom(size_t(4) << 30, pdf), 0);
    EXPECT_EQ(exit_code_with_memory_headroom(size_t(2) << 20, pdf), 4);
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
