// SPDX-License-Identifier: MIT
// SVG, PNG and PDF of the same frame agree: rasterised by rsvg-convert and pdftoppm, compared
// with Cairo's PNG by ink coverage.
#include "export/pdf.h"
#include "export/png.h"
#include "export/svg.h"

#include "core/error.h"
#include "tests/support/obj.h"
#include "tests/support/pipeline.h"
#include "tests/support/raster.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <numbers>

namespace inkline {
namespace {

namespace fs = std::filesystem;

// Ink coverage of a PNG: alpha above one half for transparent pixels, or darker than mid-grey
// over an opaque background.
std::vector<uint8_t> coverage(const fs::path& png) { return test::png_file_coverage(png, test::Ink::kAlphaOrDark); }

class Raster : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    output::Drawing torus_drawing() {
        core::LineOptions lines;
        lines.hidden = true;
        core::FrameLines frame =
            test::trace(test::torus(1.0, 0.4, 48, 24), {.eye = {0.0, 2.6, 4.6}, .fov_y_deg = 40.0, .size = 512}, lines);
        output::DrawStyle style;
        style.centerline_width_px = 3.0;
        return output::centerline_drawing(frame, style);
    }
};

TEST_F(Raster, SvgIsWellFormedAndRendersLikeCairo) {
    const output::Drawing d = torus_drawing();
    test::write_text(dir / "f.svg", output::svg_document(d, {}));
    test::write_text(dir / "f.png", output::png_image(d));
    const test::RunResult lint = test::run_shell("xmllint --noout " + (dir / "f.svg").string());
    ASSERT_EQ(lint.code, 0) << lint.output;
    const test::RunResult rsvg =
        test::run_shell("rsvg-convert " + (dir / "f.svg").string() + " -o " + (dir / "rsvg.png").string());
    ASSERT_EQ(rsvg.code, 0) << rsvg.output;
    EXPECT_GE(test::iou(coverage(dir / "rsvg.png"), coverage(dir / "f.png")), 0.98);
}

TEST_F(Raster, BrushOutlinesRenderAlikeInSvgAndCairo) {
    const core::Mesh torus = test::torus(1.0, 0.4, 64, 32);
    const test::View view{.eye = {0.0, 2.6, 4.6}, .fov_y_deg = 40.0, .size = 512};
    const test::Drawn drawn = test::draw(torus, test::scene_for(view, torus));
    const output::Drawing d = output::brush_drawing(drawn.lines, drawn.strokes, {}, false);
    size_t filled = 0;
    for (const output::Shape& s : d.shapes) filled += s.filled;
    ASSERT_GT(filled, 0u);
    test::write_text(dir / "f.svg", output::svg_document(d, {}));
    test::write_text(dir / "f.png", output::png_image(d));
    ASSERT_EQ(test::run_shell("rsvg-convert " + (dir / "f.svg").string() + " -o " + (dir / "rsvg.png").string()).code, 0);
    EXPECT_GE(test::iou(coverage(dir / "rsvg.png"), coverage(dir / "f.png")), 0.98);
}

TEST_F(Raster, BezierOutlinesFollowThePolygonsAtOneAndFourTimesTheSize) {
    // A bumpy sphere drawn at 1024 px, its outlines written as polygons and as cubic curves: at
    // the default tolerance (0.5 px) the file is less than half the size and the ink nearly the
    // same; at 0.02 px, the ink is the same to 1% (and the file no smaller).
    const core::Mesh mesh = test::bumpy_sphere(test::icosphere(4), {.count = 30, .height_max = 0.1});
    const test::View view{.eye = {0.0, 1.0, 3.6}, .fov_y_deg = 40.0, .size = 1024};
    const test::Drawn drawn = test::draw(mesh, test::scene_for(view, mesh));
    const std::string polygon_svg = output::svg_document(output::brush_drawing(drawn.lines, drawn.strokes, {}, false), {});
    test::write_text(dir / "polygon.svg", polygon_svg);
    // Ink IoU of the curves against the polygons, rasterised by rsvg-convert at `zoom`.
    auto iou_at = [&](const std::string& name, int zoom) {
        const std::string z = std::to_string(zoom);
        for (const std::string& file : {std::string("polygon"), name}) {
            const std::string in = (dir / (file + ".svg")).string(), out = (dir / (file + z + ".png")).string();
            EXPECT_EQ(test::run_shell("rsvg-convert -z " + z + " " + in + " -o " + out).code, 0);
        }
        return test::iou(coverage(dir / ("polygon" + z + ".png")), coverage(dir / (name + z + ".png")));
    };
    for (const double tolerance : {0.5, 0.02}) {
        SCOPED_TRACE(tolerance);
        output::DrawStyle style;
        style.path_format = output::PathFormat::kBezier;
        style.bezier_tolerance_px = tolerance;
        const output::Drawing curved = output::brush_drawing(drawn.lines, drawn.strokes, style, false);
        size_t curved_paths = 0;
        for (const output::Shape& s : curved.shapes) {
            for (const auto& curves : s.curves) curved_paths += curves.empty() ? 0 : 1;
        }
        ASSERT_GT(curved_paths, 5u);
        const std::string svg = output::svg_document(curved, {});
        const std::string name = tolerance > 0.1 ? "coarse" : "fine";
        test::write_text(dir / (name + ".svg"), svg);
        for (const int zoom : {1, 4}) {
            EXPECT_GE(iou_at(name, zoom), tolerance > 0.1 ? 0.9 : 0.99) << "zoom " << zoom;
        }
        if (tolerance > 0.1) {
            EXPECT_LT(2 * svg.size(), polygon_svg.size()) << "at least twice smaller";
            // Cairo draws the same curves.
            test::write_text(dir / "coarse.png", output::png_image(curved));
            EXPECT_GE(test::iou(coverage(dir / "coarse1.png"), coverage(dir / "coarse.png")), 0.98);
        }
    }
}

TEST(SvgPaths, CurvesAreWrittenInCompactRelativeSteps) {
    // Rounded once to 0.01 px: relative steps add up exactly; a curve whose control points lie
    // on its chord is a line.
    output::Drawing d;
    d.image = {20, 20};
    output::Shape s{.stroke_id = 1, .filled = true, .paths = {{{1, 1}, {9, 1}, {5, 9}}}};
    s.curves = {{{{1.004, 1}, {3.5, 1}, {6.5, 1}, {9, 1}},
                 {{9, 1}, {9.5, 4}, {7.25, 8.5}, {5, 9}},
                 {{5, 9}, {3, 8}, {1, 4}, {1.004, 1}}}};
    d.shapes.push_back(s);
    const std::string svg = output::svg_document(d, {});
    EXPECT_NE(svg.find(" d=\"M1 1l8 0c.5 3-1.75 7.5-4 8-2-1-4-5-4-8Z\""), std::string::npos) << svg;
}

TEST_F(Raster, PdfHasOnePagePerFrameAndRendersLikeCairo) {
    output::Drawing d = torus_drawing();
    d.style.background = "#ffffff";
    output::PdfDocument doc({});  // the image size at 96 dpi
    for (int frame = 1; frame <= 3; ++frame) {
        d.frame = frame;
        doc.add_page(d);
    }
    test::write_text(dir / "seq.pdf", doc.finish());
    test::write_text(dir / "f.png", output::png_image(d));
    const test::RunResult info = test::run_shell("pdfinfo " + (dir / "seq.pdf").string());
    ASSERT_EQ(info.code, 0) << info.output;
    EXPECT_NE(info.output.find("Pages:           3"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("384 x 384 pts"), std::string::npos) << "512 px at 96 dpi\n" << info.output;
    // 96 dpi in pdftoppm gives back the image size in pixels.
    const test::RunResult ppm = test::run_shell("pdftoppm -png -r 96 -f 1 -l 1 -singlefile " + (dir / "seq.pdf").string() +
                                                " " + (dir / "page").string());
    ASSERT_EQ(ppm.code, 0) << ppm.output;
    EXPECT_GE(test::iou(coverage(dir / "page.png"), coverage(dir / "f.png")), 0.98);
}

// Dots of tone on a grid, radius 2 to 4 px, and no lines.
core::FrameTone dot_grid(int width, int height) {
    core::FrameTone tone;
    tone.mode = core::ToneMode::kStipple;
    uint32_t sample = 0;
    for (int y = 8; y + 8 <= height; y += 12) {
        for (int x = 8; x + 8 <= width; x += 12) {
            core::Dot dot;
            dot.sample = sample++;
            dot.point_px = {x + 0.3, y + 0.6};
            dot.radius_px = 2.0 + (sample % 3);
            tone.dots.push_back(dot);
        }
    }
    return tone;
}

TEST_F(Raster, PngInksTheToneDotsOfAFrameWithoutLines) {
    output::Drawing d;
    d.image = {96, 64};
    const core::FrameTone tone = dot_grid(96, 64);
    d.tone = output::tone_layer(tone, core::ToneOptions{});
    ASSERT_TRUE(d.shapes.empty());
    const std::vector<uint8_t> ink = test::png_coverage(output::png_image(d), test::Ink::kAlpha);
    ASSERT_EQ(ink.size(), 96u * 64u);
    size_t inked = 0;
    double area = 0.0;
    for (const core::Dot& dot : tone.dots) {
        EXPECT_EQ(ink[size_t(dot.point_px.y) * 96 + size_t(dot.point_px.x)], 1) << "dot " << dot.sample;
        area += std::numbers::pi * dot.radius_px * dot.radius_px;
    }
    for (const uint8_t i : ink) inked += i;
    EXPECT_NEAR(double(inked), area, 0.15 * area) << "ink where the dots are, and only there";
    EXPECT_EQ(ink[0], 0);
    // Tone none: nothing drawn.
    d.tone = output::tone_layer(core::FrameTone{}, core::ToneOptions{});
    for (const uint8_t i : test::png_coverage(output::png_image(d), test::Ink::kFaint)) ASSERT_EQ(i, 0);
}

TEST_F(Raster, ToneDotsAreUnderTheLines) {
    // A white filled square over the middle of a black dot of radius 6: white where they overlap,
    // the dot's ink around it.
    output::Drawing d;
    d.image = {21, 21};
    d.style.color = "#ffffff";
    d.shapes.push_back({.stroke_id = 1, .filled = true, .paths = {{{7, 7}, {14, 7}, {14, 14}, {7, 14}}}});
    core::FrameTone tone;
    tone.mode = core::ToneMode::kStipple;
    tone.dots.push_back({.sample = 0, .point_px = {10.5, 10.5}, .radius_px = 6.0});
    core::ToneOptions options;
    options.color = {0.0, 0.0, 0.0};
    d.tone = output::tone_layer(tone, options);
    const std::vector<uint8_t> ink = test::png_coverage(output::png_image(d), test::Ink::kAlphaOrDark);
    EXPECT_EQ(ink[10 * 21 + 10], 0) << "the square is drawn over the dot";
    EXPECT_EQ(ink[5 * 21 + 10], 1) << "the dot shows outside the square";
}

TEST_F(Raster, ToneDotsRenderAlikeInSvgPdfAndCairo) {
    output::Drawing d = torus_drawing();
    d.style.background = "#ffffff";  // as pdftoppm draws the page
    d.tone = output::tone_layer(dot_grid(d.image.width, d.image.height), core::ToneOptions{});
    test::write_text(dir / "f.svg", output::svg_document(d, {}));
    ASSERT_EQ(test::run_shell("xmllint --noout " + (dir / "f.svg").string()).code, 0);
    ASSERT_EQ(test::run_shell("rsvg-convert " + (dir / "f.svg").string() + " -o " + (dir / "rsvg.png").string()).code, 0);
    output::PdfDocument doc({});
    doc.add_page(d);
    test::write_text(dir / "f.pdf", doc.finish());
    ASSERT_EQ(test::run_shell("pdftoppm -png -r 96 -singlefile " + (dir / "f.pdf").string() + " " + (dir / "page").string()).code,
              0);
    test::write_text(dir / "f.png", output::png_image(d));
    const std::vector<uint8_t> cairo = coverage(dir / "f.png");
    output::Drawing without = d;
    without.tone = {};
    const std::vector<uint8_t> lines_only = test::png_coverage(output::png_image(without), test::Ink::kAlphaOrDark);
    size_t more = 0;
    for (size_t i = 0; i < cairo.size(); ++i) more += cairo[i] > lines_only[i];
    EXPECT_GT(more, 3000u) << "the dots add ink";
    // Dots 2 to 4 px across are mostly edge, where the rasterisers' antialiasing differs by a few
    // levels of grey and flips pixels near the threshold (0.96 measured for both); a dot half a
    // pixel off would cost far more.
    EXPECT_GE(test::iou(coverage(dir / "rsvg.png"), cairo), 0.93);
    EXPECT_GE(test::iou(coverage(dir / "page.png"), cairo), 0.93);
}

TEST_F(Raster, PageSizesFitTheImage) {
    EXPECT_NEAR(output::parse_page_size("A4").width_mm, 210.0, 1e-9);
    EXPECT_NEAR(output::parse_page_size("letter").height_mm, 279.4, 1e-9);
    EXPECT_NEAR(output::parse_page_size("200x150mm").height_mm, 150.0, 1e-9);
    EXPECT_THROW(output::parse_page_size("A9"), InputError);
    EXPECT_THROW(output::parse_page_size("0x10mm"), InputError);
    output::PdfOptions options;
    options.page = output::parse_page_size("A4");
    output::PdfDocument doc(options);
    doc.add_page(torus_drawing());
    test::write_text(dir / "a4.pdf", doc.finish());
    const test::RunResult info = test::run_shell("pdfinfo " + (dir / "a4.pdf").string());
    EXPECT_NE(info.output.find("(A4)"), std::string::npos) << info.output;
}

}  // namespace
}  // namespace inkline
