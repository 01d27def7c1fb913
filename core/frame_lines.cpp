// SPDX-License-Identifier: MIT
#include "core/frame_lines.h"

namespace inkline::core {

void tally_visible_length(FrameLines& frame) {
    frame.stats.visible_length_px.fill(0.0);
    for (const Polyline& line : frame.strokes) {
        if (line.visible) frame.stats.visible_length_px[size_t(line.kind)] += line.length_px();
    }
}

}  // namespace inkline::core
