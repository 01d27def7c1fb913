// SPDX-License-Identifier: MIT
// Ray-cast occlusion against the exact reference: analytic shapes, the torus sample, random
// points and a deforming mesh refitted in place.
#include "core/visibility/raycast_visibility.h"

#include "core/error.h"
#include "core/lines/features.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/scene/scene.h"
#include "core/visibility/exact_visibility.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace inkline {
namespace {

#define SKIP_WITHOUT_EMBREE() \
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree"

// Raycast and exact must agree on at least this fraction of the visible length (issue 9).
constexpr double kMinAgreement = 0.999;

// A torus floating over an open grid: its rim hides parts of the grid's boundary.
core::Mesh torus_over_grid() {
    return test::combine(test::grid(6, 1.0), test::torus(1.0, 0.35, 48, 24), {0.0f, 0.0f, 1.6f});
}

struct Agreement {
    double visible_px = 0.0;  // visible length according to the reference
    double differ_px = 0.0;   // length where the two classifications differ
    double fraction() const { return visible_px > 0.0 ? 1.0 - differ_px / visible_px : 1.0; }
};

// Classifies the midpoints of `step_px` pieces of every chain edge with both tests.
Agreement compare_dense(const std::vector<core::Chain>& chains, const core::Mesh& mesh,
                        const core::Projection& projection, const core::Occlusion& reference,
                        const core::Occlusion& candidate, double step_px = 0.5) {
    std::vector<core::OcclusionQuery> queries;
    std::vector<double> lengths;
    for (const core::Chain& chain : chains) {
        for (size_t s = 0; s < chain.edges.size(); ++s) {
            const glm::dvec3 a(mesh.positions[chain.vertices[s]]), b(mesh.positions[chain.vertices[s + 1]]);
            const glm::dvec4 ca = projection.clip(a), cb = projection.clip(b);
            if (!projection.in_front(ca) || !projection.in_front(cb)) continue;
            const double len = glm::length(projection.pixel_from_clip(cb) - projection.pixel_from_clip(ca));
            const int n = std::max(1, int(std::ceil(len / step_px)));
            for (int k = 0; k < n; ++k) {
                const glm::dvec3 mid = a + (b - a) * ((k + 0.5) / n);
                if (!projection.inside_image(projection.pixel(mid))) continue;
                queries.push_back({mid, chain.edges[s]});
                lengths.push_back(len / n);
            }
        }
    }
    std::vector<uint8_t> expected(queries.size()), actual(queries.size());
    reference.occluded(projection.eye_object(), queries, expected);
    candidate.occluded(projection.eye_object(), queries, actual);
    Agreement out;
    for (size_t i = 0; i < queries.size(); ++i) {
        if (!expected[i]) out.visible_px += lengths[i];
        if (expected[i] != actual[i]) out.differ_px += lengths[i];
    }
    return out;
}

double visible_length(const std::vector<core::Polyline>& lines) {
    double len = 0.0;
    for (const core::Polyline& line : lines) {
        if (line.visible) len += line.length_px();
    }
    return len;
}

// Both per-sample classification and split_by_visibility's visible length agree.
void expect_agreement(const core::Mesh& mesh, const core::EdgeTable& table, const core::Projection& projection,
                      const core::LineOptions& lines, const core::Occlusion& exact,
                      const core::Occlusion& raycast) {
    const std::vector<core::Chain> chains =
        core::chain_feature_edges(core::extract_feature_edges(mesh, table, projection.eye_object(), lines), table);
    const Agreement dense = compare_dense(chains, mesh, projection, exact, raycast);
    EXPECT_GT(dense.visible_px, 100.0);
    EXPECT_GE(dense.fraction(), kMinAgreement) << dense.differ_px << " of " << dense.visible_px << " px differ";

    const core::VisibilityOptions options{.keep_hidden = true};
    const double exact_px = visible_length(core::split_by_visibility(chains, mesh, projection, exact, options));
    const double raycast_px = visible_length(core::split_by_visibility(chains, mesh, projection, raycast, options));
    EXPECT_NEAR(raycast_px, exact_px, (1.0 - kMinAgreement) * exact_px);
}

struct ShapeCase {
    const char* name;
    core::Mesh mesh;
    test::View view;
};

TEST(RaycastVisibility, AgreesWithExactOnAnalyticShapes) {
    SKIP_WITHOUT_EMBREE();
    const ShapeCase cases[] = {
        {"sphere", test::uv_sphere(64, 32, 1.0), {.eye = {0.0, 0.0, 4.0}}},
        {"cube", test::cube(1.0), {.eye = {3.0, 2.5, 4.0}, .fov_y_deg = 40.0}},
        {"torus", test::torus(1.0, 0.35, 48, 24), {.eye = {0.0, 2.2, 3.2}, .fov_y_deg = 40.0}},
        {"hemisphere", test::hemisphere(48, 24, 1.0), {.eye = {1.0, 2.5, 3.0}}},
        {"torus over grid", torus_over_grid(), {.eye = {0.4, 1.2, 6.0}, .fov_y_deg = 40.0}},
    };
    core::LineOptions lines;
    lines.hidden = true;
    for (const ShapeCase& c : cases) {
        SCOPED_TRACE(c.name);
        const core::EdgeTable table = core::build_edge_table(c.mesh);
        const core::Projection projection(test::camera_for(c.view, c.mesh), {c.view.size, c.view.size},
                                          glm::dmat4(1.0));
        const core::ExactOcclusion exact(c.mesh, table);
        const core::RaycastOcclusion raycast(c.mesh, table);
        expect_agreement(c.mesh, table, projection, lines, exact, raycast);
    }
}

TEST(RaycastVisibility, AgreesWithExactOnTheTorusSampleFrames) {
    SKIP_WITHOUT_EMBREE();
    const core::Scene scene = core::load_scene(INKLINE_SAMPLES "/torus/scene.json");
    core::MeshFrames meshes(scene.mesh, scene.first_frame);
    const core::Mesh& mesh = meshes.at(scene.first_frame);
    const core::EdgeTable& table = meshes.edges();
    // Rigid motion: one tree of each kind for every frame, the eye moves into object space.
    const core::ExactOcclusion exact(mesh, table);
    const core::RaycastOcclusion raycast(mesh, table);
    for (int frame = scene.first_frame; frame <= scene.last_frame; frame += 8) {
        SCOPED_TRACE(frame);
        const glm::dmat4 world_from_object = core::world_from_object_at(scene, frame);
        const core::Camera camera =
            core::camera_at(scene, frame, core::transformed(core::bounds_of(mesh.positions), world_from_object));
        const core::Projection projection(camera, scene.image, world_from_object);
        expect_agreement(mesh, table, projection, scene.lines, exact, raycast);
    }
}

// Random points on random edges, seen from random eyes around the mesh.
struct RandomQueries {
    std::vector<glm::dvec3> eyes;
    std::vector<core::OcclusionQuery> queries;  // the same points for every eye
};

RandomQueries random_queries(const core::Mesh& mesh, const core::EdgeTable& table, int eyes, int points,
                             uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<uint32_t> edge(0, uint32_t(table.edge_count() - 1));
    std::normal_distribution<double> gauss;
    RandomQueries out;
    for (int i = 0; i < eyes; ++i) {
        const glm::dvec3 dir = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        out.eyes.push_back(dir * (3.0 + 3.0 * unit(rng)));
    }
    for (int i = 0; i < points; ++i) {
        const uint32_t e = edge(rng);
        const glm::dvec3 a(mesh.positions[table.edge_vertices[e].x]), b(mesh.positions[table.edge_vertices[e].y]);
        out.queries.push_back({a + (b - a) * unit(rng), e});
    }
    return out;
}

// Count of queries whose answers differ, over every eye.
size_t count_differences(const RandomQueries& r, const core::Occlusion& a, const core::Occlusion& b) {
    size_t differ = 0;
    std::vector<uint8_t> ra(r.queries.size()), rb(r.queries.size());
    for (const glm::dvec3& eye : r.eyes) {
        a.occluded(eye, r.queries, ra);
        b.occluded(eye, r.queries, rb);
        for (size_t i = 0; i < ra.size(); ++i) differ += ra[i] != rb[i];
    }
    return differ;
}

TEST(RaycastVisibility, AgreesWithExactOnRandomPoints) {
    SKIP_WITHOUT_EMBREE();
    const core::Mesh mesh = test::combine(torus_over_grid(), test::uv_sphere(32, 16, 0.6), {0.3f, -0.2f, -1.2f});
    const core::EdgeTable table = core::build_edge_table(mesh);
    const RandomQueries r = random_queries(mesh, table, 8, 2000, 7);
    const core::ExactOcclusion exact(mesh, table);
    const core::RaycastOcclusion raycast(mesh, table);

    size_t occluded = 0;
    std::vector<uint8_t> hidden(r.queries.size());
    for (const glm::dvec3& eye : r.eyes) {
        exact.occluded(eye, r.queries, hidden);
        for (uint8_t h : hidden) occluded += h;
    }
    const size_t total = r.eyes.size() * r.queries.size();
    EXPECT_GT(occluded, total / 5) << "the scene must hide a fair share of the points";
    EXPECT_LT(occluded, total * 4 / 5);
    EXPECT_LE(double(count_differences(r, exact, raycast)), (1.0 - kMinAgreement) * double(total));
}

// A torus whose tube swells and twists: enough to change many answers.
core::Mesh deformed(const core::Mesh& mesh, double amount) {
    core::Mesh out = mesh;
    for (glm::vec3& p : out.positions) {
        const double angle = std::atan2(double(p.z), double(p.x));
        const double swell = 1.0 + amount * std::sin(3.0 * angle);
        p.y = float(p.y * swell);
        p.x += float(0.25 * amount * std::cos(2.0 * angle));
    }
    return out;
}

TEST(RaycastVisibility, RefitAfterDeformationMatchesRebuild) {
    SKIP_WITHOUT_EMBREE();
    const core::Mesh before = test::torus(1.0, 0.35, 48, 24);
    const core::Mesh after = deformed(before, 0.6);
    const core::EdgeTable table = core::build_edge_table(before);
    const RandomQueries r_before = random_queries(before, table, 6, 2000, 11);
    // The same points carried along with the deformation: same edges and edge parameters.
    RandomQueries r_after = r_before;
    for (core::OcclusionQuery& q : r_after.queries) {
        const glm::uvec2 v = table.edge_vertices[q.edge];
        const glm::dvec3 a0(before.positions[v.x]), b0(before.positions[v.y]);
        const double t = glm::length(q.p_object - a0) / glm::length(b0 - a0);
        q.p_object = glm::mix(glm::dvec3(after.positions[v.x]), glm::dvec3(after.positions[v.y]), t);
    }

    core::RaycastOcclusion refitted(before, table);
    const core::RaycastOcclusion rebuilt(after, table);
    EXPECT_GT(count_differences(r_after, refitted, rebuilt), 100u) << "the deformation must matter";
    refitted.update_positions(after);
    EXPECT_EQ(count_differences(r_after, refitted, rebuilt), 0u);

    const core::ExactOcclusion exact(after, table);
    const size_t total = r_after.eyes.size() * r_after.queries.size();
    EXPECT_LE(double(count_differences(r_after, exact, refitted)), (1.0 - kMinAgreement) * double(total));

    // And back: refitting is repeatable.
    refitted.update_positions(before);
    const core::ExactOcclusion exact_before(before, table);
    EXPECT_LE(double(count_differences(r_before, exact_before, refitted)), (1.0 - kMinAgreement) * double(total));

    // The first update rebuilt the BVH in its refittable form; later ones refit it, and
    // answer as a fresh build does.
    refitted.update_positions(after);
    EXPECT_EQ(count_differences(r_after, refitted, rebuilt), 0u);
}

TEST(RaycastVisibility, ResultsDoNotDependOnBatching) {
    SKIP_WITHOUT_EMBREE();
    const core::Mesh mesh = test::torus(1.0, 0.35, 48, 24);
    const core::EdgeTable table = core::build_edge_table(mesh);
    const RandomQueries r = random_queries(mesh, table, 1, 3000, 5);
    const core::RaycastOcclusion raycast(mesh, table);
    std::vector<uint8_t> batch(r.queries.size()), again(r.queries.size()), single(r.queries.size());
    raycast.occluded(r.eyes[0], r.queries, batch);
    raycast.occluded(r.eyes[0], r.queries, again);
    for (size_t i = 0; i < r.queries.size(); ++i) {
        raycast.occluded(r.eyes[0], {&r.queries[i], 1}, {&single[i], 1});
    }
    EXPECT_EQ(batch, again);
    EXPECT_EQ(batch, single);
}

TEST(RaycastVisibility, OwnFacesNeverOccludeTheirEdge) {
    SKIP_WITHOUT_EMBREE();
    // A single triangle seen from either side: all three edges, and their vertices, are visible.
    core::Mesh tri;
    tri.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    tri.triangles = {{0, 1, 2}};
    const core::EdgeTable table = core::build_edge_table(tri);
    const core::RaycastOcclusion raycast(tri, table);
    std::vector<core::OcclusionQuery> queries;
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        const glm::dvec3 a(tri.positions[table.edge_vertices[e].x]), b(tri.positions[table.edge_vertices[e].y]);
        for (double t : {0.0, 0.3, 0.5, 1.0}) queries.push_back({a + (b - a) * t, e});
    }
    for (double z : {4.0, -4.0}) {
        std::vector<uint8_t> hidden(queries.size(), 1);
        raycast.occluded(glm::dvec3{0.3, 0.2, z}, queries, hidden);
        EXPECT_EQ(hidden, std::vector<uint8_t>(queries.size(), 0));
    }
}

TEST(RaycastVisibility, AFaceInFrontOccludes) {
    SKIP_WITHOUT_EMBREE();
    // Two parallel triangles; the front one hides the back one's edges where it covers them.
    core::Mesh mesh;
    mesh.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                      {-2.0f, -2.0f, 1.0f}, {2.0f, -2.0f, 1.0f}, {0.0f, 2.0f, 1.0f}};
    mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    const core::EdgeTable table = core::build_edge_table(mesh);
    const core::RaycastOcclusion raycast(mesh, table);
    std::vector<core::OcclusionQuery> queries;
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        const glm::dvec3 a(mesh.positions[table.edge_vertices[e].x]), b(mesh.positions[table.edge_vertices[e].y]);
        queries.push_back({0.5 * (a + b), e});
    }
    std::vector<uint8_t> hidden(queries.size());
    raycast.occluded(glm::dvec3{0.0, 0.0, 5.0}, queries, hidden);
    for (size_t i = 0; i < queries.size(); ++i) EXPECT_EQ(hidden[i], queries[i].p_object.z < 0.5 ? 1 : 0) << i;
    raycast.occluded(glm::dvec3{0.0, 0.0, -5.0}, queries, hidden);
    for (size_t i = 0; i < queries.size(); ++i) EXPECT_EQ(hidden[i], 0) << i << ": the small triangle covers none of the big one's edges";
}

// Issue 19: a mesh of radius 5e17 seen from its default turntable distance sent rays beyond
// Embree's float range (SIGABRT in ray.valid()). At every scale, and from an eye at the scene
// limit, both tests give the answer of the unit-scale case.
TEST(RaycastVisibility, AnswersDoNotDependOnScaleOrEyeDistance) {
    SKIP_WITHOUT_EMBREE();
    for (const double scale : {1e-30, 1e-10, 1.0, 1e15, 5e17, 1e18}) {
        SCOPED_TRACE(scale);
        core::Mesh mesh;
        for (const glm::dvec3 p : {glm::dvec3(-1, -1, 0), glm::dvec3(1, -1, 0), glm::dvec3(0, 1, 0),
                                   glm::dvec3(-2, -2, 1), glm::dvec3(2, -2, 1), glm::dvec3(0, 2, 1)}) {
            mesh.positions.emplace_back(p * scale);
        }
        mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
        const core::EdgeTable table = core::build_edge_table(mesh);
        const core::RaycastOcclusion raycast(mesh, table);
        const core::ExactOcclusion exact(mesh, table);
        std::vector<core::OcclusionQuery> queries;
        for (uint32_t e = 0; e < table.edge_count(); ++e) {
            const glm::dvec3 a(mesh.positions[table.edge_vertices[e].x]), b(mesh.positions[table.edge_vertices[e].y]);
            queries.push_back({0.5 * (a + b), e});
        }
        for (const glm::dvec3 eye : {glm::dvec3(0.0, 0.0, 5.0 * scale), glm::dvec3(0.0, 0.0, 1e19),
                                     glm::dvec3(1e-3 * scale, 2e-3 * scale, 1e19)}) {
            std::vector<uint8_t> by_ray(queries.size()), by_segment(queries.size());
            raycast.occluded(eye, queries, by_ray);
            exact.occluded(eye, queries, by_segment);
            for (size_t i = 0; i < queries.size(); ++i) {
                const int expected = queries[i].p_object.z < 0.5 * scale ? 1 : 0;
                EXPECT_EQ(by_ray[i], expected) << "raycast, query " << i << ", eye z " << eye.z;
                EXPECT_EQ(by_segment[i], expected) << "exact, query " << i << ", eye z " << eye.z;
            }
        }
    }
}

TEST(RaycastVisibility, DegenerateFacesDoNotShiftFaceNumbers) {
    SKIP_WITHOUT_EMBREE();
    // Two parallel triangles after a zero-area face the BVH leaves out: hits must still map to
    // the right mesh faces, or the front triangle's own face would hide its edges.
    core::Mesh mesh;
    mesh.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                      {-2.0f, -2.0f, 1.0f}, {2.0f, -2.0f, 1.0f}, {0.0f, 2.0f, 1.0f}, {6.0f, -2.0f, 1.0f}};
    mesh.triangles = {{3, 4, 6}, {0, 1, 2}, {3, 4, 5}};  // face 0: collinear corners
    const core::EdgeTable table = core::build_edge_table(mesh);
    ASSERT_EQ(table.face_valid[0], 0);
    const core::RaycastOcclusion raycast(mesh, table);
    std::vector<core::OcclusionQuery> queries;
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        if (table.faces_of(e).empty()) continue;
        const glm::dvec3 a(mesh.positions[table.edge_vertices[e].x]), b(mesh.positions[table.edge_vertices[e].y]);
        queries.push_back({0.5 * (a + b), e});
    }
    std::vector<uint8_t> hidden(queries.size());
    raycast.occluded(glm::dvec3{0.0, 0.0, 5.0}, queries, hidden);
    for (size_t i = 0; i < queries.size(); ++i) EXPECT_EQ(hidden[i], queries[i].p_object.z < 0.5 ? 1 : 0) << i;
}

TEST(RaycastVisibility, MeshWithoutValidFacesOccludesNothing) {
    SKIP_WITHOUT_EMBREE();
    core::Mesh mesh;
    mesh.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}};
    mesh.triangles = {{0, 1, 2}};  // zero area
    const core::EdgeTable table = core::build_edge_table(mesh);
    core::RaycastOcclusion raycast(mesh, table);
    raycast.update_positions(mesh);
    const core::OcclusionQuery q{{0.5, 0.0, 0.0}, 0};
    uint8_t hidden = 1;
    raycast.occluded(glm::dvec3{0.0, 0.0, 4.0}, {&q, 1}, {&hidden, 1});
    EXPECT_EQ(hidden, 0);
}

TEST(RaycastVisibility, ConstructionThrowsInputErrorExactlyWithoutEmbree) {
    const core::Mesh mesh = test::cube(1.0);
    const core::EdgeTable table = core::build_edge_table(mesh);
    if (core::raycast_available()) {
        EXPECT_NO_THROW(core::RaycastOcclusion(mesh, table));
    } else {
        EXPECT_THROW(core::RaycastOcclusion(mesh, table), InputError);
    }
}

}  // namespace
}  // namespace inkline
