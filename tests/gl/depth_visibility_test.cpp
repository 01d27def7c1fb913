// SPDX-License-Identifier: MIT
// Depth-map visibility against the exact reference, on both back-ends.
#include "gl/depth_visibility.h"

#include "core/error.h"
#include "core/lines/features.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/scene/scene.h"
#include "core/visibility/exact_visibility.h"
#include "tests/gl/context_or_skip.h"
#include "tests/support/agreement.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <set>

namespace inkline {
namespace {

using test::context_or_skip;

// What issue 4 asks of the depth pass against `--visibility exact`.
constexpr double kMinAgreement = 0.995;
constexpr double kMaxDisagreementPx = 2.0;

// A torus with a sphere through its front: silhouettes, self-occlusion, mutual occlusion and
// intersection curves.
core::Mesh torus_and_sphere() {
    return test::combine(test::torus(1.0, 0.35, 64, 32), test::uv_sphere(48, 24, 0.5), {0.55f, 0.25f, 0.6f});
}

// One frame seen through both occlusions.
struct Frame {
    std::vector<core::Chain> chains;
    core::Projection projection;
    std::vector<core::Polyline> exact;
    std::vector<core::Polyline> depth;
};

class Scene {
  public:
    explicit Scene(core::Mesh mesh) : mesh_(std::move(mesh)), table_(core::build_edge_table(mesh_)) {}

    // Renders the frame with the object turned by world_from_object; change says what the
    // depth pass must upload.
    Frame frame(gl::DepthOcclusion& depth, const test::View& view, const glm::dmat4& world_from_object,
                core::MeshChange change = core::MeshChange::kNone, bool hidden = false) {
        return frame(depth, test::camera_for(view, mesh_), view.size, world_from_object, change, hidden);
    }

    Frame frame(gl::DepthOcclusion& depth, const core::Camera& camera, int size, const glm::dmat4& world_from_object,
                core::MeshChange change, bool hidden) {
        core::LineOptions lines;
        lines.hidden = hidden;
        Frame f{{}, core::Projection(camera, {size, size}, world_from_object), {}, {}};
        const core::FeatureEdges features =
            core::extract_feature_edges(mesh_, table_, f.projection.eye_object(), lines);
        f.chains = core::chain_feature_edges(features, table_);
        core::VisibilityOptions options;
        options.keep_hidden = hidden;
        if (!exact_ || change != core::MeshChange::kNone) exact_ = std::make_unique<core::ExactOcclusion>(mesh_, table_);
        f.exact = core::split_by_visibility(f.chains, mesh_, f.projection, *exact_, options);
        depth.prepare(mesh_, table_, f.projection, change);
        f.depth = core::split_by_visibility(f.chains, mesh_, f.projection, depth, options);
        return f;
    }

    test::VisibilityAgreement compare(const Frame& f) const {
        return test::compare_visibility(f.chains, mesh_, f.projection, f.exact, f.depth);
    }

    core::Mesh& mesh() { return mesh_; }
    const core::ExactOcclusion& exact() const { return *exact_; }

  private:
    core::Mesh mesh_;
    core::EdgeTable table_;
    std::unique_ptr<core::ExactOcclusion> exact_;
};

glm::dmat4 turned(double degrees) { return glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::dvec3(0, 1, 0)); }

const test::View kTurntableView{.eye = {0.0, 1.4, 3.6}, .fov_y_deg = 40.0, .size = 1024};

// A turntable of `frames` frames; every frame meets the bounds.
test::VisibilityAgreement check_turntable(gl::Backend backend, int frames) {
    const auto context = context_or_skip(backend);
    gl::DepthOcclusion depth(*context);
    Scene scene(torus_and_sphere());
    test::VisibilityAgreement total;
    for (int i = 0; i < frames; ++i) {
        const double angle = 360.0 * i / frames;
        const Frame f = scene.frame(depth, kTurntableView, turned(angle));
        const test::VisibilityAgreement a = scene.compare(f);
        EXPECT_GE(a.agreement(), kMinAgreement) << "frame at " << angle << " degrees";
        EXPECT_LE(a.longest_disagreement_px, kMaxDisagreementPx) << "frame at " << angle << " degrees";
        total.add(a);
    }
    EXPECT_GT(total.reference_visible_px, 10000.0) << "the scene shows lines";
    std::cout << context->backend_name() << ": agreement " << 100.0 * total.agreement() << "%, longest run "
              << total.longest_disagreement_px << " px, visible " << total.reference_visible_px << " px\n";
    return total;
}

TEST(DepthVisibility, EglTurntableAgreesWithExact) { check_turntable(gl::Backend::kEgl, 8); }

TEST(DepthVisibility, OsmesaTurntableAgreesWithExact) { check_turntable(gl::Backend::kOsmesa, 8); }

// An orthographic camera: the depth map stores 2 - z_clip instead of 1 / w_clip, and the local
// ray test runs towards the eye at infinity.
TEST(DepthVisibility, OrthographicTurntableAgreesWithExact) {
    const auto context = context_or_skip(gl::Backend::kAuto);
    Scene scene(torus_and_sphere());
    test::View view = kTurntableView;
    view.ortho_height = 3.2;
    for (bool ray_test : {true, false}) {
        gl::DepthOcclusion depth(*context, {.local_ray_test = ray_test});
        test::VisibilityAgreement total;
        double hidden_px = 0.0;
        for (double angle : {0.0, 45.0, 90.0, 135.0, 200.0, 290.0}) {
            const Frame f = scene.frame(depth, view, turned(angle), core::MeshChange::kNone, true);
            const test::VisibilityAgreement a = scene.compare(f);
            if (ray_test) {
                EXPECT_GE(a.agreement(), kMinAgreement) << "frame at " << angle << " degrees";
                EXPECT_LE(a.longest_disagreement_px, kMaxDisagreementPx) << "frame at " << angle << " degrees";
            }
            total.add(a);
            for (const core::Polyline& line : f.exact) hidden_px += line.visible ? 0.0 : line.length_px();
        }
        std::cout << "orthographic, ray test " << ray_test << ": agreement " << 100.0 * total.agreement()
                  << "%, longest run " << total.longest_disagreement_px << " px, hidden " << hidden_px
                  << " px, visible " << total.reference_visible_px << " px\n";
        EXPECT_GT(hidden_px, 0.3 * total.reference_visible_px) << "the scene must hide lines for the check to mean anything";
        // The depth map alone orders the surfaces: it decides most of the length (97.3% in
        // perspective from the same eye), which a q that did not follow depth could not.
        EXPECT_GE(total.agreement(), ray_test ? kMinAgreement : 0.95);
    }
}

TEST(DepthVisibility, DenseMeshContoursAgreeWithExact) {
    // 40k faces at 1024 px: faces next to the contour are grazing slivers thinner than a texel,
    // which hide bits of the mesh silhouette from the exact test. The depth map alone misses
    // them; the local ray test must find them.
    const auto context = context_or_skip(gl::Backend::kAuto);
    Scene scene(test::torus(1.0, 0.35, 200, 100));
    for (bool ray_test : {true, false}) {
        gl::DepthOcclusion depth(*context, {.local_ray_test = ray_test});
        test::VisibilityAgreement lines, direct;
        for (double angle : {0.0, 40.0}) {
            const Frame f = scene.frame(depth, kTurntableView, turned(angle));
            lines.add(scene.compare(f));
            direct.add(test::compare_occlusion(f.chains, scene.mesh(), f.projection, scene.exact(), depth));
        }
        std::cout << "ray test " << ray_test << ": lines " << 100.0 * lines.agreement() << "%, longest "
                  << lines.longest_disagreement_px << " px; test " << 100.0 * direct.agreement() << "%, longest "
                  << direct.longest_disagreement_px << " px\n";
        if (ray_test) {
            EXPECT_GE(lines.agreement(), kMinAgreement);
            EXPECT_GE(direct.agreement(), kMinAgreement);
            EXPECT_LE(direct.longest_disagreement_px, kMaxDisagreementPx);
        } else {
            EXPECT_LT(direct.agreement(), 0.99) << "if the depth map alone sufficed, the ray test would be waste";
        }
    }
}

TEST(DepthVisibility, SampleTorusSceneAgreesWithExact) {
    // samples/torus/scene.json as `inkline render` draws it: the object turns, the mesh stays in
    // object space, the motion travels in the projection (MeshChange::kNone after the first).
    const auto context = context_or_skip(gl::Backend::kAuto);
    gl::DepthOcclusion depth(*context);
    const core::Scene scene = core::load_scene(INKLINE_SAMPLES "/torus/scene.json");
    core::MeshFrames meshes(scene.mesh, scene.first_frame);
    const core::Mesh& mesh = meshes.at(scene.first_frame);
    const core::EdgeTable& table = meshes.edges();
    const core::ExactOcclusion exact(mesh, table);
    const core::VisibilityOptions options{.keep_hidden = true};
    for (int frame = scene.first_frame; frame <= scene.last_frame; frame += 6) {
        SCOPED_TRACE(frame);
        const glm::dmat4 world_from_object = core::world_from_object_at(scene, frame);
        core::Bounds world_bounds;
        const core::Bounds b = core::bounds_of(mesh.positions);
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
            world_bounds.add(glm::dvec3(world_from_object * glm::dvec4(corner, 1.0)));
        }
        const core::Projection projection(core::camera_at(scene, frame, world_bounds), scene.image, world_from_object);
        const std::vector<core::Chain> chains = core::chain_feature_edges(
            core::extract_feature_edges(mesh, table, projection.eye_object(), scene.lines), table);
        depth.prepare(mesh, table, projection, frame == scene.first_frame ? core::MeshChange::kTopology : core::MeshChange::kNone);
        const auto reference = core::split_by_visibility(chains, mesh, projection, exact, options);
        const auto lines = core::split_by_visibility(chains, mesh, projection, depth, options);
        const test::VisibilityAgreement a = test::compare_visibility(chains, mesh, projection, reference, lines);
        EXPECT_GE(a.agreement(), kMinAgreement);
        EXPECT_LE(a.longest_disagreement_px, kMaxDisagreementPx);
        EXPECT_GT(a.reference_visible_px, 1000.0);
    }
}

TEST(DepthVisibility, EglAndOsmesaGiveTheSameResult) {
    std::vector<Frame> frames[2];
    const gl::Backend backends[2] = {gl::Backend::kEgl, gl::Backend::kOsmesa};
    for (int b = 0; b < 2; ++b) {
        const auto context = context_or_skip(backends[b]);
        gl::DepthOcclusion depth(*context);
        Scene scene(torus_and_sphere());
        for (double angle : {0.0, 100.0, 230.0}) frames[b].push_back(scene.frame(depth, kTurntableView, turned(angle), core::MeshChange::kNone, true));
    }
    for (size_t i = 0; i < frames[0].size(); ++i) {
        const std::vector<core::Polyline>& egl = frames[0][i].depth;
        const std::vector<core::Polyline>& osmesa = frames[1][i].depth;
        ASSERT_EQ(egl.size(), osmesa.size());
        for (size_t k = 0; k < egl.size(); ++k) {
            EXPECT_EQ(egl[k].visible, osmesa[k].visible);
            EXPECT_EQ(egl[k].edges, osmesa[k].edges);
            ASSERT_EQ(egl[k].points_px.size(), osmesa[k].points_px.size());
            for (size_t p = 0; p < egl[k].points_px.size(); ++p) {
                EXPECT_LT(glm::length(egl[k].points_px[p] - osmesa[k].points_px[p]), 1e-9);
            }
        }
    }
}

TEST(DepthVisibility, SphereSilhouetteOnTheDepthEdgeIsFullyVisible) {
    const auto context = context_or_skip(gl::Backend::kAuto);
    gl::DepthOcclusion depth(*context);
    Scene scene(test::uv_sphere(64, 32, 1.0));
    for (int size : {256, 1024}) {
        const Frame f = scene.frame(depth, {.eye = {0.3, 0.5, 4.0}, .size = size}, glm::dmat4(1.0),
                                    core::MeshChange::kNone, true);
        ASSERT_FALSE(f.depth.empty());
        for (const core::Polyline& line : f.depth) EXPECT_TRUE(line.visible) << "at " << size << " px";
        EXPECT_EQ(scene.compare(f).disagree_px, 0.0);
    }
}

TEST(DepthVisibility, CubeShowsTheSameEdgesAsExact) {
    const auto context = context_or_skip(gl::Backend::kAuto);
    gl::DepthOcclusion depth(*context);
    Scene scene(test::cube(1.0));
    const Frame f = scene.frame(depth, {.eye = {3.0, 2.5, 4.0}, .fov_y_deg = 40.0}, glm::dmat4(1.0),
                                core::MeshChange::kNone, true);
    auto edges_by_visibility = [](const std::vector<core::Polyline>& lines, bool visible) {
        std::set<uint32_t> edges;
        for (const core::Polyline& line : lines) {
            if (line.visible == visible) edges.insert(line.edges.begin(), line.edges.end());
        }
        return edges;
    };
    EXPECT_EQ(edges_by_visibility(f.depth, true).size(), 9u);
    EXPECT_EQ(edges_by_visibility(f.depth, true), edges_by_visibility(f.exact, true));
    EXPECT_EQ(edges_by_visibility(f.depth, false), edges_by_visibility(f.exact, false));
    EXPECT_EQ(scene.compare(f).disagree_px, 0.0);
}

TEST(DepthVisibility, DeformedPositionsAreUploaded) {
    const auto context = context_or_skip(gl::Backend::kAuto);
    gl::DepthOcclusion depth(*context);
    Scene scene(torus_and_sphere());
    const test::View view{.eye = {0.0, 0.3, 4.0}, .fov_y_deg = 40.0};
    const Frame before = scene.frame(depth, view, glm::dmat4(1.0));
    // Move the sphere (the vertices after the torus's) in front of the torus's left side.
    const size_t torus_vertices = test::torus(1.0, 0.35, 64, 32).positions.size();
    for (size_t v = torus_vertices; v < scene.mesh().positions.size(); ++v) {
        scene.mesh().positions[v] += glm::vec3(-1.4f, -0.2f, 0.5f);
    }
    const Frame after = scene.frame(depth, view, glm::dmat4(1.0), core::MeshChange::kPositions);
    const test::VisibilityAgreement a = scene.compare(after);
    EXPECT_GE(a.agreement(), kMinAgreement);
    EXPECT_LE(a.longest_disagreement_px, kMaxDisagreementPx);
    // The old depth map would disagree: the torus's left side is now hidden.
    const test::VisibilityAgreement stale = test::compare_visibility(after.chains, scene.mesh(), after.projection,
                                                                     after.exact, before.depth);
    EXPECT_LT(stale.agreement(), 0.9);
}

TEST(DepthVisibility, OccludersBeforeTheNearPlaneCount) {
    // A small sphere between the eye and the near plane hides part of a torus: the exact
    // definition counts it, so the depth pass must not clip it away.
    const auto context = context_or_skip(gl::Backend::kAuto);
    gl::DepthOcclusion depth(*context);
    const core::Camera camera{.eye = {0.0, 0.0, 4.0}, .fov_y_deg = 50.0, .near = 0.5, .far = 10.0};
    auto visible_px = [](const std::vector<core::Polyline>& lines) {
        double length = 0.0;
        for (const core::Polyline& line : lines) length += line.length_px();
        return length;
    };
    Scene torus(test::torus(1.0, 0.35, 64, 32));
    const double unoccluded = visible_px(torus.frame(depth, camera, 512, glm::dmat4(1.0), core::MeshChange::kTopology, false).exact);

    Scene scene(test::combine(test::torus(1.0, 0.35, 64, 32), test::uv_sphere(24, 12, 0.08), {0.07f, 0.0f, 3.7f}));
    const Frame f = scene.frame(depth, camera, 512, glm::dmat4(1.0), core::MeshChange::kTopology, false);
    ASSERT_LT(f.projection.clip(glm::dvec3(0.07, 0.0, 3.62)).w, camera.near) << "the sphere lies before the near plane";
    EXPECT_LT(visible_px(f.exact), 0.9 * unoccluded) << "the sphere hides part of the torus";
    const test::VisibilityAgreement a = scene.compare(f);
    EXPECT_GE(a.agreement(), kMinAgreement);
    EXPECT_LE(a.longest_disagreement_px, kMaxDisagreementPx);
}

TEST(DepthVisibility, SupersamplingSetsTheDepthMapSize) {
    const auto context = context_or_skip(gl::Backend::kAuto);
    gl::DepthOcclusion depth(*context, {.supersampling = 3});
    Scene scene(test::cube(1.0));
    scene.frame(depth, {.eye = {3.0, 2.5, 4.0}, .size = 300}, glm::dmat4(1.0));
    EXPECT_EQ(depth.last_pass().supersampling, 3);
    EXPECT_EQ(depth.last_pass().width, 900);
    EXPECT_EQ(depth.last_pass().height, 900);
    EXPECT_THROW(gl::DepthOcclusion(*context, {.supersampling = 0}), InputError);

    // 6000 x 6000 at 2x would be 144M texels: over the 2^26 budget, so 1x.
    gl::DepthOcclusion big(*context, {.supersampling = 2});
    core::Mesh tri;
    tri.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    tri.triangles = {{0, 1, 2}};
    const core::EdgeTable table = core::build_edge_table(tri);
    big.prepare(tri, table, core::Projection(test::camera_for({}, tri), {6000, 6000}, glm::dmat4(1.0)),
                core::MeshChange::kTopology);
    EXPECT_EQ(big.last_pass().supersampling, 1);
    EXPECT_EQ(big.last_pass().width, 6000);
}

TEST(DepthVisibility, ADifferentMeshWithoutKTopologyIsABug) {
    const auto context = context_or_skip(gl::Backend::kAuto);
    gl::DepthOcclusion depth(*context);
    const core::Mesh cube = test::cube(1.0), sphere = test::uv_sphere(16, 8, 1.0);
    const core::EdgeTable cube_table = core::build_edge_table(cube), sphere_table = core::build_edge_table(sphere);
    const core::Projection projection(test::camera_for({}, cube), {64, 64}, glm::dmat4(1.0));
    depth.prepare(cube, cube_table, projection, core::MeshChange::kNone);  // the first call uploads anyway
    EXPECT_THROW(depth.prepare(sphere, sphere_table, projection, core::MeshChange::kPositions), InternalError);
    EXPECT_NO_THROW(depth.prepare(sphere, sphere_table, projection, core::MeshChange::kTopology));
}

TEST(DepthVisibility, QueryBeforePrepareIsABug) {
    const auto context = context_or_skip(gl::Backend::kAuto);
    const gl::DepthOcclusion depth(*context);
    const core::OcclusionQuery query{{0.0, 0.0, 0.0}, 0};
    uint8_t hidden = 0;
    EXPECT_THROW(depth.occluded(glm::dvec3{0.0, 0.0, 4.0}, {&query, 1}, {&hidden, 1}), InternalError);
}

}  // namespace
}  // namespace inkline
