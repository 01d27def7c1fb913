// SPDX-License-Identifier: MIT
// Write-on: strokes timed back to back in drawing order at one speed; at every time each stroke's
// ink reaches as far along its drawn centerline as the schedule says (within 1 px), tapered at
// the tip; once done, the drawing is the frame's own.
#include "core/strokes/write_on.h"

#include "core/strokes/brush.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace inkline {
namespace {

// A frame with loops and open strokes of several kinds: a torus seen from above at a slant,
// hidden lines drawn too.
// `look`: "dashed" (12 px dashes, 6 px gaps), "textured" (the brush texture's holes), else plain.
test::Drawn torus_frame(const std::string& look = "") {
    const core::Mesh mesh = test::torus(1.0, 0.4, 96, 48);
    core::Scene scene = test::scene_for({.eye = {0.0, 2.2, 3.2}}, mesh);
    scene.lines.hidden = true;
    if (look == "dashed") scene.brush.dash_px = {12.0, 6.0};
    if (look == "textured") scene.brush.texture.emplace();
    return test::draw(mesh, scene);
}

// Arc length along a polyline (closed: with its closing segment) of the point nearest p.
double arc_of_nearest(const std::vector<glm::dvec2>& c, bool closed, const glm::dvec2& p) {
    double best = HUGE_VAL, best_arc = 0.0, arc = 0.0;
    const size_t n = c.size(), segments = closed ? n : n - 1;
    for (size_t i = 0; i < segments; ++i) {
        const glm::dvec2 a = c[i], b = c[(i + 1) % n], ab = b - a;
        const double len = glm::length(ab);
        const double t = len > 0.0 ? std::clamp(glm::dot(p - a, ab) / (len * len), 0.0, 1.0) : 0.0;
        const double d = glm::distance(a + t * ab, p);
        if (d < best) {
            best = d;
            best_arc = arc + t * len;
        }
        arc += len;
    }
    return best_arc;
}

double polyline_length(const std::vector<glm::dvec2>& c) {
    double length = 0.0;
    for (size_t i = 1; i < c.size(); ++i) length += glm::distance(c[i - 1], c[i]);
    return length;
}

TEST(WriteOn, StrokesAreTimedBackToBackInDrawingOrderAtOneSpeed) {
    const test::Drawn d = torus_frame();
    const core::WriteOnSchedule s = core::schedule_write_on(d.strokes, 2.5);
    ASSERT_GT(s.entries.size(), 4u);
    double total = 0.0, at = 0.0;
    uint32_t last_order = 0;
    for (size_t k = 0; k < s.entries.size(); ++k) {
        const core::WriteOnSchedule::Entry& e = s.entries[k];
        const core::Stroke& stroke = d.strokes.strokes[e.stroke];
        if (k > 0) {
            EXPECT_GT(stroke.order, last_order);
        }
        last_order = stroke.order;
        EXPECT_NEAR(e.start_s, at, 1e-9);
        at = s.end_s(e);
        total += e.length_px;
        EXPECT_NEAR(s.drawn_px(e, e.start_s + 0.5 * (s.end_s(e) - e.start_s)), 0.5 * e.length_px, 1e-6);
    }
    EXPECT_NEAR(at, 2.5, 1e-9);
    EXPECT_NEAR(s.speed_px_s, total / 2.5, 1e-9);
    // Every stroke the writers draw is timed.
    size_t written = 0;
    for (const core::Stroke& stroke : d.strokes.strokes) written += (!stroke.geometry.visible || stroke.drawn) ? 1 : 0;
    EXPECT_EQ(s.entries.size(), written);
}

// The ink of every stroke under way reaches as far along its drawn centerline as the schedule
// says, within 1 px (less up to gap_px where the tip is in a gap between dashes), its tip
// thinner than the stroke was there, for every frame of a 24 fps write-on; a finished stroke is
// the frame's own.
void expect_ink_follows_schedule(const test::Drawn& d, double gap_px = 0.0) {
    const double seconds = 1.5, fps = 24.0;
    const core::WriteOnSchedule s = core::schedule_write_on(d.strokes, seconds);
    size_t under_way = 0;
    for (int frame = 0; frame <= int(seconds * fps); ++frame) {
        const double t = frame / fps;
        const core::FrameStrokes at = core::strokes_at(d.strokes, s, t);
        ASSERT_TRUE(at.write_on);
        ASSERT_EQ(at.write_on->strokes.size(), at.strokes.size());
        std::set<uint32_t> shown;
        for (size_t k = 0; k < at.strokes.size(); ++k) shown.insert(at.strokes[k].id);
        for (const core::WriteOnSchedule::Entry& e : s.entries) {
            const core::Stroke& full = d.strokes.strokes[e.stroke];
            const double drawn = s.drawn_px(e, t);
            EXPECT_EQ(shown.count(full.id) == 1, drawn > 0.0) << "stroke " << full.id << " at " << t;
        }
        for (size_t k = 0; k < at.strokes.size(); ++k) {
            const core::Stroke& part = at.strokes[k];
            const core::WriteOnFrame::StrokeProgress& p = at.write_on->strokes[k];
            if (p.start_s < 0.0) {  // not timed: shown once done
                EXPECT_GE(t, seconds);
                continue;
            }
            const auto it = std::find_if(s.entries.begin(), s.entries.end(),
                                         [&](const auto& e) { return d.strokes.strokes[e.stroke].id == part.id; });
            ASSERT_NE(it, s.entries.end());
            const core::Stroke& full = d.strokes.strokes[it->stroke];
            EXPECT_NEAR(p.drawn_px, s.drawn_px(*it, t), 1e-9);
            if (p.drawn_px >= p.length_px) {
                EXPECT_EQ(part.outline, full.outline);
                EXPECT_EQ(part.centerline_px, full.centerline_px);
                continue;
            }
            ++under_way;
            EXPECT_FALSE(part.geometry.closed);
            EXPECT_NEAR(polyline_length(part.centerline_px), p.drawn_px, 1e-6);
            // The drawn part is the whole stroke's up to the tip, no wider; the tip is a point.
            for (size_t i = 0; i + 1 < part.centerline_px.size(); ++i) {
                EXPECT_EQ(part.centerline_px[i], full.centerline_px[i]);
                EXPECT_LE(part.centerline_width[i], full.centerline_width[i] + 1e-12);
            }
            EXPECT_EQ(part.centerline_width.back(), 0.0);
            // How far the ink reaches along the whole stroke's centerline (a loop's ink around its
            // start, whose nearest point may lie on its closing segment, left out).
            const std::vector<core::Ring> rings = full.geometry.visible ? part.outline : std::vector<core::Ring>{part.centerline_px};
            const double widest = *std::max_element(full.centerline_width.begin(), full.centerline_width.end());
            double reach = 0.0;
            for (const core::Ring& ring : rings) {
                for (const glm::dvec2& q : ring) {
                    if (full.geometry.closed && glm::distance(q, full.centerline_px.front()) <= 0.5 * widest + 1.0) continue;
                    reach = std::max(reach, arc_of_nearest(full.centerline_px, full.geometry.closed, q));
                }
            }
            EXPECT_LE(reach, p.drawn_px + 1.0) << "stroke " << part.id << " at " << t;
            if (p.drawn_px > 0.5 * widest + 2.0) {
                EXPECT_GE(reach, p.drawn_px - 1.0 - gap_px) << "stroke " << part.id << " at " << t;
            }
        }
    }
    EXPECT_GT(under_way, 20u);
    // Done: the frame's drawing.
    const core::FrameStrokes done = core::strokes_at(d.strokes, s, seconds);
    ASSERT_EQ(done.strokes.size(), d.strokes.strokes.size());
    for (size_t k = 0; k < done.strokes.size(); ++k) {
        EXPECT_EQ(done.strokes[k].id, d.strokes.strokes[k].id);
        EXPECT_EQ(done.strokes[k].outline, d.strokes.strokes[k].outline);
    }
}

TEST(WriteOn, InkReachesAsFarAsTheScheduleSaysAtEveryFrame) { expect_ink_follows_schedule(torus_frame()); }

TEST(WriteOn, TexturedStrokesAreWrittenOnWithTheirHoles) {
    const test::Drawn d = torus_frame("textured");
    size_t holes = 0;
    for (const core::Stroke& s : d.strokes.strokes) holes += s.outline.size() > 2 ? 1 : 0;
    EXPECT_GT(holes, 2u);
    expect_ink_follows_schedule(d);
}

TEST(WriteOn, DashedStrokesAreWrittenOnWithTheirDashesInPlace) {
    const test::Drawn d = torus_frame("dashed");
    expect_ink_follows_schedule(d, 6.0);
    // A dash drawn so far lies where the finished stroke has one.
    const core::WriteOnSchedule s = core::schedule_write_on(d.strokes, 1.0);
    const core::FrameStrokes half = core::strokes_at(d.strokes, s, 0.5);
    size_t checked = 0;
    for (const core::Stroke& part : half.strokes) {
        if (!part.geometry.visible || part.outline.size() < 3) continue;
        const auto full = std::find_if(d.strokes.strokes.begin(), d.strokes.strokes.end(), [&](const core::Stroke& x) { return x.id == part.id; });
        ASSERT_NE(full, d.strokes.strokes.end());
        // Every whole dash but the last (the tip's) is one of the finished stroke's.
        for (size_t r = 0; r + 1 < part.outline.size(); ++r) {
            EXPECT_NE(std::find(full->outline.begin(), full->outline.end(), part.outline[r]), full->outline.end());
            ++checked;
        }
    }
    EXPECT_GT(checked, 10u);
}

TEST(WriteOn, AStrokeWithoutACenterlineAppearsWhenTheDrawingIsDone) {
    test::Drawn d = torus_frame();
    ASSERT_GT(d.strokes.strokes.size(), 2u);
    core::Stroke& bare = d.strokes.strokes[1];
    bare.geometry.visible = false;
    bare.centerline_px.clear();
    const core::WriteOnSchedule s = core::schedule_write_on(d.strokes, 1.0);
    EXPECT_TRUE(std::none_of(s.entries.begin(), s.entries.end(), [](const auto& e) { return e.stroke == 1; }));
    const auto has_bare = [&](const core::FrameStrokes& f) {
        return std::any_of(f.strokes.begin(), f.strokes.end(), [&](const core::Stroke& x) { return x.id == bare.id; });
    };
    EXPECT_FALSE(has_bare(core::strokes_at(d.strokes, s, 0.999)));
    const core::FrameStrokes done = core::strokes_at(d.strokes, s, 1.0);
    ASSERT_TRUE(has_bare(done));
    for (size_t k = 0; k < done.strokes.size(); ++k) {
        if (done.strokes[k].id == bare.id) {
            EXPECT_LT(done.write_on->strokes[k].start_s, 0.0);
        }
    }
}

TEST(WriteOn, NothingIsDrawnAtTheStartAndAnEmptyFrameIsDoneAtOnce) {
    const test::Drawn d = torus_frame();
    const core::WriteOnSchedule s = core::schedule_write_on(d.strokes, 1.0);
    EXPECT_TRUE(core::strokes_at(d.strokes, s, 0.0).strokes.empty());
    core::FrameStrokes empty;
    const core::WriteOnSchedule none = core::schedule_write_on(empty, 1.0);
    EXPECT_TRUE(none.entries.empty());
    EXPECT_EQ(none.speed_px_s, 0.0);
    EXPECT_TRUE(core::strokes_at(empty, none, 0.5).strokes.empty());
}

}  // namespace
}  // namespace inkline
