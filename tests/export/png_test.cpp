// SPDX-License-Identifier: MIT
// The PNG encoder writes the image Cairo's own encoder (cairo_surface_write_to_png_stream) wrote
// before it: the same colour type, bit depth and chunks, and the same decoded pixels byte for
// byte, for drawings with and without a background and with partial alpha; only the
// compression differs, and the files stay about as small.
#include "export/png.h"

#include "export/internal/cairo_paint.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <cairo.h>
#include <gtest/gtest.h>
#include <png.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace inkline {
namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// What Cairo's encoder writes for a surface.
std::string cairo_encoded(cairo_surface_t* surface) {
    cairo_surface_flush(surface);
    std::string bytes;
    EXPECT_EQ(cairo_surface_write_to_png_stream(surface, output::internal::append_to_string, &bytes),
              CAIRO_STATUS_SUCCESS);
    return bytes;
}

// The PNG of a drawing as Cairo encoded it before png_image() had an encoder of its own.
std::string cairo_png_image(const output::Drawing& drawing) {
    const Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, drawing.image.width, drawing.image.height),
                          cairo_surface_destroy);
    cairo_t* cr = cairo_create(surface.get());
    output::internal::paint_drawing(cr, drawing);
    EXPECT_EQ(cairo_status(cr), CAIRO_STATUS_SUCCESS);
    cairo_destroy(cr);
    return cairo_encoded(surface.get());
}

// The PNG of straight RGBA pixels as png_from_rgba() wrote it through Cairo's encoder.
std::string cairo_png_from_rgba(int width, int height, const std::vector<uint8_t>& rgba) {
    const Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height), cairo_surface_destroy);
    cairo_surface_flush(surface.get());
    unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < height; ++y) {
        auto* row = reinterpret_cast<uint32_t*>(data + size_t(y) * size_t(stride));
        for (int x = 0; x < width; ++x) {
            const uint8_t* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
            const uint32_t a = p[3];
            auto premultiply = [a](uint32_t c) { return (c * a + 127) / 255; };
            row[x] = a << 24 | premultiply(p[0]) << 16 | premultiply(p[1]) << 8 | premultiply(p[2]);
        }
    }
    cairo_surface_mark_dirty(surface.get());
    return cairo_encoded(surface.get());
}

// A PNG as libpng reads it without transformations: the header, the chunks in file order (one
// "IDAT" for a run of them) and the rows exactly as stored.
struct Decoded {
    uint32_t width = 0, height = 0;
    int bit_depth = 0, color_type = 0, interlace = 0;
    std::vector<std::string> chunks;
    std::vector<uint8_t> rows;
    // Cairo's reading of the same file: premultiplied ARGB32.
    std::vector<uint8_t> cairo_pixels;
};

struct Reader {
    const std::string* bytes;
    size_t at = 0;
};

void read_bytes(png_structp png, png_bytep out, png_size_t length) {
    auto* r = static_cast<Reader*>(png_get_io_ptr(png));
    if (r->at + length > r->bytes->size()) png_error(png, "read past the end");
    std::memcpy(out, r->bytes->data() + r->at, length);
    r->at += length;
}

cairo_status_t read_for_cairo(void* closure, unsigned char* out, unsigned int length) {
    auto* r = static_cast<Reader*>(closure);
    if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
    std::memcpy(out, r->bytes->data() + r->at, length);
    r->at += length;
    return CAIRO_STATUS_SUCCESS;
}

std::vector<std::string> chunk_types(const std::string& bytes) {
    std::vector<std::string> types;
    for (size_t at = 8; at + 8 <= bytes.size();) {
        const auto* p = reinterpret_cast<const uint8_t*>(bytes.data() + at);
        const size_t length = size_t(p[0]) << 24 | size_t(p[1]) << 16 | size_t(p[2]) << 8 | size_t(p[3]);
        const std::string type = bytes.substr(at + 4, 4);
        if (types.empty() || type != "IDAT" || types.back() != "IDAT") types.push_back(type);
        at += 12 + length;
    }
    return types;
}

Decoded decode(const std::string& bytes) {
    Decoded d;
    d.chunks = chunk_types(bytes);
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    Reader reader{&bytes};
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        ADD_FAILURE() << "libpng cannot read the PNG";
        return {};
    }
    png_set_read_fn(png, &reader, read_bytes);
    png_read_info(png, info);
    d.width = png_get_image_width(png, info);
    d.height = png_get_image_height(png, info);
    d.bit_depth = png_get_bit_depth(png, info);
    d.color_type = png_get_color_type(png, info);
    d.interlace = png_get_interlace_type(png, info);
    const size_t row_bytes = png_get_rowbytes(png, info);
    d.rows.resize(row_bytes * d.height);
    for (uint32_t y = 0; y < d.height; ++y) png_read_row(png, &d.rows[y * row_bytes], nullptr);
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);

    Reader for_cairo{&bytes};
    const Surface image(cairo_image_surface_create_from_png_stream(read_for_cairo, &for_cairo), cairo_surface_destroy);
    EXPECT_EQ(cairo_surface_status(image.get()), CAIRO_STATUS_SUCCESS);
    const unsigned char* data = cairo_image_surface_get_data(image.get());
    const size_t stride = size_t(cairo_image_surface_get_stride(image.get()));
    for (uint32_t y = 0; data && y < d.height; ++y) {
        d.cairo_pixels.insert(d.cairo_pixels.end(), data + y * stride, data + y * stride + d.width * 4);
    }
    return d;
}

// Expects the two PNGs to hold the same image, decoded both ways.
void expect_same_image(const std::string& ours, const std::string& cairos, const std::string& what) {
    const Decoded a = decode(ours), b = decode(cairos);
    EXPECT_EQ(a.width, b.width) << what;
    EXPECT_EQ(a.height, b.height) << what;
    EXPECT_EQ(a.bit_depth, b.bit_depth) << what;
    EXPECT_EQ(a.color_type, b.color_type) << what;
    EXPECT_EQ(a.interlace, b.interlace) << what;
    EXPECT_EQ(a.chunks, b.chunks) << what;
    EXPECT_TRUE(a.rows == b.rows) << what << ": the stored rows differ";
    EXPECT_TRUE(a.cairo_pixels == b.cairo_pixels) << what << ": Cairo reads different pixels";
    EXPECT_FALSE(a.cairo_pixels.empty()) << what;
}

// How many pixels of a PNG's stored RGBA rows have an alpha strictly between 0 and 255.
size_t partly_transparent(const std::string& png) {
    const Decoded d = decode(png);
    if (d.color_type != PNG_COLOR_TYPE_RGB_ALPHA) return 0;
    size_t n = 0;
    for (size_t i = 3; i < d.rows.size(); i += 4) n += d.rows[i] != 0 && d.rows[i] != 255;
    return n;
}

// Brush outlines of a torus: filled, antialiased edges.
output::Drawing torus_brush(const output::DrawStyle& style) {
    const core::Mesh torus = test::torus(1.0, 0.4, 64, 32);
    const test::View view{.eye = {0.0, 2.6, 4.6}, .fov_y_deg = 40.0, .size = 384};
    const test::Drawn drawn = test::draw(torus, test::scene_for(view, torus));
    return output::brush_drawing(drawn.lines, drawn.strokes, style, false);
}

// Hairline centerlines and dashed hidden lines of a torus, half-transparent coloured ink.
output::Drawing torus_hairlines(const output::DrawStyle& style) {
    core::LineOptions lines;
    lines.hidden = true;
    const core::FrameLines frame =
        test::trace(test::torus(1.0, 0.4, 48, 24), {.eye = {0.0, 2.6, 4.6}, .fov_y_deg = 40.0, .size = 320}, lines);
    return output::centerline_drawing(frame, style);
}

TEST(Png, DrawingDecodesToWhatCairosEncoderWrote) {
    output::DrawStyle thin;
    thin.centerline_width_px = 0.35;
    thin.color = "#3366cc";
    thin.opacity = 0.6;
    output::DrawStyle on_paper = thin;
    on_paper.background = "#fdf6e3";
    output::DrawStyle white;
    white.background = "#ffffff";
    const struct {
        const char* name;
        output::Drawing drawing;
        bool transparent;
    } cases[] = {
        {"brush, transparent", torus_brush({}), true},
        {"brush on white", torus_brush(white), false},
        {"hairlines, transparent", torus_hairlines(thin), true},
        {"hairlines on paper", torus_hairlines(on_paper), false},
    };
    for (const auto& c : cases) {
        const std::string ours = output::png_image(c.drawing), cairos = cairo_png_image(c.drawing);
        expect_same_image(ours, cairos, c.name);
        // Faster, not larger: about Cairo's size, also on a coloured background.
        EXPECT_LT(ours.size(), cairos.size() * 5 / 4) << c.name;
        EXPECT_EQ(decode(ours).color_type, c.transparent ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB) << c.name;
        // Antialiased edges: partial alpha is there to get right.
        if (c.transparent) {
            EXPECT_GT(partly_transparent(ours), 100u) << c.name;
        }
        EXPECT_EQ(output::png_image(c.drawing), ours) << c.name << ": the same drawing makes the same file";
    }
}

TEST(Png, BlankImagesDecodeToWhatCairosEncoderWrote) {
    for (const bool background : {false, true}) {
        output::Drawing d;
        d.image = {7, 3};
        if (background) d.style.background = "#102030";
        expect_same_image(output::png_image(d), cairo_png_image(d), background ? "background only" : "blank");
    }
}

TEST(Png, FromRgbaDecodesToWhatCairosEncoderWrote) {
    // Every alpha with random colours (straight RGBA: any colour under any alpha), an odd width.
    const int width = 97, height = 61;
    std::vector<uint8_t> rgba(size_t(width) * height * 4);
    std::mt19937 random(27);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = uint8_t(random());
    for (size_t p = 0; p < 256; ++p) rgba[p * 4 + 3] = uint8_t(p);
    expect_same_image(output::png_from_rgba(width, height, rgba), cairo_png_from_rgba(width, height, rgba),
                      "random RGBA");
    EXPECT_GT(partly_transparent(output::png_from_rgba(width, height, rgba)), 1000u);
    // Opaque pixels: an RGB file, as Cairo writes one.
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
    const std::string opaque = output::png_from_rgba(width, height, rgba);
    expect_same_image(opaque, cairo_png_from_rgba(width, height, rgba), "opaque RGBA");
    EXPECT_EQ(decode(opaque).color_type, PNG_COLOR_TYPE_RGB);
}

}  // namespace
}  // namespace inkline
