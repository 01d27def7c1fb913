// SPDX-License-Identifier: MIT
#include "export/pdf.h"

#include "core/error.h"
#include "export/internal/cairo_paint.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <nlohmann/json.hpp>
#include <qpdf/Buffer.hh>
#include <qpdf/QPDF.hh>
#include <qpdf/QPDFObjectHandle.hh>
#include <qpdf/QPDFPageDocumentHelper.hh>
#include <qpdf/QPDFPageObjectHelper.hh>
#include <qpdf/QPDFWriter.hh>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <regex>
#include <vector>

#include <sys/stat.h>

namespace inkline::output {
namespace {

constexpr double kPointsPerInch = 72.0;
constexpr double kMmPerInch = 25.4;
constexpr double kLabelPoints = 8.0;  // size of the frame label printed in the bottom margin

double mm_to_points(double mm) { return mm / kMmPerInch * kPointsPerInch; }

// Where the image goes on its page, in points.
struct PageLayout {
    double page_w = 0.0, page_h = 0.0;
    double scale = 1.0, offset_x = 0.0, offset_y = 0.0;
    std::optional<PageSize> page;  // the page size asked for, turned to the image's orientation
};

PageLayout layout(const PdfOptions& o, double image_w, double image_h) {
    PageLayout l;
    if (o.page) {
        PageSize p = *o.page;
        if (p.named && image_w > image_h) std::swap(p.width_mm, p.height_mm);
        l.page = p;
        l.page_w = mm_to_points(p.width_mm);
        l.page_h = mm_to_points(p.height_mm);
        const double margin = mm_to_points(o.margin_mm);
        const double avail_w = std::max(l.page_w - 2.0 * margin, 1.0), avail_h = std::max(l.page_h - 2.0 * margin, 1.0);
        l.scale = std::min(avail_w / image_w, avail_h / image_h);
        l.offset_x = (l.page_w - l.scale * image_w) / 2.0;
        l.offset_y = (l.page_h - l.scale * image_h) / 2.0;
    } else {
        l.scale = kPointsPerInch / o.dpi;
        l.page_w = image_w * l.scale;
        l.page_h = image_h * l.scale;
    }
    return l;
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// `text` with every byte sequence that is not UTF-8 replaced by U+FFFD: Cairo takes UTF-8 only.
std::string valid_utf8(const std::string& text) {
    using nlohmann::json;
    return json::parse(json(text).dump(-1, ' ', false, json::error_handler_t::replace)).get<std::string>();
}

}  // namespace

void check_pdf_page(const PdfOptions& o, int width, int height) {
    const PageLayout l = layout(o, width, height);
    const bool fits = l.page_w >= kMinPdfPagePoints && l.page_w <= kMaxPdfPagePoints &&
                      l.page_h >= kMinPdfPagePoints && l.page_h <= kMaxPdfPagePoints;
    const std::string limits =
        "PDF pages are " + number(kMinPdfPagePoints) + " to " + number(kMaxPdfPagePoints) + " pt a side";
    if (!fits && !o.page) {
        throw InputError("--dpi " + number(o.dpi) + ": a " + std::to_string(width) + "x" + std::to_string(height) +
                         " px image makes a PDF page of " + number(l.page_w) + "x" + number(l.page_h) + " pt; " +
                         limits + " (use --page, or another --dpi)");
    }
    if (!fits) {
        throw InputError("--page " + number(l.page->width_mm) + "x" + number(l.page->height_mm) + "mm: " + limits);
    }
    if (l.page && (2.0 * o.margin_mm >= l.page->width_mm || 2.0 * o.margin_mm >= l.page->height_mm)) {
        throw InputError("--margin " + number(o.margin_mm) + " mm leaves no room for the image on a " +
                         number(l.page->width_mm) + "x" + number(l.page->height_mm) + " mm page");
    }
}

std::string reproducible_creation_date(const std::filesystem::path& input) {
    std::time_t when = 0;
    if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch && *epoch) {
        when = std::time_t(std::strtoll(epoch, nullptr, 10));
    } else {
        struct stat info {};
        if (::stat(input.c_str(), &info) != 0) return "";
        when = info.st_mtime;
    }
    std::tm utc{};
    gmtime_r(&when, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
    return text;
}

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
    throw InputError("--page '" + quote_value(text) + "': expected A4, A3, Letter or WxHmm with sides 1..5000 mm");
}

namespace {

// A PDF layer: an optional content group, inside its parent's (an object's or a style's) where
// it has one.
struct PdfLayer {
    std::string key;  // unique: "tone", "KIND" or "PARENT-ID/KIND"
    std::string label;
    std::string parent_key, parent_label;  // empty at the top
};

// A frame's pages in Cairo's document: the page it ends up on (background and label), then one
// page per layer, drawn in that order.
struct FramePages {
    size_t base = 0;
    std::string label;
    std::vector<std::pair<size_t, PdfLayer>> layers;  // (page, layer)
};

// Puts each frame's layer pages on its first page, each as a form XObject marked as optional
// content of its layer (and of its parent's), and lists the layers in the document.
std::string assemble_layers(const std::string& cairo_pdf, const std::vector<FramePages>& frames) {
    QPDF pdf;
    pdf.setSuppressWarnings(true);
    pdf.processMemoryFile("inkline PDF", cairo_pdf.data(), cairo_pdf.size());
    QPDFPageDocumentHelper document(pdf);
    std::vector<QPDFPageObjectHelper> pages = document.getAllPages();
    std::map<std::string, QPDFObjectHandle> groups;  // layer key -> its optional content group
    std::vector<std::string> top;                    // top-level keys, in drawing order
    std::map<std::string, std::vector<std::string>> children;
    auto group = [&](const std::string& key, const std::string& label, const std::string& parent) {
        auto [it, added] = groups.try_emplace(key);
        if (added) {
            it->second = pdf.makeIndirectObject(QPDFObjectHandle::parse("<< /Type /OCG >>"));
            it->second.replaceKey("/Name", QPDFObjectHandle::newUnicodeString(label));
            (parent.empty() ? top : children[parent]).push_back(key);
        }
        return it->second;
    };
    QPDFObjectHandle labels = QPDFObjectHandle::newArray();
    for (size_t f = 0; f < frames.size(); ++f) {
        const FramePages& frame = frames[f];
        QPDFPageObjectHelper base = pages.at(frame.base);
        QPDFObjectHandle resources = base.getAttribute("/Resources", true);
        if (!resources.isDictionary()) {
            resources = QPDFObjectHandle::newDictionary();
            base.getObjectHandle().replaceKey("/Resources", resources);
        }
        for (const char* key : {"/XObject", "/Properties"}) {
            if (!resources.getKey(key).isDictionary()) resources.replaceKey(key, QPDFObjectHandle::newDictionary());
        }
        QPDFObjectHandle xobjects = resources.getKey("/XObject"), properties = resources.getKey("/Properties");
        std::string content = "Q\n";
        for (size_t k = 0; k < frame.layers.size(); ++k) {
            const auto& [page, layer] = frame.layers[k];
            const std::string form = "/InkLayer" + std::to_string(k);
            xobjects.replaceKey(form, pages.at(page).getFormXObjectForPage());
            std::string marks = "/OC /InkOC" + std::to_string(k) + " BDC ";
            properties.replaceKey("/InkOC" + std::to_string(k), group(layer.key, layer.label, layer.parent_key));
            if (!layer.parent_key.empty()) {
                properties.replaceKey("/InkOCP" + std::to_string(k), group(layer.parent_key, layer.parent_label, ""));
                marks = "/OC /InkOCP" + std::to_string(k) + " BDC " + marks;
            }
            content += marks + form + " Do EMC" + (layer.parent_key.empty() ? "" : " EMC") + "\n";
        }
        // The page's own drawing (background, label) keeps its graphics state to itself.
        base.addPageContents(QPDFObjectHandle::newStream(&pdf, "q\n"), true);
        base.addPageContents(QPDFObjectHandle::newStream(&pdf, content), false);
        labels.appendItem(QPDFObjectHandle::newInteger(static_cast<long long>(f)));
        QPDFObjectHandle label = QPDFObjectHandle::newDictionary();
        label.replaceKey("/P", QPDFObjectHandle::newUnicodeString(frame.label));
        labels.appendItem(label);
    }
    // The page tree keeps the frames' pages only (one pass: removing pages one by one costs the
    // square of their number); the layer pages live on in the forms made of them.
    QPDFObjectHandle root = pdf.getRoot();
    QPDFObjectHandle tree = root.getKey("/Pages"), frame_pages = QPDFObjectHandle::newArray();
    for (const FramePages& frame : frames) {
        QPDFObjectHandle page = pages.at(frame.base).getObjectHandle();
        page.replaceKey("/Parent", tree);
        frame_pages.appendItem(page);
    }
    tree.replaceKey("/Kids", frame_pages);
    tree.replaceKey("/Count", QPDFObjectHandle::newInteger(static_cast<long long>(frames.size())));
    pdf.updateAllPagesCache();
    QPDFObjectHandle all = QPDFObjectHandle::newArray(), order = QPDFObjectHandle::newArray();
    for (const std::string& key : top) {
        all.appendItem(groups.at(key));
        order.appendItem(groups.at(key));
        if (const auto kids = children.find(key); kids != children.end()) {
            QPDFObjectHandle nested = QPDFObjectHandle::newArray();
            for (const std::string& kid : kids->second) {
                all.appendItem(groups.at(kid));
                nested.appendItem(groups.at(kid));
            }
            order.appendItem(nested);
        }
    }
    if (!top.empty()) {
        QPDFObjectHandle config = QPDFObjectHandle::newDictionary();
        config.replaceKey("/Name", QPDFObjectHandle::newUnicodeString("inkline"));
        config.replaceKey("/Order", order);
        QPDFObjectHandle properties = QPDFObjectHandle::newDictionary();
        properties.replaceKey("/OCGs", all);
        properties.replaceKey("/D", config);
        root.replaceKey("/OCProperties", properties);
    }
    QPDFObjectHandle page_labels = QPDFObjectHandle::newDictionary();
    page_labels.replaceKey("/Nums", labels);
    root.replaceKey("/PageLabels", page_labels);
    QPDFWriter writer(pdf);
    writer.setOutputMemory();
    writer.setDeterministicID(true);
    writer.setCompressStreams(true);
    writer.setDecodeLevel(qpdf_dl_none);  // Cairo's streams as they are; only the new ones compressed
    writer.setObjectStreamMode(qpdf_o_generate);
    writer.write();
    const std::shared_ptr<Buffer> out = writer.getBufferSharedPointer();
    return std::string(reinterpret_cast<const char*>(out->getBuffer()), out->getSize());
}

}  // namespace

struct PdfDocument::Impl {
    PdfOptions options;
    std::string bytes;
    std::vector<FramePages> frames;  // with layers
    size_t cairo_pages = 0;
    cairo_surface_t* surface = nullptr;
    cairo_t* cr = nullptr;
    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl() {
        if (cr) cairo_destroy(cr);
        if (surface) cairo_surface_destroy(surface);
    }
};

PdfDocument::PdfDocument(const PdfOptions& options) : impl_(std::make_unique<Impl>()) {
    impl_->options = options;
    impl_->options.title = valid_utf8(options.title);
    // The real page size is set per page; the first page's is a placeholder.
    impl_->surface = cairo_pdf_surface_create_for_stream(internal::append_to_string, &impl_->bytes, 100, 100);
    cairo_pdf_surface_set_metadata(impl_->surface, CAIRO_PDF_METADATA_TITLE, impl_->options.title.c_str());
    cairo_pdf_surface_set_metadata(impl_->surface, CAIRO_PDF_METADATA_CREATOR, "inkline");
    if (!options.creation_date.empty()) {
        cairo_pdf_surface_set_metadata(impl_->surface, CAIRO_PDF_METADATA_CREATE_DATE, options.creation_date.c_str());
    }
    impl_->cr = cairo_create(impl_->surface);
    internal::check_cairo(impl_->cr, "PDF document");
}

PdfDocument::~PdfDocument() = default;

void PdfDocument::add_page(const Drawing& drawing) {
    INKLINE_CHECK(impl_->cr != nullptr);
    const PdfOptions& o = impl_->options;
    check_pdf_page(o, drawing.image.width, drawing.image.height);
    const PageLayout l = layout(o, drawing.image.width, drawing.image.height);
    const double page_h = l.page_h;
    const std::string label = "frame " + std::to_string(drawing.frame);
    cairo_t* cr = impl_->cr;
    // One Cairo page: the whole drawing, or with layers one part of it, at the image's place.
    auto page = [&](internal::Part part, const LineLayer* layer, bool first) {
        cairo_pdf_surface_set_size(impl_->surface, l.page_w, page_h);
        if (!o.layers) cairo_pdf_surface_set_page_label(impl_->surface, label.c_str());
        cairo_save(cr);
        cairo_translate(cr, l.offset_x, l.offset_y);
        cairo_scale(cr, l.scale, l.scale);
        if (o.layers) {
            internal::paint_part(cr, drawing, part, layer);
        } else {
            internal::paint_drawing(cr, drawing);
        }
        cairo_restore(cr);
        if (first && o.page && o.margin_mm > 0.0) {
            // The frame number in the bottom margin, small and grey.
            cairo_save(cr);
            cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
            cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
            cairo_set_font_size(cr, kLabelPoints);
            cairo_move_to(cr, mm_to_points(o.margin_mm), page_h - mm_to_points(o.margin_mm) / 2.0);
            cairo_show_text(cr, (o.title + " - " + label).c_str());
            cairo_restore(cr);
        }
        // Cairo records a failure in the context and draws nothing more: check before the page counts.
        internal::check_cairo(cr, "PDF drawing");
        cairo_show_page(cr);
        internal::check_cairo(cr, "PDF drawing");
        return impl_->cairo_pages++;
    };
    if (!o.layers) {
        page(internal::Part::kBackground, nullptr, true);
        ++pages_;
        return;
    }
    FramePages frame;
    frame.label = label;
    frame.base = page(internal::Part::kBackground, nullptr, true);
    if (drawing.tone.mode != core::ToneMode::kNone) {
        frame.layers.emplace_back(page(internal::Part::kTone, nullptr, false), PdfLayer{"tone", "tone", "", ""});
    }
    for (const LineLayer& layer : line_layers(drawing, *o.layers)) {
        if (layer.shapes.empty()) continue;
        const std::string kind = layer_name(layer.kind);
        PdfLayer pdf_layer{layer.parent_id.empty() ? kind : layer.parent_id + "/" + kind, kind, layer.parent_id,
                           layer.parent_label};
        frame.layers.emplace_back(page(internal::Part::kLines, &layer, false), std::move(pdf_layer));
    }
    impl_->frames.push_back(std::move(frame));
    ++pages_;
}

std::string PdfDocument::finish() {
    INKLINE_CHECK(impl_->cr != nullptr);
    const cairo_status_t drawn = cairo_status(impl_->cr);
    cairo_destroy(impl_->cr);
    impl_->cr = nullptr;
    cairo_surface_finish(impl_->surface);
    const cairo_status_t status = cairo_surface_status(impl_->surface);
    cairo_surface_destroy(impl_->surface);
    impl_->surface = nullptr;
    internal::check_cairo(drawn, "PDF drawing");
    internal::check_cairo(status, "PDF encoding");
    if (!impl_->options.layers) return std::move(impl_->bytes);
    try {
        return assemble_layers(impl_->bytes, impl_->frames);
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        throw OutputError(std::string("PDF layers: ") + e.what());
    }
}

}  // namespace inkline::output
