// SPDX-License-Identifier: MIT
// The brush's character as vector shapes (`brush.texture`): dry-brush breaks where a free end is
// lifted off the paper and bristle streaks along the stroke, cut out of the stroke's outline as
// holes, as the GL preview's tip shows them (gl/brush_tip.h). Everything is placed by u, which is
// carried from frame to frame, and drawn from a generator seeded with the stroke's id, so a
// frame is reproducible and the texture stays on the stroke as it moves. docs/styles.md.
#pragma once

#include "core/strokes/brush_style.h"
#include "core/strokes/outline.h"
#include "core/strokes/stroke_geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

// One hole of the texture: a ring, and the part of u and the band across the stroke it spans
// (bands 0..6: the dry brush's lanes, from the right edge to the left; 7..11: the streaks).
struct TextureHole {
    int band = 0;
    double u_start = 0.0, u_end = 0.0;
    Ring ring;
};

// The holes the texture cuts into one stroke's outline: rings oriented against the outline's, so
// that filled together with it (nonzero rule) they are left blank. c, u and width are the drawn
// centerline's samples; outline the stroke's rings (one, or two for a loop).
std::vector<TextureHole> texture_gaps(std::span<const glm::dvec2> c, std::span<const double> u, std::span<const double> width,
                               bool closed, StrokeEnd end, uint32_t stroke_id, const BrushTexture& texture,
                               const std::vector<Ring>& outline);

// How much darker a stroke is drawn for the pressure its widths show: texture.pressure times the
// mean of (w - width_min_px) / (width_max_px - width_min_px) along it, in [0, 1].
double pressure_darkening(std::span<const double> width, const BrushStyle& style);

}  // namespace inkline::core
