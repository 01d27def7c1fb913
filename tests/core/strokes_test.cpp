// SPDX-License-Identifier: MIT
#include "core/strokes/strokes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/geometric.hpp>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/lines/chaining.h"
#include "core/lines/features.h"
#include "core/mesh/mesh_frames.h"
#include "core/scene/scene.h"
#include "core/strokes/stroke_path.h"
#include "core/visibility/exact_visibility.h"
#include "core/visibility/visibility.h"

namespace inkline {
namespace {

// The torus sample turning 3 degrees per frame (a full turn in 120 frames), run through the
// pipeline as the CLI runs it, strokes included.
class TorusTurn {
  public:
    explicit TorusTurn(const core::BrushStyle& style = {}, bool keep_hidden = false)
        : style_(style), keep_hidden_(keep_hidden) {
        scene_ = core::load_scene(std::filesystem::path(INKLINE_SAMPLES) / "torus" / "scene.json");
        scene_.last_frame = scene_.first_frame + 119;
        meshes_ = std::make_unique<core::MeshFrames>(scene_.mesh, scene_.first_frame);
        occlusion_ = std::make_unique<core::ExactOcclusion>(meshes_->at(scene_.first_frame), meshes_->edges());
    }

    int first_frame() const { return scene_.first_frame; }

    core::FrameStrokes next(core::StrokeCoherence& coherence, int frame) {
        const core::Mesh& mesh = meshes_->at(frame);
        const glm::dmat4 world_from_object = core::world_from_object_at(scene_, frame);
        core::Bounds world_bounds;
        for (const glm::vec3& p : mesh.positions)
            world_bounds.add(glm::dvec3(world_from_object * glm::dvec4(glm::dvec3(p), 1.0)));
        core::FrameLines lines;
        lines.frame = frame;
        lines.image = scene_.image;
        lines.light = scene_.light;
        lines.camera = core::camera_at(scene_, frame, world_bounds);
        const core::Projection projection(lines.camera, scene_.image, world_from_object);
        const core::EdgeTable& table = meshes_->edges();
        const core::FeatureEdges features =
            core::extract_feature_edges(mesh, table, projection.eye_object(), scene_.lines);
        lines.polylines = core::split_by_visibility(core::chain_feature_edges(features, table), mesh, projection,
                                                  *occlusion_, {.keep_hidden = true});
        if (!keep_hidden_) core::set_aside_occluded(lines);
        return core::build_strokes(lines, mesh, table, projection, style_, coherence);
    }

  private:
    core::BrushStyle style_;
    bool keep_hidden_ = false;
    core::Scene scene_;
    std::unique_ptr<core::MeshFrames> meshes_;
    std::unique_ptr<core::ExactOcclusion> occlusion_;
};

void expect_identical(const core::FrameStrokes& a, const core::FrameStrokes& b) {
    ASSERT_EQ(a.strokes.size(), b.strokes.size());
    for (size_t i = 0; i < a.strokes.size(); ++i) {
        const core::Stroke& x = a.strokes[i];
        const core::Stroke& y = b.strokes[i];
        EXPECT_EQ(x.id, y.id);
        EXPECT_EQ(x.geometry.points_px, y.geometry.points_px);
        EXPECT_EQ(x.geometry.edges, y.geometry.edges);
        EXPECT_EQ(x.u, y.u);
        EXPECT_EQ(x.width, y.width);
        EXPECT_EQ(x.outline, y.outline);
    }
}

TEST(Strokes, PerPointDataIsComplete) {
    TorusTurn torus;
    core::StrokeCoherence coherence;
    const core::FrameStrokes frame = torus.next(coherence, torus.first_frame());
    ASSERT_FALSE(frame.strokes.empty());
    std::set<uint32_t> ids;
    for (const core::Stroke& s : frame.strokes) {
        EXPECT_TRUE(ids.insert(s.id).second) << "ids are unique within a frame";
        const size_t n = s.geometry.points_px.size();
        ASSERT_GE(n, 2u);
        EXPECT_EQ(s.geometry.points_world.size(), n);
        EXPECT_EQ(s.geometry.edges.size(), n - 1);
        EXPECT_EQ(s.u.size(), n);
        EXPECT_EQ(s.intensity.size(), n);
        EXPECT_EQ(s.width.size(), n);
        for (size_t k = 1; k < n; ++k) EXPECT_GE(s.u[k], s.u[k - 1]) << "u runs along the stroke";
        for (size_t k = 0; k < n; ++k) {
            EXPECT_TRUE(s.intensity[k] >= 0.0 && s.intensity[k] <= 1.0);
            EXPECT_TRUE(s.width[k] >= 0.0 && s.width[k] <= core::BrushStyle{}.width_max_px);
        }
        if (s.geometry.closed) {
            EXPECT_EQ(s.geometry.ends[0], core::StrokeEnd::kLoop);
            EXPECT_EQ(s.u.front(), 0.0);
            EXPECT_EQ(s.geometry.points_px.front(), s.geometry.points_px.back());
            EXPECT_EQ(s.outline.size(), 2u);
        } else if (s.drawn) {
            EXPECT_EQ(s.outline.size(), 1u);
        }
        EXPECT_EQ(s.drawn, !s.outline.empty());
        EXPECT_LE(s.deviation_px, core::BrushStyle{}.max_deviation_px + 1e-9);
    }
    EXPECT_EQ(frame.stats.inherited, 0u) << "the first frame inherits nothing";
}

// Whether two parts of a centerline that lie apart along it (more than twice the widest width)
// come closer than their half widths: then the brush covers one place twice (a stroke whose two
// ends overlap where a zig-zag silhouette turns), and no single simple ring can outline it.
bool brush_overlaps_itself(const std::vector<glm::dvec2>& c, const std::vector<double>& w, bool closed) {
    std::vector<double> arc(c.size(), 0.0);
    for (size_t i = 1; i < c.size(); ++i) arc[i] = arc[i - 1] + glm::length(c[i] - c[i - 1]);
    const double total = closed && !c.empty() ? arc.back() + glm::length(c.front() - c.back()) : arc.back();
    const double apart = 2.0 * *std::max_element(w.begin(), w.end());
    for (size_t i = 0; i < c.size(); ++i) {
        for (size_t j = i + 1; j < c.size(); ++j) {
            double along = arc[j] - arc[i];
            if (closed) along = std::min(along, total - along);
            if (along > apart && glm::length(c[i] - c[j]) < 0.5 * (w[i] + w[j])) return true;
        }
    }
    return false;
}

// Outlines of real frames (every 10th frame of a turn, strokes joined by memory included):
// closed, simple where the brush does not cover a place twice, faithful to the width (area
// within 3% of the width integral plus round caps) and never sticking out of the centerline's
// width.
TEST(Strokes, OutlinesOfATorusFrameAreFaithful) {
    TorusTurn torus;
    core::StrokeCoherence coherence;
    std::vector<core::Stroke> strokes;
    for (int f = torus.first_frame(); f <= torus.first_frame() + 30; ++f) {
        core::FrameStrokes frame = torus.next(coherence, f);
        if ((f - torus.first_frame()) % 10 != 0) continue;
        for (core::Stroke& s : frame.strokes) strokes.push_back(std::move(s));
    }
    size_t checked = 0, simple = 0;
    for (const core::Stroke& s : strokes) {
        if (!s.drawn) continue;
        const std::vector<glm::dvec2>& c = s.centerline_px;
        const std::vector<double>& w = s.centerline_width;
        const size_t n = c.size();
        double swept = 0.0;
        for (size_t i = 0; i + 1 < n + (s.geometry.closed ? 1 : 0); ++i) {
            swept += 0.5 * (w[i] + w[(i + 1) % n]) * glm::length(c[(i + 1) % n] - c[i]);
        }
        if (!s.geometry.closed) swept += (w.front() * w.front() + w.back() * w.back()) * 3.141592653589793 / 8.0;
        SCOPED_TRACE("stroke " + std::to_string(s.id));
        if (s.geometry.length_px() >= 20.0) {
            EXPECT_NEAR(core::outline_area(s.outline), swept, 0.03 * swept);
        }
        const bool overlaps = brush_overlaps_itself(c, w, s.geometry.closed);
        simple += !overlaps;
        for (const core::Ring& ring : s.outline) {
            if (!overlaps) {
                EXPECT_TRUE(core::is_simple(ring));
            }
            for (const glm::dvec2& p : ring) {
                ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
                double excess = HUGE_VAL;
                for (size_t i = 0; i + (s.geometry.closed ? 0 : 1) < n; ++i) {
                    const glm::dvec2 a = c[i], ab = c[(i + 1) % n] - a;
                    const double len2 = glm::dot(ab, ab);
                    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
                    excess =
                        std::min(excess, glm::length(p - (a + ab * t)) - 0.5 * (w[i] + (w[(i + 1) % n] - w[i]) * t));
                }
                EXPECT_LE(excess, 0.25);
            }
        }
        ++checked;
    }
    EXPECT_GE(checked, 5u);
    EXPECT_GE(simple, checked - 3) << "most strokes cover no place twice";
}

double distance_to_polyline(const glm::dvec2& p, const std::vector<glm::dvec2>& line) {
    double best = HUGE_VAL;
    for (size_t i = 0; i + 1 < line.size(); ++i) best = std::min(best, core::distance_to_segment(p, line[i], line[i + 1]));
    return best;
}

// A gap drawn across (an occluded part inside a visible stroke) is drawn straight from where the
// line goes behind to where it comes out: the hidden folds of the torus's zig-zag silhouette
// near its cusps leave neither spikes nor holes in the outline.
TEST(Strokes, BridgedGapsAreDrawnStraightAcross) {
    TorusTurn torus;
    core::StrokeCoherence coherence;
    const double limit = core::BrushStyle{}.max_deviation_px + 1e-9;
    size_t folds = 0;
    for (int f = torus.first_frame(); f < torus.first_frame() + 40; ++f) {
        const core::FrameStrokes frame = torus.next(coherence, f);
        for (const core::Stroke& s : frame.strokes) {
            const core::StrokeGeometry& g = s.geometry;
            if (g.bridged.empty() || !s.drawn) continue;
            // The exact points with every point inside a bridged run left out.
            std::vector<glm::dvec2> drawn;
            for (size_t k = 0; k < g.points_px.size(); ++k) {
                const bool inside = k > 0 && k < g.bridged.size() && g.bridged[k - 1] && g.bridged[k];
                if (!inside) drawn.push_back(g.points_px[k]);
                if (inside && distance_to_polyline(g.points_px[k], drawn) > 2.0) ++folds;
            }
            SCOPED_TRACE("frame " + std::to_string(f) + " stroke " + std::to_string(s.id));
            for (const glm::dvec2& p : s.centerline_px) ASSERT_LE(distance_to_polyline(p, drawn), limit);
        }
    }
    EXPECT_GT(folds, 0u) << "the turn has hidden folds to draw across";
}

TEST(Strokes, SequenceIsDeterministicAndStateIsAValue) {
    TorusTurn torus;
    core::StrokeCoherence a, b;
    std::vector<core::FrameStrokes> first, second;
    for (int f = torus.first_frame(); f < torus.first_frame() + 4; ++f) first.push_back(torus.next(a, f));
    for (int f = torus.first_frame(); f < torus.first_frame() + 3; ++f) second.push_back(torus.next(b, f));
    // A copy of the state (as a chunked render would restore it) gives the same next frame.
    core::StrokeCoherence restored(b.traces(), b.next_id());
    second.push_back(torus.next(restored, torus.first_frame() + 3));
    for (size_t i = 0; i < first.size(); ++i) expect_identical(first[i], second[i]);
}

// Coherence figures over a full 3-degree-per-frame turn of the torus sample.
struct TurnFigures {
    double overall = 0.0;      // inherited fraction of all visible length
    double worst = 1.0;        // of the worst frame
    size_t at_95 = 0, frames = 0;
    double median_move = 0.0;  // loop start movement, px
};

TurnFigures measure_torus_turn(bool keep_hidden) {
    TorusTurn torus({}, keep_hidden);
    core::StrokeCoherence coherence;
    std::map<uint32_t, glm::dvec2> last_starts;
    std::vector<double> start_moves, fractions;
    double inherited = 0.0, visible = 0.0;
    for (int f = torus.first_frame(); f < torus.first_frame() + 120; ++f) {
        const core::FrameStrokes frame = torus.next(coherence, f);
        std::map<uint32_t, glm::dvec2> starts;
        for (const core::Stroke& s : frame.strokes) {
            if (!s.geometry.closed) continue;
            starts[s.id] = s.geometry.points_px.front();
            if (const auto it = last_starts.find(s.id); it != last_starts.end()) {
                start_moves.push_back(glm::length(it->second - s.geometry.points_px.front()));
            }
        }
        last_starts = starts;
        if (f == torus.first_frame()) continue;
        fractions.push_back(frame.stats.inherited_length_px / frame.stats.visible_length_px);
        inherited += frame.stats.inherited_length_px;
        visible += frame.stats.visible_length_px;
    }
    TurnFigures r;
    r.frames = fractions.size();
    r.at_95 = size_t(std::count_if(fractions.begin(), fractions.end(), [](double x) { return x >= 0.95; }));
    r.worst = *std::min_element(fractions.begin(), fractions.end());
    r.overall = inherited / visible;
    std::sort(start_moves.begin(), start_moves.end());
    if (!start_moves.empty()) r.median_move = start_moves[start_moves.size() / 2];
    std::printf(
        "torus turn%s: inherited length %.2f%% overall, frames >= 95%%: %zu of %zu, worst frame %.1f%%;"
        " loop start moves: median %.2f px over %zu\n",
        keep_hidden ? " (hidden lines kept)" : "", 100.0 * r.overall, r.at_95, r.frames, 100.0 * r.worst,
        r.median_move, start_moves.size());
    EXPECT_FALSE(start_moves.empty());
    return r;
}

// Acceptance figures (issue 5 asks for 95% in every frame): most visible length keeps its id
// from frame to frame, and loop starts barely move. Measured 117 of 119 frames at 95% (115
// before hairpins were cut at their tips, 114 before strokes split at a fold or T-junction were
// joined again, 109 before strokes split at a tangle were joined again by memory, 102 before
// short occluded gaps were bridged) and a worst frame of 77.4%. The two frames that fall short
// are where a line comes into view (frames 53 and 113: the hole's inner silhouette, 533 px,
// hidden the frame before, which this output does not carry).
TEST(Strokes, CoherentOverATorusTurn) {
    const TurnFigures r = measure_torus_turn(false);
    EXPECT_GE(r.overall, 0.99);
    EXPECT_GE(r.at_95, 117u) << "only frames where new lines come into view fall short";
    EXPECT_GE(r.worst, 0.77);
    EXPECT_LE(r.median_move, 2.0);
}

// With hidden lines kept, a line coming into view keeps the id it had while hidden: measured
// 119 of 119 frames at 95%, worst 95.5%.
TEST(Strokes, CoherentOverATorusTurnWithHiddenLines) {
    const TurnFigures r = measure_torus_turn(true);
    EXPECT_GE(r.overall, 0.995);
    EXPECT_EQ(r.at_95, r.frames) << "every frame";
    EXPECT_GE(r.worst, 0.95);
    EXPECT_LE(r.median_move, 2.0);
}

// Hidden lines add strokes and change nothing about the visible ones: the same geometry, the
// same occluded gaps drawn across, frame after frame.
TEST(Strokes, HiddenLinesLeaveTheVisibleStrokesAsTheyAre) {
    TorusTurn plain, with_hidden({}, true);
    core::StrokeCoherence a, b;
    for (int f = plain.first_frame(); f < plain.first_frame() + 16; ++f) {
        const core::FrameStrokes x = plain.next(a, f);
        const core::FrameStrokes y = with_hidden.next(b, f);
        auto visible = [](const core::FrameStrokes& fs) {
            std::vector<std::pair<std::vector<glm::dvec2>, std::vector<uint8_t>>> out;
            for (const core::Stroke& s : fs.strokes) {
                if (!s.geometry.visible) continue;
                std::vector<glm::dvec2> pts = s.geometry.points_px;
                std::vector<uint8_t> bridged = s.geometry.bridged;
                // Directions follow each run's own history; compare each stroke one way round.
                if (pts.size() > 1 && std::tie(pts.back().x, pts.back().y) < std::tie(pts.front().x, pts.front().y)) {
                    std::reverse(pts.begin(), pts.end());
                    std::reverse(bridged.begin(), bridged.end());
                }
                out.emplace_back(std::move(pts), std::move(bridged));
            }
            std::sort(out.begin(), out.end(), [](const auto& p, const auto& q) {
                return std::tie(p.first.front().x, p.first.front().y, p.first.back().x) <
                       std::tie(q.first.front().x, q.first.front().y, q.first.back().x);
            });
            return out;
        };
        EXPECT_EQ(visible(x), visible(y)) << "frame " << f;
        EXPECT_EQ(x.stats.visible_length_px, y.stats.visible_length_px) << "frame " << f;
        const auto hidden_count = std::count_if(y.strokes.begin(), y.strokes.end(),
                                                [](const core::Stroke& s) { return !s.geometry.visible; });
        EXPECT_GT(hidden_count, 0) << "frame " << f;
    }
}

}  // namespace
}  // namespace inkline
