// SPDX-License-Identifier: MIT
// Paints a Drawing on a Cairo context in pixel units (the caller sets any page transform).
#pragma once

#include "export/drawing.h"

#include <cairo.h>

#include <string>

namespace inkline::output::internal {

// Background (when the style has one), then every layer in order.
void paint_drawing(cairo_t* cr, const Drawing& drawing);

// Appends Cairo's output to a string (for cairo_*_create_for_stream / write_to_png_stream).
cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length);

}  // namespace inkline::output::internal
