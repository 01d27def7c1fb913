// SPDX-License-Identifier: MIT
// Orthographic cameras through the whole pipeline: projection, the facing test and both
// trackers (against brute force), every CPU visibility test, strokes and tone, checked against
// analytic contours that only a parallel projection gives.
#include "core/lines/features.h"
#include "core/lines/silhouette_tracker.h"
#include "core/lines/smooth_contours.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/camera.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/agreement.h"
#include "tests/support/pipeline.h"
#include "tests/support/segment_occlusion.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace inkline {
namespace {

constexpr double kPi = std::numbers::pi;

// 3 world units high on 1024 px: a unit sphere is a circle of 341.3 px radius at any distance.
constexpr double kHeight = 3.0;
constexpr int kSize = 1024;
constexpr double kPxPerUnit = kSize / kHeight;

test::View ortho_view(const glm::dvec3& eye) { return {.eye = eye, .size = kSize, .ortho_height = kHeight}; }

core::FrameResult render(const core::Mesh& mesh, const test::View& view, core::VisibilityMode mode,
                         core::ContourMode contour = core::ContourMode::kMesh) {
    return test::render_frame(mesh, view, mode, contour);
}

using test::visible_length;

std::vector<core::VisibilityMode> cpu_modes() {
    std::vector<core::VisibilityMode> modes{core::VisibilityMode::kExact};
    if (core::raycast_available()) modes.push_back(core::VisibilityMode::kRaycast);
    return modes;
}

glm::dvec3 orbit(double degrees, double distance, double lift) {
    const double a = degrees * kPi / 180.0;
    return {distance * std::sin(a), lift, distance * std::cos(a)};
}

TEST(Orthographic, ProjectionIsParallelAndMeasuresDepthAlongTheAxis) {
    const core::Camera camera{.eye = {0.0, 0.0, 10.0}, .near = 2.0, .far = 30.0, .ortho_height = 4.0};
    const core::Projection projection(camera, {800, 400}, glm::dmat4(1.0));
    ASSERT_TRUE(projection.orthographic());
    EXPECT_EQ(projection.eye_object().w, 0.0);
    EXPECT_EQ(projection.eye_object().xyz, glm::dvec3(0.0, 0.0, 1.0));
    for (const double z : {7.0, 0.0, -15.0}) {
        // 4 units high on 400 px, and as wide per unit on 800 px.
        const glm::dvec2 px = projection.pixel({1.0, 1.0, z});
        EXPECT_NEAR(px.x, 500.0, 1e-9);
        EXPECT_NEAR(px.y, 100.0, 1e-9);
        EXPECT_NEAR(projection.depth(projection.clip({0.0, 0.0, z})), 10.0 - z, 1e-9);
    }
    EXPECT_FALSE(projection.in_front(projection.clip({0.0, 0.0, 8.5})));  // nearer than near
    // An object turned and moved: the viewpoint turns with it and stays a unit direction.
    const glm::dmat4 world_from_object = glm::dmat4(0.0, 0.0, -2.0, 0.0,  // x -> -2z
                                                    0.0, 2.0, 0.0, 0.0,   // y -> 2y
                                                    2.0, 0.0, 0.0, 0.0,   // z -> 2x
                                                    5.0, 1.0, 0.0, 1.0);
    const core::Projection moved(camera, {800, 400}, world_from_object);
    EXPECT_EQ(moved.eye_object().w, 0.0);
    EXPECT_NEAR(glm::length(moved.eye_object().xyz - glm::dvec3(-1.0, 0.0, 0.0)), 0.0, 1e-12);
}

// Seen in parallel projection a sphere's contour is its great circle across the view, of its
// own radius wherever the camera stands (in perspective it is smaller, and shrinks nearer).
TEST(Orthographic, SphereContourIsTheGreatCircleInEveryModeAndEveryVisibilityTest) {
    const core::Mesh sphere = test::icosphere(6);
    for (const glm::dvec3& eye : {glm::dvec3(0.0, 0.0, 3.0), glm::dvec3(2.0, 1.5, 40.0)}) {
        for (const core::ContourMode contour : {core::ContourMode::kMesh, core::ContourMode::kSmooth}) {
            for (const core::VisibilityMode mode : cpu_modes()) {
                SCOPED_TRACE(testing::Message() << "eye " << eye.z << ", contour " << int(contour) << ", visibility "
                                                << int(mode));
                const core::FrameResult r = render(sphere, ortho_view(eye), mode, contour);
                const core::Projection projection(r.lines.camera, {kSize, kSize}, glm::dmat4(1.0));
                const glm::dvec2 center = projection.pixel(glm::dvec3(0.0));
                double worst = 0.0;
                for (const core::Polyline& line : r.lines.polylines) {
                    for (const glm::dvec2& p : line.points_px) {
                        worst = std::max(worst, std::abs(glm::length(p - center) - kPxPerUnit));
                    }
                }
                EXPECT_LE(worst, 0.25);
                EXPECT_NEAR(visible_length(r.lines), 2.0 * kPi * kPxPerUnit, 0.002 * 2.0 * kPi * kPxPerUnit);
                // Exact visibility draws the whole circle as one stroke; ray casting in float may
                // hide a pixel or two where a mesh silhouette edge grazes its neighbours.
                if (mode == core::VisibilityMode::kExact) {
                    ASSERT_EQ(r.strokes.strokes.size(), 1u);
                    EXPECT_TRUE(r.strokes.strokes[0].geometry.closed);
                }
            }
        }
    }
}

// Two unit spheres, the second 3 units behind the first along the view and 0.5 to the side:
// in parallel projection the second's contour is a circle as large as the first's, and the
// part of it outside the first's disc, an arc of 2 acos(-1/4), is what shows.
TEST(Orthographic, ASphereBehindAnotherShowsTheArcOutsideItsDisc) {
    const core::Mesh front = test::icosphere(6);
    const core::Mesh both = test::combine(front, front, {0.5f, 0.0f, -3.0f});
    const double arc = 2.0 * std::acos(-0.25) * kPxPerUnit;
    for (const core::ContourMode contour : {core::ContourMode::kMesh, core::ContourMode::kSmooth}) {
        for (const core::VisibilityMode mode : cpu_modes()) {
            SCOPED_TRACE(testing::Message() << "contour " << int(contour) << ", visibility " << int(mode));
            const core::FrameResult r = render(both, ortho_view({0.0, 0.0, 20.0}), mode, contour);
            const core::Projection projection(r.lines.camera, {kSize, kSize}, glm::dmat4(1.0));
            const glm::dvec2 front_center = projection.pixel(glm::dvec3(0.0));
            EXPECT_NEAR(visible_length(r.lines), 2.0 * kPi * kPxPerUnit + arc, 0.004 * arc);
            // No visible point lies inside the front sphere's disc.
            for (const core::Polyline& line : r.lines.polylines) {
                if (!line.visible) continue;
                for (const glm::dvec2& p : line.points_px) EXPECT_GE(glm::length(p - front_center), kPxPerUnit - 0.25);
            }
        }
    }
}

TEST(Orthographic, RaycastAgreesWithExactOnATorus) {
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree";
    const core::Mesh torus = test::torus(1.0, 0.35, 96, 48);
    const core::EdgeTable table = core::build_edge_table(torus);
    for (const glm::dvec3& eye : {glm::dvec3(0.0, 2.0, 3.5), glm::dvec3(1.0, 1.0, 3.0), glm::dvec3(0.3, 0.6, 4.0)}) {
        const test::View view = ortho_view(eye);
        const core::Camera camera = test::camera_for(view, torus);
        const core::Projection projection(camera, {kSize, kSize}, glm::dmat4(1.0));
        const std::vector<core::Chain> chains = test::feature_chains(torus, view, {});
        const auto exact_source = core::make_cpu_occlusion(core::VisibilityMode::kExact);
        const auto raycast_source = core::make_cpu_occlusion(core::VisibilityMode::kRaycast);
        const core::Occlusion& exact = exact_source->prepare(torus, table, projection, core::MeshChange::kTopology);
        const core::Occlusion& raycast = raycast_source->prepare(torus, table, projection, core::MeshChange::kTopology);
        const test::VisibilityAgreement a = test::compare_occlusion(chains, torus, projection, exact, raycast);
        EXPECT_GT(a.reference_visible_px, 1000.0);
        EXPECT_GE(a.agreement(), 0.999) << eye.x << " " << eye.y << " " << eye.z;
        // The inner contour is partly hidden behind the tube: visibility did work.
        const core::FrameResult r = render(torus, view, core::VisibilityMode::kExact);
        double hidden = 0.0;
        for (const core::Polyline& line : r.lines.occluded) hidden += line.length_px();
        EXPECT_GT(hidden, 10.0) << eye.x << " " << eye.y << " " << eye.z;
    }
}

// The trackers follow an orthographic turntable (its viewpoint a direction turning) and equal
// brute force on every frame.
TEST(Orthographic, TrackersEqualBruteForceOnATurntable) {
    const core::Mesh mesh = test::bumpy_sphere(test::icosphere(5), {.count = 60, .height_max = 0.12});
    const core::EdgeTable table = core::build_edge_table(mesh);
    core::SilhouetteTracker tracker(table, mesh);
    core::SmoothContourTracer smooth(mesh, table);
    core::SmoothContourTracer smooth_brute(mesh, table, {.mode = core::TrackerMode::kBrute});
    size_t tested = 0, edges = 0;
    for (int i = 0; i < 40; ++i) {
        const core::Viewpoint eye = core::Viewpoint::at_infinity(orbit(3.0 * i, 1.0, 0.3));
        const core::FeatureEdges brute = core::extract_feature_edges(mesh, table, eye, {});
        const core::FeatureEdges tracked = tracker.update(mesh, eye, {});
        ASSERT_EQ(tracked.edges.size(), brute.edges.size()) << "frame " << i;
        for (size_t k = 0; k < brute.edges.size(); ++k) {
            ASSERT_EQ(tracked.edges[k].edge, brute.edges[k].edge) << "frame " << i;
            ASSERT_EQ(tracked.edges[k].kind, brute.edges[k].kind) << "frame " << i;
        }
        if (i > 0) tested += tracked.edges_tested, edges += table.edge_count();
        const std::vector<core::Chain> expected = smooth_brute.trace(mesh, table, eye);
        const std::vector<core::Chain>& got = smooth.trace(mesh, table, eye);
        ASSERT_EQ(got.size(), expected.size()) << "frame " << i;
        for (size_t k = 0; k < got.size(); ++k) ASSERT_EQ(got[k].points, expected[k].points) << "frame " << i;
    }
    EXPECT_LT(tested, edges / 2) << "the cones rule out most edges towards an eye at infinity too";
}

// Dots are drawn on visible surface only.
TEST(Orthographic, StippleDotsLieOnVisibleSurface) {
    const core::Mesh mesh =
        test::combine(test::torus(1.0, 0.35, 48, 24), test::uv_sphere(32, 16, 0.45), {0.2f, 0.3f, 1.2f});
    core::Scene scene = test::scene_for({.eye = {0.4, 1.6, 4.2}, .size = 512, .ortho_height = 3.2}, mesh);
    scene.tone = {.mode = core::ToneMode::kStipple, .curve = {.max = 0.7}};
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes,
                                 core::make_cpu_occlusion(core::raycast_available() ? core::VisibilityMode::kRaycast
                                                                                    : core::VisibilityMode::kExact));
    const core::FrameResult r = pipeline.run(scene.first_frame);
    ASSERT_GT(r.tone.dots.size(), 500u);
    ASSERT_GT(r.tone.stipple_stats.occluded, 100u) << "the sphere must hide some of the torus";
    const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
    const test::SegmentOcclusion exact(mesh);
    EXPECT_LE(exact.hidden_share(projection.eye_object(), r.tone.dots), 0.005);
}

}  // namespace
}  // namespace inkline
