// SPDX-License-Identifier: MIT
#include "export/png.h"

#include "core/error.h"
#include "export/internal/cairo_paint.h"

#include <cairo.h>

namespace inkline::output {

std::string png_image(const Drawing& drawing) {
    cairo_surface_t* surface =
        cairo_image_surface_create(CAIRO_FORMAT_ARGB32, drawing.image.width, drawing.image.height);
    cairo_t* cr = cairo_create(surface);
    internal::paint_drawing(cr, drawing);
    cairo_destroy(cr);
    std::string bytes;
    const cairo_status_t status = cairo_surface_write_to_png_stream(surface, internal::append_to_string, &bytes);
    cairo_surface_destroy(surface);
    if (status != CAIRO_STATUS_SUCCESS) {
        throw InternalError(std::string("PNG encoding failed: ") + cairo_status_to_string(status));
    }
    return bytes;
}

std::string png_from_rgba(int width, int height, std::span<const uint8_t> rgba) {
    INKLINE_CHECK(width > 0 && height > 0);
    INKLINE_CHECK_EQ(rgba.size(), size_t(width) * size_t(height) * 4);
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
        const cairo_status_t status = cairo_surface_status(surface);
        cairo_surface_destroy(surface);
        throw InternalError(std::string("PNG image surface: ") + cairo_status_to_string(status));
    }
    // Cairo's ARGB32 is premultiplied, one native-endian 32-bit word per pixel.
    cairo_surface_flush(surface);
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int y = 0; y < height; ++y) {
        auto* row = reinterpret_cast<uint32_t*>(data + size_t(y) * size_t(stride));
        for (int x = 0; x < width; ++x) {
            const uint8_t* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
            const uint32_t a = p[3];
            auto premultiply = [a](uint32_t c) { return (c * a + 127) / 255; };
            row[x] = a << 24 | premultiply(p[0]) << 16 | premultiply(p[1]) << 8 | premultiply(p[2]);
        }
    }
    cairo_surface_mark_dirty(surface);
    std::string bytes;
    const cairo_status_t status = cairo_surface_write_to_png_stream(surface, internal::append_to_string, &bytes);
    cairo_surface_destroy(surface);
    if (status != CAIRO_STATUS_SUCCESS) {
        throw InternalError(std::string("PNG encoding failed: ") + cairo_status_to_string(status));
    }
    return bytes;
}

}  // namespace inkline::output
