// SPDX-License-Identifier: MIT
#include "export/png.h"

#include "core/error.h"
#include "export/internal/cairo_paint.h"

#include <cairo.h>

#include <memory>
#include <string>

namespace inkline::output {
namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// A blank ARGB32 image surface.
Surface image_surface(int width, int height) {
    check_png_size(width, height);
    Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height), cairo_surface_destroy);
    internal::check_cairo(cairo_surface_status(surface.get()), "PNG image surface");
    return surface;
}

std::string encode_png(const Surface& surface) {
    cairo_surface_flush(surface.get());
    internal::check_cairo(cairo_surface_status(surface.get()), "PNG drawing");
    std::string bytes;
    internal::check_cairo(cairo_surface_write_to_png_stream(surface.get(), internal::append_to_string, &bytes),
                          "PNG encoding");
    return bytes;
}

}  // namespace

void check_png_size(int width, int height) {
    if (width > kMaxPngSide || height > kMaxPngSide) {
        throw InputError("PNG of " + std::to_string(width) + "x" + std::to_string(height) +
                         " px: Cairo draws images of at most " + std::to_string(kMaxPngSide) + " px a side");
    }
    INKLINE_CHECK(width > 0 && height > 0);
}

std::string png_image(const Drawing& drawing) {
    const Surface surface = image_surface(drawing.image.width, drawing.image.height);
    {
        const std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), cairo_destroy);
        internal::check_cairo(cr.get(), "PNG drawing");
        internal::paint_drawing(cr.get(), drawing);
        // Cairo records a failure (out of memory in a layer group, say) in the context and draws
        // nothing more: a blank or half-drawn image is never encoded.
        internal::check_cairo(cr.get(), "PNG drawing");
    }
    return encode_png(surface);
}

std::string png_from_rgba(int width, int height, std::span<const uint8_t> rgba) {
    INKLINE_CHECK(width > 0 && height > 0);
    INKLINE_CHECK_EQ(rgba.size(), size_t(width) * size_t(height) * 4);
    const Surface surface = image_surface(width, height);
    // Cairo's ARGB32 is premultiplied, one native-endian 32-bit word per pixel.
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
    return encode_png(surface);
}

}  // namespace inkline::output
