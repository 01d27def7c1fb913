// SPDX-License-Identifier: MIT
// PDF layers: each line layer of a frame is optional content of its own, grouped as the SVG's
// layers are (--layers), listed in the document in drawing order; a page with layers renders as
// the page without them, and switching a layer off takes exactly its lines away.
#include "export/pdf.h"

#include "tests/support/obj.h"
#include "tests/support/pipeline.h"
#include "tests/support/raster.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>
#include <qpdf/Buffer.hh>
#include <qpdf/Pl_Buffer.hh>
#include <qpdf/QPDF.hh>
#include <qpdf/QPDFObjectHandle.hh>
#include <qpdf/QPDFPageDocumentHelper.hh>
#include <qpdf/QPDFPageObjectHelper.hh>
#include <qpdf/QPDFWriter.hh>

#include <algorithm>
#include <cctype>
#include <map>
#include <string>
#include <vector>

namespace inkline {
namespace {

namespace fs = std::filesystem;

// The layers a PDF lists (/OCProperties /D /Order): names, a nested list as "parent/child".
std::vector<std::string> listed_layers(QPDF& pdf) {
    std::vector<std::string> names;
    QPDFObjectHandle order = pdf.getRoot().getKey("/OCProperties").getKey("/D").getKey("/Order");
    std::string parent;
    for (int i = 0; order.isArray() && i < order.getArrayNItems(); ++i) {
        QPDFObjectHandle item = order.getArrayItem(i);
        if (item.isDictionary()) {
            parent = item.getKey("/Name").getUTF8Value();
            names.push_back(parent);
            continue;
        }
        for (int k = 0; k < item.getArrayNItems(); ++k) {
            names.push_back(parent + "/" + item.getArrayItem(k).getKey("/Name").getUTF8Value());
        }
    }
    return names;
}

// Per page, the layers its content marks, in order: "name" or "parent/name" for nested marks.
std::vector<std::vector<std::string>> marked_layers(QPDF& pdf) {
    std::vector<std::vector<std::string>> pages;
    for (QPDFPageObjectHelper& page : QPDFPageDocumentHelper(pdf).getAllPages()) {
        QPDFObjectHandle properties = page.getAttribute("/Resources", false).getKey("/Properties");
        std::vector<std::string> marks, open;
        Pl_Buffer buffer("content");
        page.pipeContents(&buffer);
        const std::shared_ptr<Buffer> bytes = buffer.getBufferSharedPointer();
        const std::string content(reinterpret_cast<const char*>(bytes->getBuffer()), bytes->getSize());
        // Tokens of interest: "/OC /X BDC", "Do", "EMC".
        std::vector<std::string> tokens;
        for (size_t i = 0; i < content.size();) {
            while (i < content.size() && std::isspace(static_cast<unsigned char>(content[i]))) ++i;
            size_t j = i;
            while (j < content.size() && !std::isspace(static_cast<unsigned char>(content[j]))) ++j;
            if (j > i) tokens.push_back(content.substr(i, j - i));
            i = j;
        }
        for (size_t t = 0; t < tokens.size(); ++t) {
            if (tokens[t] == "BDC" && t >= 2 && tokens[t - 2] == "/OC") {
                open.push_back(properties.getKey(tokens[t - 1]).getKey("/Name").getUTF8Value());
            } else if (tokens[t] == "EMC" && !open.empty()) {
                open.pop_back();
            } else if (tokens[t] == "Do" && !open.empty()) {
                std::string name;
                for (const std::string& o : open) name += (name.empty() ? "" : "/") + o;
                marks.push_back(name);
            }
        }
        EXPECT_TRUE(open.empty()) << "every mark is closed";
        pages.push_back(marks);
    }
    return pages;
}

class PdfLayers : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // The torus's silhouette and its hidden lines, white background (as pdftoppm draws the page).
    static output::Drawing torus_drawing() {
        core::LineOptions lines;
        lines.hidden = true;
        const core::FrameLines frame =
            test::trace(test::torus(1.0, 0.4, 48, 24), {.eye = {0.0, 2.6, 4.6}, .fov_y_deg = 40.0, .size = 256}, lines);
        output::DrawStyle style;
        style.centerline_width_px = 3.0;
        style.background = "#ffffff";
        return output::centerline_drawing(frame, style);
    }

    static std::string pdf_of(const std::vector<output::Drawing>& frames, std::optional<output::LayerGrouping> layers) {
        output::PdfOptions options;
        options.layers = layers;
        options.creation_date = "2026-01-01T00:00:00";
        output::PdfDocument doc(options);
        for (const output::Drawing& d : frames) doc.add_page(d);
        return doc.finish();
    }

    // Page `page` (from 1) as pdftoppm draws it at 96 dpi: the image's own pixels, grey.
    std::vector<uint8_t> raster(const std::string& pdf, int page, const std::string& name) {
        test::write_text(dir / (name + ".pdf"), pdf);
        const test::RunResult r = test::run_shell("pdftoppm -png -gray -r 96 -f " + std::to_string(page) + " -l " +
                                                  std::to_string(page) + " -singlefile " + (dir / (name + ".pdf")).string() +
                                                  " " + (dir / name).string());
        EXPECT_EQ(r.code, 0) << r.output;
        return test::png_file_coverage(dir / (name + ".png"), test::Ink::kAlphaOrDark);
    }
};

TEST_F(PdfLayers, EachKindIsALayerOfEveryPageAndThePagesRenderAsWithoutLayers) {
    std::vector<output::Drawing> frames(2, torus_drawing());
    frames[1].frame = 2;
    const std::string layered = pdf_of(frames, output::LayerGrouping::kKind);
    QPDF pdf;
    pdf.processMemoryFile("layered", layered.data(), layered.size());
    EXPECT_EQ(listed_layers(pdf), (std::vector<std::string>{"silhouette", "hidden"}));
    const std::vector<std::vector<std::string>> marks = marked_layers(pdf);
    ASSERT_EQ(marks.size(), 2u) << "one page per frame";
    for (const std::vector<std::string>& page : marks) EXPECT_EQ(page, (std::vector<std::string>{"silhouette", "hidden"}));
    QPDFObjectHandle labels = pdf.getRoot().getKey("/PageLabels").getKey("/Nums");
    ASSERT_EQ(labels.getArrayNItems(), 4);
    EXPECT_EQ(labels.getArrayItem(3).getKey("/P").getUTF8Value(), "frame 2");
    const std::vector<uint8_t> with = raster(layered, 2, "layered");
    const std::vector<uint8_t> without = raster(pdf_of(frames, std::nullopt), 2, "flat");
    EXPECT_EQ(with, without) << "the same picture, pixel for pixel";
    EXPECT_GT(std::count(with.begin(), with.end(), 1), 1000);
    EXPECT_EQ(layered, pdf_of(frames, output::LayerGrouping::kKind)) << "the same input gives the same bytes";
}

TEST_F(PdfLayers, ALayerSwitchedOffTakesAwayItsLinesAndNothingElse) {
    const output::Drawing d = torus_drawing();
    const std::string layered = pdf_of({d}, output::LayerGrouping::kKind);
    QPDF pdf;
    pdf.processMemoryFile("layered", layered.data(), layered.size());
    // The hidden layer off, as a viewer's layer panel does.
    QPDFObjectHandle properties = pdf.getRoot().getKey("/OCProperties");
    QPDFObjectHandle off = QPDFObjectHandle::newArray();
    QPDFObjectHandle groups = properties.getKey("/OCGs");
    for (int i = 0; i < groups.getArrayNItems(); ++i) {
        if (groups.getArrayItem(i).getKey("/Name").getUTF8Value() == "hidden") off.appendItem(groups.getArrayItem(i));
    }
    ASSERT_EQ(off.getArrayNItems(), 1);
    properties.getKey("/D").replaceKey("/OFF", off);
    QPDFWriter writer(pdf);
    writer.setOutputMemory();
    writer.write();
    const std::shared_ptr<Buffer> b = writer.getBufferSharedPointer();
    const std::vector<uint8_t> switched = raster(std::string(reinterpret_cast<const char*>(b->getBuffer()), b->getSize()), 1, "off");
    output::Drawing visible = d;
    std::erase_if(visible.shapes, [](const output::Shape& s) { return s.hidden; });
    ASSERT_LT(visible.shapes.size(), d.shapes.size());
    EXPECT_EQ(switched, raster(pdf_of({visible}, std::nullopt), 1, "visible")) << "the visible lines alone";
    EXPECT_NE(switched, raster(layered, 1, "all"));
}

TEST_F(PdfLayers, ObjectsAndStylesHoldTheirKindLayersAndTheToneLiesUnderAll) {
    output::Drawing d = torus_drawing();
    // Two objects: the first half of the shapes is "Ring", the rest "Post"; the hidden lines
    // are styled "dotted".
    output::InkStyle brush, dotted;
    brush.color = dotted.color = "#000000";
    dotted.name = "dotted";
    dotted.rule = 0;
    d.styles = {brush, dotted};
    for (size_t i = 0; i < d.shapes.size(); ++i) {
        output::Shape& s = d.shapes[i];
        const bool first = i < d.shapes.size() / 2;
        s.object = first ? "Ring" : "Post";
        s.object_index = first ? 0 : 1;
        if (s.hidden) s.style = 1;
    }
    core::FrameTone tone;
    tone.mode = core::ToneMode::kStipple;
    tone.dots.push_back(core::Dot{.point_px = {20.0, 20.0}, .radius_px = 3.0});
    d.tone = output::tone_layer(tone, core::ToneOptions{});
    std::vector<std::string> kinds;  // "object/kind" of the shapes, as the SVG groups them
    for (const output::LineLayer& layer : output::line_layers(d, output::LayerGrouping::kObject)) {
        kinds.push_back(layer.parent_label + "/" + output::layer_name(layer.kind));
    }
    {
        const std::string bytes = pdf_of({d}, output::LayerGrouping::kObject);
        QPDF pdf;
        pdf.processMemoryFile("objects", bytes.data(), bytes.size());
        std::vector<std::string> expected = {"tone"};
        expected.insert(expected.end(), kinds.begin(), kinds.end());
        EXPECT_EQ(marked_layers(pdf).at(0), expected);
        const std::vector<std::string> listed = listed_layers(pdf);
        EXPECT_EQ(listed.front(), "tone");
        EXPECT_NE(std::find(listed.begin(), listed.end(), "Ring"), listed.end());
        EXPECT_NE(std::find(listed.begin(), listed.end(), "Post/hidden"), listed.end());
        EXPECT_LT(std::find(listed.begin(), listed.end(), "Ring"), std::find(listed.begin(), listed.end(), "Post"));
    }
    {
        const std::string bytes = pdf_of({d}, output::LayerGrouping::kStyle);
        QPDF pdf;
        pdf.processMemoryFile("styles", bytes.data(), bytes.size());
        EXPECT_EQ(marked_layers(pdf).at(0),
                  (std::vector<std::string>{"tone", "unstyled/silhouette", "dotted/hidden"}));
    }
}

TEST_F(PdfLayers, ADocumentWithoutPagesIsStillAPdf) {
    const std::string layered = pdf_of({}, output::LayerGrouping::kKind);
    QPDF pdf;
    pdf.processMemoryFile("empty", layered.data(), layered.size());
    EXPECT_EQ(QPDFPageDocumentHelper(pdf).getAllPages().size(), 0u);
    EXPECT_TRUE(listed_layers(pdf).empty());
}

}  // namespace
}  // namespace inkline
