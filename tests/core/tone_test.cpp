// SPDX-License-Identifier: MIT
// Stippled tone (core/tone) through core::FramePipeline, measured independently of it: ink
// coverage per band of N.L against the tone asked for (tests/support/tone_raster.h), no dot on
// hidden surface (tests/support/segment_occlusion.h), the same surface samples from frame to
// frame on a turntable, constant dots per square pixel on a dolly, nesting of tones, no dot on a
// stroke's ink, and determinism. The tables go to stdout for the log.
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/camera.h"
#include "core/tone/stipple.h"
#include "core/tone/tone_options.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/ground_plane.h"
#include "tests/support/pipeline.h"
#include "tests/support/segment_occlusion.h"
#include "tests/support/shapes.h"
#include "tests/support/tone_raster.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace inkline {
namespace {

// Issue 24's bounds: coverage within 10% of the target in every band of N.L whose target is at
// least 0.05, at most 0.5% of drawn dots hidden by an exact ray test, at least 95% of a
// turntable frame's dots drawn the frame before, dots per square pixel within 20% over a 1x-3x
// dolly.
constexpr double kCoverageTolerance = 0.10;
constexpr double kMinAssertedTone = 0.05;
constexpr double kMaxHiddenShare = 0.005;
constexpr double kMinKeptShare = 0.95;
constexpr double kDensityTolerance = 0.20;

// Light from the side (+x) of a camera on +z: N.L spans -1 to 1 over the visible half.
const core::Light kSideLight{.direction = {-1.0, 0.0, 0.0}};

core::ToneOptions stipple(double max) {
    return {.mode = core::ToneMode::kStipple, .curve = {.max = max}};
}

void lines_off(core::Scene& scene) {
    scene.lines.silhouette = scene.lines.boundary = scene.lines.crease = scene.lines.intersection = false;
}

// A torus with a sphere in front of it (as in frame_pipeline_test): the sphere hides part of
// the torus, and the torus's far side hides behind its near side.
core::Mesh torus_behind_sphere() {
    return test::combine(test::torus(1.0, 0.35, 48, 24), test::uv_sphere(32, 16, 0.45), {0.2f, 0.3f, 1.2f});
}
const test::View kTorusView{.eye = {0.4, 1.6, 4.2}, .fov_y_deg = 40.0, .size = 512};

// The torus and sphere seen from kTorusView at `size` px, stippled to tone 0.4.
core::Scene stippled_torus_scene(const core::Mesh& mesh, int size) {
    test::View view = kTorusView;
    view.size = size;
    core::Scene scene = test::scene_for(view, mesh);
    scene.tone = stipple(0.4);
    return scene;
}

core::VisibilityMode raycast_or_exact() {
    return core::raycast_available() ? core::VisibilityMode::kRaycast : core::VisibilityMode::kExact;
}

// Every frame of `scene` through one pipeline (FrameResult::mesh is not valid afterwards).
std::vector<core::FrameResult> run_frames(const core::Scene& scene, const core::Mesh& mesh, core::VisibilityMode mode) {
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(mode));
    std::vector<core::FrameResult> out;
    for (int frame = scene.first_frame; frame <= scene.last_frame; ++frame) out.push_back(pipeline.run(frame));
    return out;
}

core::Projection projection_of(const core::Scene& scene, const core::FrameResult& result) {
    return core::Projection(result.lines.camera, scene.image, result.world_from_object);
}

// One frame of the torus and sphere seen from kTorusView, tone max 0.7, lines on, drawn once for
// the tests that check its dots: building the surface samples is most of a first frame's cost.
struct TorusFrame {
    core::Mesh mesh;
    core::Scene scene;
    core::FrameResult result;  // its `mesh` is not valid
};
const TorusFrame& torus_frame() {
    static const TorusFrame frame = [] {
        TorusFrame f;
        f.mesh = torus_behind_sphere();
        f.scene = test::scene_for(kTorusView, f.mesh);
        f.scene.tone = stipple(0.7);
        f.result = std::move(run_frames(f.scene, f.mesh, raycast_or_exact()).front());
        return f;
    }();
    return frame;
}


double distance_to_segment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, double* r_t) {
    const glm::dvec2 d = b - a;
    const double len2 = glm::dot(d, d);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
    *r_t = t;
    return glm::length(a + t * d - p);
}

// Nonzero winding of the rings around p.
int winding(const std::vector<core::Ring>& rings, const glm::dvec2& p) {
    int w = 0;
    for (const core::Ring& ring : rings) {
        for (size_t i = 0; i < ring.size(); ++i) {
            const glm::dvec2 a = ring[i], b = ring[(i + 1) % ring.size()];
            const double side = (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y);
            if (a.y <= p.y && b.y > p.y && side > 0.0) ++w;
            if (a.y > p.y && b.y <= p.y && side < 0.0) --w;
        }
    }
    return w;
}

// a. Ink coverage per band of N.L on a lit sphere, with the dots rasterised here (8 x 8 samples
// a pixel, overlaps counted once) and N.L from the analytic sphere through each pixel's centre.
TEST(Tone, CoverageFollowsTheToneOnALitSphere) {
    const core::Mesh sphere = test::icosphere(5);  // unit radius, 20480 faces
    for (const double max : {0.4, 0.7}) {
        SCOPED_TRACE("max " + std::to_string(max));
        core::Scene scene = test::scene_for({.eye = {0.0, 0.0, 4.0}, .size = 768}, sphere);
        scene.light = kSideLight;
        scene.tone = stipple(max);
        lines_off(scene);
        const std::vector<core::FrameResult> frames = run_frames(scene, sphere, raycast_or_exact());
        const core::FrameResult& result = frames.front();
        const std::vector<double> coverage = test::dot_coverage(result.tone.dots, scene.image);
        const test::SurfacePixels surface =
            test::sphere_pixels(glm::dvec3(0.0), 1.0, projection_of(scene, result), scene.light);
        const std::vector<test::ToneBand> bands = test::tone_bands(surface, coverage, result.tone.dots, scene.tone);
        // The measurement's own check: the tone each dot was drawn for against the tone of the
        // analytic sphere's N.L at the pixel it lies in.
        double tone_gap = 0.0;
        size_t tone_dots = 0;
        for (const core::Dot& dot : result.tone.dots) {
            const int x = int(dot.point_px.x), y = int(dot.point_px.y);
            if (!surface.interior(x, y)) continue;
            tone_gap += std::abs(dot.tone - core::tone_of(surface.n_dot_l[size_t(y) * size_t(scene.image.width) + size_t(x)], scene.tone));
            ++tone_dots;
        }
        tone_gap /= double(std::max<size_t>(tone_dots, 1));
        std::printf("tone coverage, sphere 768 px, side light, max %.1f, %zu dots (their tone differs from the analytic "
                    "sphere's at their pixel by %.4f on average):\n%s",
                    max, result.tone.dots.size(), tone_gap, test::band_table(bands).c_str());
        EXPECT_LT(tone_gap, 0.005) << "the analytic N.L must be the one the dots were drawn for";
        for (const test::ToneBand& band : bands) {
            if (band.target < kMinAssertedTone) continue;
            EXPECT_LE(std::abs(band.coverage - band.target), kCoverageTolerance * band.target)
                << "N.L in [" << band.lo << ", " << band.hi << "): target " << band.target << ", coverage "
                << band.coverage << " over " << band.pixels << " pixels";
        }
    }
}

// b. No dot on hidden surface: every drawn dot's centre, tested by a segment from the eye
// against every other face in double precision.
// A ground plane of two triangles running from far ahead to behind the camera, as a shot's
// ground does: stippled where it is seen, evenly in perspective, and its samples built for the
// part in view (the corner under the camera would ask for far more).
TEST(Tone, AGroundPlaneRunningBehindTheCameraIsStippledWhereItIsSeen) {
    const core::Mesh plane = test::ground_plane(6.0f, -14.0f, 8.0f);
    core::Scene scene = test::ground_scene(plane, {400, 300});
    scene.tone = {.mode = core::ToneMode::kStipple, .curve = {.min = 0.3, .max = 0.3}, .dot_radius_px = 2.0};
    const core::FrameResult r = run_frames(scene, plane, raycast_or_exact()).front();
    std::printf("ground: %zu dots from %zu samples\n", r.tone.dots.size(), r.tone.stipple_stats.samples);
    ASSERT_GT(r.tone.dots.size(), 2000u) << "the ground runs behind the camera: it was left unshaded";
    // Rows where the plane fills the image from side to side, in four bands from far to near.
    const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
    const std::vector<double> bands =
        test::ground_band_ink(plane, projection, test::dot_coverage(r.tone.dots, scene.image), 4);
    ASSERT_EQ(bands.size(), 4u);
    for (size_t band = 0; band < bands.size(); ++band) {
        std::printf("band %zu of rows from far to near: ink %.4f against the tone 0.3\n", band, bands[band]);
        EXPECT_NEAR(bands[band], 0.3, kCoverageTolerance * 0.3) << "band " << band;
    }
    // The samples follow the part in view: the nearest ground in the image is about 2.6 units
    // away, the corner under the camera 1.2.
    EXPECT_LT(r.tone.stipple_stats.samples, 500'000u);
}

TEST(Tone, NoDotOnOccludedSurface) {
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree";
    const auto& [mesh, scene, result] = torus_frame();
    const core::FrameTone& tone = result.tone;
    const test::SegmentOcclusion exact(mesh);
    const core::Viewpoint eye = projection_of(scene, result).eye_object();
    const double share = exact.hidden_share(eye, tone.dots);
    std::printf("tone occlusion: %zu dots drawn, %zu culled as hidden by ray casting; %.4f%% hidden by the exact "
                "test\n",
                tone.dots.size(), tone.stipple_stats.occluded, 100.0 * share);
    ASSERT_GT(tone.stipple_stats.occluded, 1000u) << "the scene must hide surface for the test to mean anything";
    EXPECT_LE(share, kMaxHiddenShare);

    // The check itself, on the same view at 320 px: one Stippler (keeping its samples) stipples
    // the frame with ray casting and again with nothing culled, where the exact test must find
    // about as many hidden dots as ray casting culled.
    struct NothingHidden final : core::Occlusion {
        void occluded(const core::Viewpoint&, std::span<const core::OcclusionQuery>, std::span<uint8_t> r) const override {
            std::fill(r.begin(), r.end(), uint8_t(0));
        }
    };
    const core::Projection small(result.lines.camera, {320, 320}, result.world_from_object);
    const core::EdgeTable table = core::build_edge_table(mesh);
    const std::vector<glm::dvec3> normals = core::vertex_normals(mesh);
    const std::unique_ptr<core::OcclusionSource> source = core::make_cpu_occlusion(core::VisibilityMode::kRaycast);
    const core::Occlusion& raycast = source->prepare(mesh, table, small, core::MeshChange::kTopology);
    core::Stippler stippler(scene.tone);
    const std::vector<core::Dot> drawn = stippler.stipple(mesh, table, normals, small, scene.light, raycast, {}, true);
    const size_t culled = stippler.stats().occluded;
    const std::vector<core::Dot> all =
        stippler.stipple(mesh, table, normals, small, scene.light, NothingHidden{}, {}, false);
    ASSERT_EQ(all.size(), drawn.size() + culled);
    const double drawn_share = exact.hidden_share(eye, drawn);
    const double all_share = exact.hidden_share(eye, all);
    const double culled_share = double(culled) / double(all.size());
    std::printf("tone occlusion at 320 px: %zu dots drawn, %.4f%% hidden by the exact test; with nothing culled %zu "
                "dots, %.2f%% hidden by the exact test, %.2f%% culled by ray casting\n",
                drawn.size(), 100.0 * drawn_share, all.size(), 100.0 * all_share, 100.0 * culled_share);
    EXPECT_LE(drawn_share, kMaxHiddenShare);
    EXPECT_NEAR(all_share, culled_share, 0.005);
}

// c. Coherence on a turntable at 2 degrees a frame under a fixed light: the objects turn (the
// sphere around the torus, so occlusion changes too), the light stays.
TEST(Tone, TurntableKeepsTheSameSurfaceSamples) {
    const core::Mesh mesh = torus_behind_sphere();
    core::Scene scene = test::scene_for(kTorusView, mesh);
    scene.tone = stipple(0.4);
    constexpr int kFrames = 12;
    scene.last_frame = kFrames;
    scene.object_rotation = core::Rotation{.axis = {0.0, 1.0, 0.0}, .degrees = 2.0 * kFrames};
    scene.camera.near.reset();
    scene.camera.far.reset();
    const std::vector<core::FrameResult> frames = run_frames(scene, mesh, raycast_or_exact());
    double least = 1.0, sum = 0.0;
    std::string per_frame;
    for (size_t f = 1; f < frames.size(); ++f) {
        const double kept = test::kept_share(frames[f - 1].tone.dots, frames[f].tone.dots);
        EXPECT_GE(kept, kMinKeptShare) << "frame " << frames[f].lines.frame;
        least = std::min(least, kept);
        sum += kept;
        per_frame += " " + std::to_string(frames[f].tone.dots.size());
    }
    std::printf("tone turntable, 2 degrees a frame: dots per frame%s; kept from the frame before: min %.4f, mean "
                "%.4f\n",
                per_frame.c_str(), least, sum / double(frames.size() - 1));
}

// d. Dolly from 1x to 3x on-screen size: dots per square pixel of the sphere's image stay
// within 20% of the first frame's. The tone is flat (min = max), so the density asked for is the
// same everywhere and only the screen-space density model is measured.
TEST(Tone, DollyKeepsDotsPerSquarePixel) {
    const core::Mesh sphere = test::icosphere(5);
    constexpr int kSize = 512;
    constexpr double kFovDeg = 35.0;
    core::Scene scene = test::scene_for({.eye = {0.0, 0.0, 4.0}, .fov_y_deg = kFovDeg, .size = kSize}, sphere);
    scene.tone = stipple(0.4);
    scene.tone.curve.min = 0.4;
    lines_off(scene);
    scene.camera.near.reset();
    scene.camera.far.reset();
    // The image radius of a unit sphere at distance d is f tan(asin(1 / d)), f the focal length
    // in pixels: from 75 px to 225 px.
    constexpr int kFrames = 11;
    const double focal_px = 0.5 * kSize / std::tan(glm::radians(0.5 * kFovDeg));
    for (int f = 1; f <= kFrames; ++f) {
        const double radius_px = 75.0 * (1.0 + 2.0 * (f - 1) / (kFrames - 1));
        const double t = radius_px / focal_px;  // tan(asin(1 / d))
        const double d = std::sqrt(1.0 + 1.0 / (t * t));
        scene.camera.per_frame[f] = {.eye = {0.0, 0.0, d}, .fov_y_deg = kFovDeg};
    }
    scene.last_frame = kFrames;
    const std::vector<core::FrameResult> frames = run_frames(scene, sphere, raycast_or_exact());
    double first = 0.0;
    std::printf("tone dolly, flat tone 0.4:\n  frame  size  surface px    dots   dots/px^2   vs frame 1\n");
    for (const core::FrameResult& result : frames) {
        const size_t pixels = test::sphere_pixels(glm::dvec3(0.0), 1.0, projection_of(scene, result), scene.light).count();
        const double density = double(result.tone.dots.size()) / double(pixels);
        if (first == 0.0) first = density;
        const double size = 1.0 + 2.0 * (result.lines.frame - 1) / double(kFrames - 1);
        std::printf("  %5d  %.1fx  %10zu  %6zu   %.5f   %+6.1f%%\n", result.lines.frame, size, pixels,
                    result.tone.dots.size(), density, 100.0 * (density / first - 1.0));
        EXPECT_LE(std::abs(density / first - 1.0), kDensityTolerance) << "frame " << result.lines.frame;
    }
}

// A close view builds samples where it looks, not over the whole surface at the closest density:
// a camera 0.05 from a unit sphere sees a patch of about 1/1000 of it. The dots are those a
// frame drawn alone draws, after frames that built other parts of the surface first.
TEST(Tone, ACloseViewBuildsSamplesWhereItLooksAndDrawsWhatItDrawsAlone) {
    const core::Mesh sphere = test::icosphere(5);
    core::Scene scene = test::scene_for({.eye = {0.0, 0.0, 4.0}, .fov_y_deg = 40.0, .size = 512}, sphere);
    scene.tone = stipple(0.4);
    scene.tone.curve.min = 0.4;
    lines_off(scene);
    scene.camera.near = 0.01;
    scene.camera.far.reset();
    // From afar on +x, then close on +z, then close on +z a little aside.
    scene.camera.per_frame[1] = {.eye = {4.0, 0.0, 0.0}, .fov_y_deg = 40.0};
    scene.camera.per_frame[2] = {.eye = {0.0, 0.0, 1.05}, .fov_y_deg = 40.0};
    scene.camera.per_frame[3] = {.eye = {0.01, 0.0, 1.05}, .target = {0.01, 0.0, 0.0}, .fov_y_deg = 40.0};
    scene.last_frame = 3;
    const std::vector<core::FrameResult> run = run_frames(scene, sphere, raycast_or_exact());
    scene.first_frame = 3;
    const std::vector<core::FrameResult> alone = run_frames(scene, sphere, raycast_or_exact());
    const core::StippleStats& close = run[1].tone.stipple_stats;
    std::printf(
        "close view: %zu dots, %zu samples held after the far view, %zu after the close one; the frame "
        "drawn alone: %zu dots, %zu samples\n",
        run[1].tone.dots.size(), run[0].tone.stipple_stats.samples, close.samples, alone[0].tone.dots.size(),
        alone[0].tone.stipple_stats.samples);
    for (const core::FrameResult& r : run) EXPECT_TRUE(r.warnings.empty());
    ASSERT_GT(run[1].tone.dots.size(), 3000u);
    // The whole sphere at the close view's density would take about 1,000 times its dots.
    EXPECT_LT(close.samples, 60 * run[1].tone.dots.size());
    const std::vector<core::Dot>& a = run[2].tone.dots;
    const std::vector<core::Dot>& b = alone[0].tone.dots;
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].sample, b[i].sample);
        EXPECT_EQ(a[i].point_px, b[i].point_px);
        EXPECT_EQ(a[i].radius_px, b[i].radius_px);
    }
}

// The least over the drawn visible strokes of (distance from p to the centerline) - (half the
// width there), px: negative inside the ink.
double ink_clearance(const std::vector<core::Stroke>& strokes, const glm::dvec2& p) {
    double least = std::numeric_limits<double>::infinity();
    for (const core::Stroke& stroke : strokes) {
        if (!stroke.drawn || !stroke.geometry.visible) continue;
        const std::vector<glm::dvec2>& c = stroke.centerline_px;
        const std::vector<double>& w = stroke.centerline_width;
        const size_t n = c.size();
        const size_t segments = n < 2 ? n : (stroke.geometry.closed ? n : n - 1);
        for (size_t i = 0; i < segments; ++i) {
            const size_t j = n == 1 ? 0 : (i + 1) % n;
            double t = 0.0;
            const double distance = distance_to_segment(p, c[i], c[j], &t);
            least = std::min(least, distance - 0.5 * ((1.0 - t) * w[i] + t * w[j]));
        }
    }
    return least;
}

// e. Nesting: a darker tone draws every sample the lighter one draws, at the same place (lines
// on: the dots next to the strokes' ink too).
TEST(Tone, DarkerToneDrawsASupersetAtTheSamePlaces) {
    const core::Mesh mesh = torus_behind_sphere();
    core::Scene scene = stippled_torus_scene(mesh, 320);
    scene.light = kSideLight;
    const core::FrameResult light = std::move(run_frames(scene, mesh, raycast_or_exact()).front());
    scene.tone = stipple(0.7);
    const core::FrameResult dark = std::move(run_frames(scene, mesh, raycast_or_exact()).front());
    size_t missing = 0, missing_near_ink = 0, moved = 0;
    for (const core::Dot& dot : light.tone.dots) {
        const std::vector<core::Dot>& in = dark.tone.dots;
        const auto it = std::lower_bound(in.begin(), in.end(), dot.sample,
                                         [](const core::Dot& d, uint64_t sample) { return d.sample < sample; });
        if (it == in.end() || it->sample != dot.sample) {
            ++missing;
            // Within a full dot's radius of the ink: a dot that grew there would touch it.
            if (ink_clearance(dark.strokes.strokes, dot.point_px) < scene.tone.dot_radius_px) ++missing_near_ink;
            continue;
        }
        if (it->point_px != dot.point_px || it->point_world != dot.point_world || it->face != dot.face) ++moved;
    }
    std::printf("tone nesting: %zu dots at max 0.4, %zu at max 0.7; %zu of the lighter missing from the darker (%zu of "
                "them within a full dot radius of a stroke's ink), %zu moved\n",
                light.tone.dots.size(), dark.tone.dots.size(), missing, missing_near_ink, moved);
    ASSERT_GT(light.tone.stipple_stats.inked, 0u) << "dots must meet the strokes for the test to mean anything";
    EXPECT_GT(dark.tone.dots.size(), light.tone.dots.size());
    EXPECT_EQ(missing, 0u);
    EXPECT_EQ(moved, 0u);
}

// Segments binned on a pixel grid, each with a half width at its ends, to find those near a point.
class SegmentGrid {
  public:
    struct Segment {
        glm::dvec2 a, b;
        double half_a = 0.0, half_b = 0.0;
        size_t stroke = 0;
    };
    SegmentGrid(core::ImageSize image) : cols_(image.width / kCell + 1), rows_(image.height / kCell + 1) {
        cells_.resize(size_t(cols_) * size_t(rows_));
    }
    void add(const Segment& segment) {
        const double reach = std::max(segment.half_a, segment.half_b) + kReach;
        const auto range = [&](double lo, double hi, int count) {
            return std::pair(std::clamp(int(std::floor(lo / kCell)), 0, count - 1),
                             std::clamp(int(std::floor(hi / kCell)), 0, count - 1));
        };
        const auto [c0, c1] = range(std::min(segment.a.x, segment.b.x) - reach, std::max(segment.a.x, segment.b.x) + reach, cols_);
        const auto [r0, r1] = range(std::min(segment.a.y, segment.b.y) - reach, std::max(segment.a.y, segment.b.y) + reach, rows_);
        for (int r = r0; r <= r1; ++r) {
            for (int c = c0; c <= c1; ++c) cells_[size_t(r) * size_t(cols_) + size_t(c)].push_back(segments_.size());
        }
        segments_.push_back(segment);
    }
    // The segments that may lie within kReach of p beyond their half width.
    std::vector<Segment> near(const glm::dvec2& p) const {
        const int c = int(std::floor(p.x / kCell)), r = int(std::floor(p.y / kCell));
        if (c < 0 || r < 0 || c >= cols_ || r >= rows_) return {};
        std::vector<Segment> out;
        for (size_t k : cells_[size_t(r) * size_t(cols_) + size_t(c)]) out.push_back(segments_[k]);
        return out;
    }
    static constexpr double kReach = 4.0;  // px: more than a dot's radius

  private:
    static constexpr int kCell = 8;
    int cols_, rows_;
    std::vector<Segment> segments_;
    std::vector<std::vector<size_t>> cells_;
};

// f. No dot touches a visible stroke's ink: each dot's disc stays at least half the stroke's
// width there from its drawn centerline, and outside its outline.
TEST(Tone, NoDotTouchesAStroke) {
    const auto& [mesh, scene, result] = torus_frame();
    const std::vector<core::Dot>& dots = result.tone.dots;
    const std::vector<core::Stroke>& all = result.strokes.strokes;
    SegmentGrid centerlines(scene.image), outlines(scene.image);
    size_t strokes = 0;
    for (size_t k = 0; k < all.size(); ++k) {
        const core::Stroke& stroke = all[k];
        if (!stroke.drawn || !stroke.geometry.visible) continue;
        ++strokes;
        const std::vector<glm::dvec2>& c = stroke.centerline_px;
        const std::vector<double>& w = stroke.centerline_width;
        const size_t n = c.size();
        const size_t segments = n < 2 ? n : (stroke.geometry.closed ? n : n - 1);
        for (size_t i = 0; i < segments; ++i) {
            const size_t j = n == 1 ? 0 : (i + 1) % n;
            centerlines.add({c[i], c[j], 0.5 * w[i], 0.5 * w[j], k});
        }
        for (const core::Ring& ring : stroke.outline) {
            for (size_t i = 0; i < ring.size(); ++i) outlines.add({ring[i], ring[(i + 1) % ring.size()], 0.0, 0.0, k});
        }
    }
    ASSERT_LT(scene.tone.dot_radius_px, SegmentGrid::kReach);
    size_t centre_in_ink = 0, disc_on_ink = 0, in_outline = 0;
    double clearance = std::numeric_limits<double>::infinity();  // least distance from a disc's edge to the ink
    double deepest = -std::numeric_limits<double>::infinity();   // most a disc overlaps an outline, px
    for (const core::Dot& dot : dots) {
        bool centre = false, disc = false, outline = false;
        for (const SegmentGrid::Segment& seg : centerlines.near(dot.point_px)) {
            double t = 0.0;
            const double distance = distance_to_segment(dot.point_px, seg.a, seg.b, &t);
            const double half = (1.0 - t) * seg.half_a + t * seg.half_b;
            centre |= distance < half;
            disc |= distance < half + dot.radius_px;
            clearance = std::min(clearance, distance - half - dot.radius_px);
        }
        // The outline: the disc overlaps the filled rings by `depth` px (negative: apart). A
        // dot inside a stroke's rings is within its half width (at most kReach) of their edge.
        std::vector<size_t> near_strokes;
        double edge = std::numeric_limits<double>::infinity();
        for (const SegmentGrid::Segment& seg : outlines.near(dot.point_px)) {
            double t = 0.0;
            edge = std::min(edge, distance_to_segment(dot.point_px, seg.a, seg.b, &t));
            near_strokes.push_back(seg.stroke);
        }
        std::sort(near_strokes.begin(), near_strokes.end());
        near_strokes.erase(std::unique(near_strokes.begin(), near_strokes.end()), near_strokes.end());
        bool inside = false;
        for (size_t k : near_strokes) inside |= winding(all[k].outline, dot.point_px) != 0;
        if (!near_strokes.empty()) {
            const double depth = inside ? dot.radius_px + edge : dot.radius_px - edge;
            outline = depth > 0.0;
            deepest = std::max(deepest, depth);
        }
        centre_in_ink += centre;
        disc_on_ink += disc;
        in_outline += outline;
    }
    std::printf("tone and strokes: %zu dots, %zu drawn visible strokes, %zu dots removed under ink; centre within "
                "half a width: %zu, disc within: %zu, disc on an outline: %zu; least clearance from the centerline's "
                "ink %.4f px, deepest overlap of an outline %.4f px\n",
                dots.size(), strokes, result.tone.stipple_stats.inked, centre_in_ink, disc_on_ink, in_outline, clearance,
                deepest);
    ASSERT_GT(strokes, 0u);
    ASSERT_GT(result.tone.stipple_stats.inked, 0u) << "some dots must have fallen under the ink for the test to mean anything";
    EXPECT_EQ(centre_in_ink, 0u);
    EXPECT_EQ(disc_on_ink, 0u);
    EXPECT_EQ(in_outline, 0u);
}

// A close view asks for more surface samples than tone.max_samples keeps: the dots are drawn from
// those kept, and a warning says so once a run. With room enough, no warning.
TEST(Tone, ASampleBoundThatHoldsTheDotsBackIsSaidOnce) {
    const core::Mesh mesh = torus_behind_sphere();
    core::Scene scene = stippled_torus_scene(mesh, 256);
    scene.last_frame = 2;
    scene.tone.max_samples = 1000;
    const std::vector<core::FrameResult> held = run_frames(scene, mesh, raycast_or_exact());
    std::vector<std::string> warnings;
    for (const core::FrameResult& r : held) {
        EXPECT_FALSE(r.tone.dots.empty());
        EXPECT_LT(r.tone.stipple_stats.samples, r.tone.stipple_stats.asked);
        warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
    }
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("frame 1: stippling asks for "), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find(" (tone.max_samples): dots where the surface is seen closest are sparser"), std::string::npos)
        << warnings[0];
    scene.tone.max_samples = 8'000'000;
    for (const core::FrameResult& r : run_frames(scene, mesh, raycast_or_exact())) {
        EXPECT_TRUE(r.warnings.empty());
        EXPECT_GE(r.tone.stipple_stats.samples, r.tone.stipple_stats.asked);
    }
}

// g. Determinism: two runs give the same dots, bit for bit.
TEST(Tone, TwoRunsGiveTheSameDots) {
    const core::Mesh mesh = torus_behind_sphere();
    core::Scene scene = stippled_torus_scene(mesh, 384);
    scene.last_frame = 2;
    scene.object_rotation = core::Rotation{.axis = {0.0, 1.0, 0.0}, .degrees = 4.0};
    scene.camera.near.reset();
    scene.camera.far.reset();
    const std::vector<core::FrameResult> a = run_frames(scene, mesh, raycast_or_exact());
    const std::vector<core::FrameResult> b = run_frames(scene, mesh, raycast_or_exact());
    for (size_t f = 0; f < a.size(); ++f) {
        const std::vector<core::Dot>&da = a[f].tone.dots, &db = b[f].tone.dots;
        ASSERT_EQ(da.size(), db.size()) << "frame " << a[f].lines.frame;
        ASSERT_FALSE(da.empty());
        for (size_t i = 0; i < da.size(); ++i) {
            ASSERT_EQ(da[i].sample, db[i].sample) << "frame " << a[f].lines.frame << ", dot " << i;
            EXPECT_EQ(da[i].face, db[i].face);
            EXPECT_EQ(da[i].barycentric, db[i].barycentric);
            EXPECT_EQ(da[i].point_px, db[i].point_px);
            EXPECT_EQ(da[i].point_world, db[i].point_world);
            EXPECT_EQ(da[i].radius_px, db[i].radius_px);
            EXPECT_EQ(da[i].tone, db[i].tone);
        }
    }
}

}  // namespace
}  // namespace inkline
