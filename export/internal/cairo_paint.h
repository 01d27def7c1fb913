// SPDX-License-Identifier: MIT
// Paints a Drawing on a Cairo context in pixel units (the caller sets any page transform).
#pragma once

#include "export/drawing.h"

#include <cairo.h>

#include <string>

namespace inkline::output::internal {

// Background (when the style has one), the tone layer (when there is one), then every line
// layer in order.
void paint_drawing(cairo_t* cr, const Drawing& drawing);

// One part of a drawing, for writers that keep its layers apart: the background (nothing
// without one), the tone (nothing without one), or the lines of `layer` (one of
// line_layers(drawing, ...)). Painted one over the other in that order they give paint_drawing's
// picture (with the line layers of its grouping).
enum class Part : uint8_t { kBackground, kTone, kLines };
void paint_part(cairo_t* cr, const Drawing& drawing, Part part, const LineLayer* layer = nullptr);

// Appends Cairo's output to a string (for cairo_*_create_for_stream / write_to_png_stream); out
// of memory is reported to Cairo as CAIRO_STATUS_NO_MEMORY.
cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length);

// Throws for a failed Cairo status: std::bad_alloc for out of memory, InputError for what the
// input asked for (a size, a string, a transform Cairo cannot take), OutputError otherwise, the
// message `what`: Cairo's reason.
void check_cairo(cairo_status_t status, const std::string& what);
// Checks the context's status and its target surface's.
void check_cairo(cairo_t* cr, const std::string& what);

}  // namespace inkline::output::internal
