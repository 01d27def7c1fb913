// SPDX-License-Identifier: MIT
// The brush's texture as vector holes: inside the ink and against it, seeded by the stroke's id,
// dry only toward free ends, and anchored to u as strokes move.
#include "core/strokes/brush_texture.h"

#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/strokes/outline.h"
#include "core/visibility/occlusion_source.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

namespace inkline {
namespace {

constexpr int kDryBands = 7;  // bands below this are the dry brush's lanes, the rest streaks

struct Line {
    std::vector<glm::dvec2> c;
    std::vector<double> u, w;
};

// A gently curving stroke of `length` px, sampled every half pixel, of constant width, its u
// starting at u0.
Line arc(double length, double width, double u0) {
    Line l;
    for (double s = 0.0; s <= length; s += 0.5) {
        l.c.push_back({100.0 + s, 200.0 + 20.0 * std::sin(s / 80.0)});
        l.u.push_back(u0 + s);
        l.w.push_back(width);
    }
    return l;
}

double distance_to(const Line& l, const glm::dvec2& p) {
    double best = HUGE_VAL;
    for (size_t i = 0; i + 1 < l.c.size(); ++i) {
        const glm::dvec2 ab = l.c[i + 1] - l.c[i];
        const double t = std::clamp(glm::dot(p - l.c[i], ab) / glm::dot(ab, ab), 0.0, 1.0);
        best = std::min(best, glm::length(p - (l.c[i] + ab * t)));
    }
    return best;
}

TEST(BrushTexture, HolesLieInsideTheInkAndRunAgainstIt) {
    const Line l = arc(300.0, 6.0, 0.0);
    const std::vector<core::Ring> outline = core::build_outline(l.c, l.w, false, {});
    ASSERT_EQ(outline.size(), 1u);
    const double ink = core::signed_area(outline.front());
    const core::BrushTexture texture{.dry = 1.0, .dry_px = 60.0, .streaks = 1.0, .pressure = 0.25};
    const auto holes = core::texture_gaps(l.c, l.u, l.w, false, core::StrokeEnd::kFree, 7, texture, outline);
    size_t dry = 0, streaks = 0;
    for (const core::TextureHole& h : holes) {
        EXPECT_LT(core::signed_area(h.ring) * ink, 0.0) << "a hole runs against the ink";
        for (const glm::dvec2& p : h.ring) EXPECT_LT(distance_to(l, p), 0.5 * 6.0) << "inside the ink";
        EXPECT_LE(h.u_start, h.u_end);
        if (h.band < kDryBands) {
            ++dry;
            EXPECT_GE(h.u_start, 300.0 - 60.0) << "dry only in the tail";
        } else {
            ++streaks;
        }
    }
    EXPECT_GT(dry, 0u);
    EXPECT_GT(streaks, 0u);
    // Blunt ends and loops never dry out; without streaks, they have no holes.
    const core::BrushTexture dry_only{.dry = 1.0, .dry_px = 60.0, .streaks = 0.0, .pressure = 0.0};
    EXPECT_TRUE(core::texture_gaps(l.c, l.u, l.w, false, core::StrokeEnd::kCorner, 7, dry_only, outline).empty());
    EXPECT_FALSE(core::texture_gaps(l.c, l.u, l.w, false, core::StrokeEnd::kFree, 7, dry_only, outline).empty());
}

TEST(BrushTexture, SeededByTheStrokeIdAndPlacedByU) {
    const core::BrushTexture texture;
    const Line a = arc(400.0, 5.0, 0.0);
    const auto outline = core::build_outline(a.c, a.w, false, {});
    const auto first = core::texture_gaps(a.c, a.u, a.w, false, core::StrokeEnd::kFree, 3, texture, outline);
    const auto again = core::texture_gaps(a.c, a.u, a.w, false, core::StrokeEnd::kFree, 3, texture, outline);
    ASSERT_EQ(first.size(), again.size());
    for (size_t k = 0; k < first.size(); ++k) EXPECT_EQ(first[k].ring, again[k].ring);
    const auto other = core::texture_gaps(a.c, a.u, a.w, false, core::StrokeEnd::kFree, 4, texture, outline);
    bool differs = other.size() != first.size();
    for (size_t k = 0; !differs && k < first.size(); ++k) differs = first[k].u_start != other[k].u_start;
    EXPECT_TRUE(differs) << "another stroke, another texture";

    // The same stroke 30 px further along its u: every streak moves with u, so a streak at u
    // shows at u again (sampling aside).
    const Line b = arc(400.0, 5.0, 30.0);
    const auto shifted = core::texture_gaps(b.c, b.u, b.w, false, core::StrokeEnd::kCorner, 3, texture, outline);
    const auto base = core::texture_gaps(a.c, a.u, a.w, false, core::StrokeEnd::kCorner, 3, texture, outline);
    size_t matched = 0;
    for (const core::TextureHole& h : base) {
        if (h.u_start < 40.0 || h.u_end > 390.0) continue;  // runs that the shift cuts at an end
        for (const core::TextureHole& g : shifted) {
            if (g.band == h.band && std::abs(g.u_start - h.u_start) <= 0.5 && std::abs(g.u_end - h.u_end) <= 0.5) ++matched;
        }
    }
    size_t inner = 0;
    for (const core::TextureHole& h : base) inner += h.u_start >= 40.0 && h.u_end <= 390.0;
    EXPECT_GT(inner, 3u);
    EXPECT_EQ(matched, inner);
}

TEST(BrushTexture, PressureDarkensByTheMeanWidth) {
    core::BrushStyle style;
    EXPECT_EQ(core::pressure_darkening(std::vector<double>{4.8, 4.8}, style), 0.0) << "no texture, no darkening";
    style.texture = core::BrushTexture{.pressure = 0.5};
    EXPECT_DOUBLE_EQ(core::pressure_darkening(std::vector<double>{style.width_max_px, style.width_max_px}, style), 0.5);
    EXPECT_DOUBLE_EQ(core::pressure_darkening(std::vector<double>{style.width_min_px, style.width_max_px}, style), 0.25);
    EXPECT_DOUBLE_EQ(core::pressure_darkening(std::vector<double>{0.0}, style), 0.0);
}

// The torus sample turning 3 degrees a frame with a textured brush: a hole found in one frame
// is found again in the next at the same u, to within a pixel, on strokes that keep their id.
TEST(BrushTexture, HolesStayOnTheStrokeAlongTheTorusTurntable) {
    core::Scene scene = core::load_scene(std::filesystem::path(INKLINE_SAMPLES) / "torus" / "scene.json");
    scene.last_frame = scene.first_frame + 119;  // 3 degrees a frame
    scene.brush.texture = core::BrushTexture{};
    core::MeshFrames meshes(scene.mesh, scene.first_frame);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    using Holes = std::map<uint32_t, std::vector<core::TextureHole>>;  // by stroke id
    const auto holes_of = [&](const core::FrameStrokes& frame) {
        Holes out;
        for (const core::Stroke& s : frame.strokes) {
            if (!s.drawn || !s.geometry.visible) continue;
            out[s.id] = core::texture_gaps(s.centerline_px, s.centerline_u, s.centerline_width, s.geometry.closed,
                                           s.geometry.ends[1], s.id, *scene.brush.texture, s.outline);
        }
        return out;
    };
    Holes last = holes_of(pipeline.run(scene.first_frame).strokes);
    std::vector<double> drift;
    for (int f = scene.first_frame + 1; f <= scene.first_frame + 20; ++f) {
        Holes now = holes_of(pipeline.run(f).strokes);
        for (const auto& [id, holes] : now) {
            const auto before = last.find(id);
            if (before == last.end()) continue;
            for (const core::TextureHole& h : holes) {
                // The nearest hole of the same band last frame, if one lies within 10 px.
                double best = HUGE_VAL;
                for (const core::TextureHole& g : before->second) {
                    if (g.band != h.band) continue;
                    best = std::min(best, std::abs(0.5 * (g.u_start + g.u_end) - 0.5 * (h.u_start + h.u_end)));
                }
                if (best <= 10.0) drift.push_back(best);
            }
        }
        last = std::move(now);
    }
    ASSERT_GT(drift.size(), 200u);
    std::sort(drift.begin(), drift.end());
    const double median = drift[drift.size() / 2], p90 = drift[drift.size() * 9 / 10];
    std::printf("[ texture ] %zu matched holes, drift along u: median %.3f px, 90th percentile %.3f px a frame\n",
                drift.size(), median, p90);
    EXPECT_LE(median, 1.0);
    EXPECT_LE(p90, 1.0);
}

}  // namespace
}  // namespace inkline
