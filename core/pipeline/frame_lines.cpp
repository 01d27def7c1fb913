// SPDX-License-Identifier: MIT
#include "core/pipeline/frame_lines.h"

namespace inkline::core {

void set_aside_occluded(FrameLines& frame) {
    std::vector<Polyline> shown;
    for (Polyline& line : frame.polylines) (line.visible ? shown : frame.occluded).push_back(std::move(line));
    for (size_t i = 0; i < shown.size(); ++i) shown[i].id = uint32_t(i);
    frame.polylines = std::move(shown);
}

void tally_visible_length(FrameLines& frame) {
    frame.stats.visible_length_px.fill(0.0);
    for (const Polyline& line : frame.polylines) {
        if (line.visible) frame.stats.visible_length_px[size_t(line.kind)] += line.length_px();
    }
}

}  // namespace inkline::core
