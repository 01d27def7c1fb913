// SPDX-License-Identifier: MIT
#include "gl/brush_tip.h"

#include "core/error.h"
#include "core/random.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace inkline::gl {
namespace {

// The built-in tip: 12 stroke widths long, so that at the default width_max_px of 4.8 px its
// head covers 7 px, each repeat of the middle 33 px and the dry tail 17 px. 64 rows resolve
// streaks a texel or two wide, which mipmapping averages away on thin strokes.
constexpr int kTipWidth = 768;
constexpr int kTipHeight = 64;
constexpr double kHeadFraction = 0.12;
constexpr double kTailFraction = 0.3;
// A soft edge of an eighth of the height on each side: alpha rises from 0 at the image border to
// 1/2 on the outline and to 1 as far inside it. Of 0.1, 0.125 and 0.15, this one kept the ink
// coverage closest to the outlines' (IoU 0.947, 0.968, 0.968 on the torus test frame; 0.930,
// 0.957, 0.949 on the cube), where mipmapping averages the profile across thin strokes.
constexpr double kEdgeMargin = 0.125;

constexpr int kStreaks = 16;  // bristle streaks along the stroke
constexpr int kLanes = 26;    // bands across the stroke that dry out independently in the tail
// No streak takes more than this much ink, so the body stays above one half everywhere and the
// ink coverage (alpha > 1/2) of a stroke is its outline.
constexpr double kMinBodyAlpha = 0.62;

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Smooth 1D value noise in [0, 1] with one feature per unit of x, from a table of knots.
double value_noise(const std::vector<double>& knots, double x) {
    const double f = std::floor(x);
    const auto i = size_t(std::max(f, 0.0)) % knots.size();
    const double t = smoothstep(0.0, 1.0, x - f);
    return knots[i] + (knots[(i + 1) % knots.size()] - knots[i]) * t;
}

struct Streak {
    double y = 0.0;      // centre across the image, 0..1
    double sigma = 0.0;  // Gaussian half-width, in image heights
    double depth = 0.0;  // ink taken at its strongest
    int cycles = 1;      // of its strength along one repeat of the middle (so the middle tiles)
    double phase = 0.0;
};

struct Lane {
    double y_end = 0.0;   // upper boundary across the image; the lane starts at the previous one's
    double dry_at = 0.0;  // dryness at which it breaks
    std::vector<double> noise_knots;
};

}  // namespace

BrushTip default_brush_tip() {
    BrushTip tip;
    tip.width = kTipWidth;
    tip.height = kTipHeight;
    tip.head_fraction = kHeadFraction;
    tip.tail_fraction = kTailFraction;
    tip.edge_margin = kEdgeMargin;
    tip.alpha.resize(size_t(kTipWidth) * kTipHeight);

    core::SplitMix64 random(0x1b2d3f4e5a697887ull);
    std::array<Streak, kStreaks> streaks;
    for (Streak& s : streaks) {
        s.y = random.uniform(kEdgeMargin, 1.0 - kEdgeMargin);
        s.sigma = random.uniform(0.5, 1.4) / kTipHeight;
        s.depth = random.uniform(0.10, 0.30);
        s.cycles = 1 + int(random.uniform(0.0, 3.0));
        s.phase = random.uniform(0.0, 1.0);
    }
    // Lanes: random widths; those near the border break first, as a drying brush splits at its
    // edges before its core.
    std::array<Lane, kLanes> lanes;
    double y = 0.0;
    std::array<double, kLanes> widths;
    for (double& w : widths) y += (w = random.uniform(0.5, 1.5));
    double acc = 0.0;
    for (int l = 0; l < kLanes; ++l) {
        Lane& lane = lanes[size_t(l)];
        acc += widths[size_t(l)] / y;
        lane.y_end = l + 1 == kLanes ? 1.0 : acc;
        const double centre = acc - 0.5 * widths[size_t(l)] / y;
        const double to_border = std::min(centre, 1.0 - centre) * 2.0;  // 0 at the border, 1 in the middle
        lane.dry_at = random.uniform(0.25, 1.05) * (0.55 + 0.45 * to_border);
        lane.noise_knots.resize(96);
        for (double& k : lane.noise_knots) k = random.uniform(0.0, 1.0);
    }

    const double body = 1.0 - kHeadFraction - kTailFraction;
    for (int j = 0; j < kTipHeight; ++j) {
        const double v = (j + 0.5) / kTipHeight;
        // Soft edge: one half on the outline, which lies kEdgeMargin inside the border.
        const double edge = smoothstep(0.0, 2.0 * kEdgeMargin, std::min(v, 1.0 - v));
        const Lane* lane = &lanes.back();
        for (const Lane& l : lanes) {
            if (v < l.y_end) {
                lane = &l;
                break;
            }
        }
        for (int i = 0; i < kTipWidth; ++i) {
            const double x = (i + 0.5) / kTipWidth;
            // Position in repeats of the middle: continuous through head and tail, and the
            // streak strengths have whole cycles per repeat, so the middle tiles.
            const double xb = (x - kHeadFraction) / body;
            double taken = 0.0;
            for (const Streak& s : streaks) {
                const double strength = 0.55 + 0.45 * std::sin(2.0 * std::numbers::pi * (s.cycles * xb + s.phase));
                const double d = (v - s.y) / s.sigma;
                taken += s.depth * strength * std::exp(-0.5 * d * d);
            }
            // The head is set down loaded with ink: fewer streaks.
            if (x < kHeadFraction) taken *= 0.4 + 0.6 * smoothstep(0.0, kHeadFraction, x);
            double a = std::max(1.0 - taken, kMinBodyAlpha);

            // Dry brush: past the start of the tail, lanes break where the dryness, wobbled by
            // each lane's own noise along the stroke, passes their threshold.
            const double t = std::clamp((x - (1.0 - kTailFraction)) / kTailFraction, 0.0, 1.0);
            if (t > 0.0) {
                const double dryness = 1.1 * std::pow(t, 1.6);
                const double wobble = 0.6 * (value_noise(lane->noise_knots, x * 64.0) - 0.5);
                const double gap = smoothstep(lane->dry_at - 0.05, lane->dry_at + 0.05, dryness + wobble);
                a *= (1.0 - 0.92 * gap) * (1.0 - 0.25 * t * t * t);
            }
            // The edge bounds the ink rather than scaling it: a streak along the outline must not
            // pull it under one half there.
            tip.alpha[size_t(j) * kTipWidth + size_t(i)] =
                uint8_t(std::lround(255.0 * std::clamp(std::min(a, edge), 0.0, 1.0)));
        }
    }
    return tip;
}

BrushTip load_brush_tip(const std::filesystem::path& png) {
    const std::string name = png.string();
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    // The simplified API frees its own state when begin fails and when finish returns.
    if (!png_image_begin_read_from_file(&image, name.c_str())) {
        throw InputError(name + ": cannot read the brush tip as PNG (" + image.message + ")");
    }
    const auto width = int(image.width), height = int(image.height);
    if (image.width < 2 || image.height < 2 || image.width > kMaxBrushTipSide || image.height > kMaxBrushTipSide) {
        png_image_free(&image);
        throw InputError(name + ": brush tip of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " px; each side must be 2.." + std::to_string(kMaxBrushTipSide));
    }
    const bool has_alpha = (image.format & PNG_FORMAT_FLAG_ALPHA) != 0;
    image.format = PNG_FORMAT_GA;  // 8-bit gray (sRGB) and alpha, converted by libpng
    std::vector<uint8_t> gray_alpha(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, gray_alpha.data(), 0, nullptr)) {
        throw InputError(name + ": cannot decode the brush tip (" + image.message + ")");
    }
    BrushTip tip;
    tip.width = width;
    tip.height = height;
    tip.alpha.resize(size_t(width) * size_t(height));
    bool transparent = false;
    for (size_t k = 0; k < tip.alpha.size(); ++k) transparent |= gray_alpha[2 * k + 1] != 255;
    for (size_t k = 0; k < tip.alpha.size(); ++k) {
        tip.alpha[k] = has_alpha && transparent ? gray_alpha[2 * k + 1] : gray_alpha[2 * k];
    }
    return tip;
}

}  // namespace inkline::gl
