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

}  // namespace inkline::output
