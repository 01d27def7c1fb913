// SPDX-License-Identifier: MIT
// Write-on: a frame's drawing as a person draws it, one stroke after another in drawing order
// (drawing_order.h), each along u from its start, at one speed for the whole drawing, the brush's
// taper growing at the moving tip. schedule_write_on() times the strokes; strokes_at() gives the
// drawing at a time.
#pragma once

#include "core/strokes/strokes.h"

#include <cstdint>
#include <vector>

namespace inkline::core {

// When each stroke is drawn: back to back in drawing order, at speed_px_s.
struct WriteOnSchedule {
    struct Entry {
        uint32_t stroke = 0;     // index into the frame's strokes
        double start_s = 0.0;    // when its tip sets off
        double length_px = 0.0;  // its drawn centerline's length (a loop's closing segment included)
    };
    double seconds = 0.0;        // the whole drawing takes this long
    double speed_px_s = 0.0;     // the strokes' total length over seconds
    std::vector<Entry> entries;  // in drawing order

    // When the entry's stroke is finished.
    double end_s(const Entry& entry) const;
    // Length of the entry's stroke drawn at time t (s): 0 until its start, then speed_px_s per
    // second, its whole length from end_s on.
    double drawn_px(const Entry& entry, double t) const;
};

// Times every stroke the writers draw that has a drawn centerline of some length: visible strokes
// that are drawn (Stroke::drawn) and hidden strokes, in their `order`.
// A stroke without such a centerline has no entry: it appears whole when the drawing is done.
// seconds must be above 0.
WriteOnSchedule schedule_write_on(const FrameStrokes& strokes, double seconds);

// The frame's drawing at time t (s) since it began: the strokes that have started, in the
// order they are stored, each with its drawn centerline (samples, u, width) cut where its tip is
// and its outline made again from that (stroke_ink): the width tapers to a point over
// brush.taper_px behind the moving tip, as at a free end, so the ink ends where the tip is; a
// loop under way is an open stroke; a finished stroke is exactly the frame's. Strokes without an
// entry are left out until t reaches the schedule's seconds; from then on the strokes are the
// frame's, whole. Geometry, exact u, intensity and widths stay whole; FrameStrokes::write_on says
// how far each stroke is drawn.
FrameStrokes strokes_at(const FrameStrokes& strokes, const WriteOnSchedule& schedule, double t);

}  // namespace inkline::core
