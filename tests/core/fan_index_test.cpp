// SPDX-License-Identifier: MIT
// Fans (core/visibility/internal/fan_index.h): which faces form them, and that ray casting and
// exact visibility answer through the fan index exactly as a brute-force test of every face
// with the same triangle test does, on random fans, deformed fans and rays through the apex.
#include "core/visibility/internal/fan_index.h"

#include "core/mesh/topology.h"
#include "core/visibility/exact_visibility.h"
#include "core/visibility/internal/face_tests.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace inkline {
namespace {

namespace internal = core::internal;

#define SKIP_WITHOUT_EMBREE() \
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree"

// An umbrella of `sides` faces around an apex above a wavy, uneven rim: radii in [0.4, 1.2],
// heights in [-0.4, 0.4], angles jittered (seeded). Not planar, not convex.
core::Mesh umbrella(uint32_t sides, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    core::Mesh m;
    m.positions.push_back({0.1f, 0.3f, -0.05f});
    for (uint32_t i = 0; i < sides; ++i) {
        const double a = 2.0 * std::numbers::pi * (i + 0.8 * unit(rng)) / sides;
        const double r = 0.4 + 0.8 * unit(rng);
        m.positions.push_back({float(r * std::cos(a)), float(0.8 * unit(rng) - 0.4), float(r * std::sin(a))});
    }
    for (uint32_t i = 0; i < sides; ++i) m.triangles.push_back({0, 1 + (i + 1) % sides, 1 + i});
    return m;
}

// A smooth bend, twist and swell: moves every rim point and the apex.
core::Mesh deformed(core::Mesh mesh, double amount) {
    for (glm::vec3& p : mesh.positions) {
        const double twist = amount * 0.8 * p.y;
        const double x = p.x * std::cos(twist) - p.z * std::sin(twist);
        const double z = p.x * std::sin(twist) + p.z * std::cos(twist);
        p.x = float(x * (1.0 + 0.3 * amount * std::sin(3.0 * z)));
        p.z = float(z);
        p.y = float(p.y + 0.25 * amount * std::sin(2.0 * x + 1.0));
    }
    return mesh;
}

// N sheets on one edge: the segment from (0, 0, -1) to (0, 0, 1) and a point of the unit circle
// in z = 0 each (a non-manifold edge of N faces).
core::Mesh sheets(uint32_t n) {
    core::Mesh m;
    m.positions = {{0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}};
    for (uint32_t i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        m.positions.push_back({float(std::cos(a)), float(std::sin(a)), 0.0f});
        m.triangles.push_back({0, 1, 2 + i});
    }
    return m;
}

struct Shape {
    std::string name;
    core::Mesh mesh;
};

std::vector<Shape> fan_shapes() {
    return {
        {"cone", test::closed_cone(397)},
        {"stacked discs", test::combine(test::disc_cap(256), test::disc_cap(256), {0.05f, 0.3f, -0.1f})},
        {"umbrella", umbrella(300, 3)},
        {"twin cones", test::twin_cones(150)},
        {"stacked polygons", test::combine(test::fan_polygon(500), test::fan_polygon(300), {-0.1f, -0.2f, 0.05f})},
        {"deformed cone", deformed(test::closed_cone(211), 0.7)},
        {"deformed umbrella", deformed(umbrella(128, 9), 1.0)},
    };
}

// Queries on random edges (points inside edges, and at their ends: the apex among them) seen
// from random eyes: near the mesh, inside it, and far away.
struct Queries {
    std::vector<glm::dvec3> eyes;
    std::vector<core::OcclusionQuery> queries;
};

Queries random_queries(const core::Mesh& mesh, const core::EdgeTable& table, int eyes, int points, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<uint32_t> edge(0, uint32_t(table.edge_count() - 1));
    std::normal_distribution<double> gauss;
    const core::Bounds bounds = core::bounds_of(mesh.positions);
    Queries out;
    for (int i = 0; i < eyes; ++i) {
        if (i % 4 == 3) {  // inside the box
            out.eyes.push_back(glm::mix(bounds.min, bounds.max, glm::dvec3(unit(rng), unit(rng), unit(rng))));
            continue;
        }
        const glm::dvec3 dir = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        out.eyes.push_back(bounds.center() + dir * (i % 4 == 2 ? 1e3 : 1.5 + 3.0 * unit(rng)));
    }
    for (int i = 0; i < points; ++i) {
        const uint32_t e = edge(rng);
        const glm::dvec3 a(mesh.positions[table.edge_vertices[e].x]), b(mesh.positions[table.edge_vertices[e].y]);
        const double t = i % 10 == 0 ? 0.0 : i % 10 == 1 ? 1.0 : unit(rng);
        out.queries.push_back({a + (b - a) * t, e});
    }
    return out;
}

// The plain answer of ray casting: every valid face but the edge's own, each with the ray cast
// and the double-precision triangle test that the fans' faces get.
std::vector<uint8_t> brute_force_raycast(const core::Mesh& mesh, const core::EdgeTable& table, const glm::dvec3& eye,
                                         const std::vector<core::OcclusionQuery>& queries) {
    const double scale = internal::raycast_scale(mesh.positions);
    const double reach = core::occlusion_reach(mesh.positions);
    std::vector<uint8_t> out;
    for (const core::OcclusionQuery& q : queries) {
        const internal::RayTriangleTest test(internal::occlusion_ray(q.p_object, eye, reach, scale));
        const auto own = table.faces_of(q.edge);
        bool hit = false;
        for (uint32_t f = 0; f < mesh.triangles.size() && !hit; ++f) {
            if (!table.face_valid[f] || std::find(own.begin(), own.end(), f) != own.end()) continue;
            const glm::uvec3 t = mesh.triangles[f];
            hit = test.meets(glm::dvec3(mesh.positions[t.x]) * scale, glm::dvec3(mesh.positions[t.y]) * scale,
                             glm::dvec3(mesh.positions[t.z]) * scale);
        }
        out.push_back(hit ? 1 : 0);
    }
    return out;
}

// The plain answer of exact visibility: CGAL's test against every valid face but the own.
std::vector<uint8_t> brute_force_exact(const core::Mesh& mesh, const core::EdgeTable& table, const glm::dvec3& eye,
                                       const std::vector<core::OcclusionQuery>& queries) {
    const double reach = core::occlusion_reach(mesh.positions);
    std::vector<uint8_t> out;
    for (const core::OcclusionQuery& q : queries) {
        const internal::QuerySegment segment = internal::query_segment(q.p_object, eye, reach);
        const auto own = table.faces_of(q.edge);
        bool hit = false;
        for (uint32_t f = 0; f < mesh.triangles.size() && !hit; ++f) {
            if (!table.face_valid[f] || std::find(own.begin(), own.end(), f) != own.end()) continue;
            const glm::uvec3 t = mesh.triangles[f];
            hit = internal::segment_meets_triangle(segment, glm::dvec3(mesh.positions[t.x]),
                                                   glm::dvec3(mesh.positions[t.y]), glm::dvec3(mesh.positions[t.z]));
        }
        out.push_back(hit ? 1 : 0);
    }
    return out;
}

using BruteForce = std::vector<uint8_t> (*)(const core::Mesh&, const core::EdgeTable&, const glm::dvec3&,
                                            const std::vector<core::OcclusionQuery>&);

// Answers of `occlusion` that differ from the brute force's, over every eye; also counts the
// occluded answers into r_occluded.
size_t count_differences(const core::Mesh& mesh, const core::EdgeTable& table, const Queries& r,
                         const core::Occlusion& occlusion, BruteForce brute_force, size_t& r_occluded) {
    size_t differ = 0;
    std::vector<uint8_t> actual(r.queries.size());
    for (const glm::dvec3& eye : r.eyes) {
        occlusion.occluded(eye, r.queries, actual);
        const std::vector<uint8_t> expected = brute_force(mesh, table, eye, r.queries);
        for (size_t i = 0; i < actual.size(); ++i) {
            differ += actual[i] != expected[i];
            r_occluded += expected[i];
        }
    }
    return differ;
}

// Queries whose ray runs through or close by the apex of the first fan: from points on random
// edges towards eyes on the far side of the apex, on the line through it or just off it.
Queries through_the_apex(const core::Mesh& mesh, const core::EdgeTable& table, const glm::dvec3& apex, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<uint32_t> edge(0, uint32_t(table.edge_count() - 1));
    std::normal_distribution<double> gauss;
    Queries out;
    for (int i = 0; i < 40; ++i) {
        const uint32_t e = edge(rng);
        const glm::dvec3 a(mesh.positions[table.edge_vertices[e].x]), b(mesh.positions[table.edge_vertices[e].y]);
        out.queries.push_back({a + (b - a) * unit(rng), e});
    }
    // One eye per offset from the apex: the queries' rays pass the apex at about that distance
    // (the eye is far beyond it, so each ray's direction differs).
    for (const double offset : {0.0, 1e-12, 1e-9, 1e-6, 1e-3}) {
        const glm::dvec3 off = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng))) * offset;
        out.eyes.push_back(apex + off);
    }
    return out;
}

TEST(FanIndex, FindsTheConesApexAndBaseCentre) {
    const core::Mesh cone = test::closed_cone(200);
    const core::EdgeTable table = core::build_edge_table(cone);
    const internal::FanIndex fans(cone, table, 1.0);
    ASSERT_EQ(fans.fan_count(), 2u);
    EXPECT_EQ(fans.apex(0), 0u);
    EXPECT_EQ(fans.apex(1), 1u);
    std::set<uint32_t> all;
    for (uint32_t fan = 0; fan < 2; ++fan) {
        const std::vector<uint32_t> faces = fans.faces(fan);
        EXPECT_EQ(faces.size(), 200u);
        for (const uint32_t f : faces) {
            const glm::uvec3 t = cone.triangles[f];
            EXPECT_TRUE(t.x == fans.apex(fan) || t.y == fans.apex(fan) || t.z == fans.apex(fan));
            all.insert(f);
        }
    }
    EXPECT_EQ(all.size(), 400u) << "every face in exactly one fan";
    EXPECT_EQ(std::count(fans.in_fan().begin(), fans.in_fan().end(), uint8_t(1)), 400);
}

TEST(FanIndex, RingOrderWalksAroundTheApex) {
    // Faces in a scrambled order: the ring must still come out edge to edge.
    core::Mesh disc = test::disc_cap(300);
    std::mt19937 rng(5);
    std::shuffle(disc.triangles.begin(), disc.triangles.end(), rng);
    const core::EdgeTable table = core::build_edge_table(disc);
    const internal::FanIndex fans(disc, table, 1.0);
    ASSERT_EQ(fans.fan_count(), 1u);
    const std::vector<uint32_t> faces = fans.faces(0);
    ASSERT_EQ(faces.size(), 300u);
    auto rim = [&](uint32_t f) {
        std::set<uint32_t> v = {disc.triangles[f].x, disc.triangles[f].y, disc.triangles[f].z};
        v.erase(0);
        return v;
    };
    for (size_t i = 0; i < faces.size(); ++i) {
        const std::set<uint32_t> a = rim(faces[i]), b = rim(faces[(i + 1) % faces.size()]);
        std::vector<uint32_t> shared;
        std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
        EXPECT_EQ(shared.size(), 1u) << "faces " << i << " and " << i + 1 << " of the ring share an edge";
    }

    // An open fan walks from one end to the other.
    const core::Mesh polygon = test::fan_polygon(100);
    const core::EdgeTable polygon_table = core::build_edge_table(polygon);
    const internal::FanIndex open(polygon, polygon_table, 1.0);
    ASSERT_EQ(open.fan_count(), 1u);
    const std::vector<uint32_t> run = open.faces(0);
    ASSERT_EQ(run.size(), 98u);
    const bool forward = run.front() == 0;
    EXPECT_TRUE(forward || run.front() == 97);
    for (size_t i = 0; i < run.size(); ++i) EXPECT_EQ(run[i], forward ? i : 97 - i);
}

TEST(FanIndex, OrdinaryMeshesHaveNoFans) {
    for (const core::Mesh& mesh : {test::torus(1.0, 0.35, 48, 24), test::uv_sphere(48, 24, 1.0), test::icosphere(3),
                                   test::disc_cap(63), test::closed_cone(63)}) {
        const core::EdgeTable table = core::build_edge_table(mesh);
        const internal::FanIndex fans(mesh, table, 1.0);
        EXPECT_TRUE(fans.empty());
        EXPECT_TRUE(fans.in_fan().empty());
    }
    // From kMinFanFaces faces on, a vertex has a fan.
    const core::Mesh disc = test::disc_cap(uint32_t(internal::kMinFanFaces));
    EXPECT_EQ(internal::FanIndex(disc, core::build_edge_table(disc), 1.0).fan_count(), 1u);
}

TEST(FanIndex, SheetsAroundOneEdgeAreNoFan) {
    // Every face holds the shared edge: no face is a fan face of either end.
    const core::Mesh mesh = sheets(500);
    const core::EdgeTable table = core::build_edge_table(mesh);
    EXPECT_TRUE(internal::FanIndex(mesh, table, 1.0).empty());
}

TEST(FanIndex, TwinConesShareTheirApexFan) {
    const core::Mesh mesh = test::twin_cones(100);
    const core::EdgeTable table = core::build_edge_table(mesh);
    const internal::FanIndex fans(mesh, table, 1.0);
    ASSERT_EQ(fans.fan_count(), 3u);
    EXPECT_EQ(fans.apex(0), 0u);
    EXPECT_EQ(fans.faces(0).size(), 200u) << "both cones' side faces, two rings";
    EXPECT_EQ(fans.faces(1).size(), 100u);
    EXPECT_EQ(fans.faces(2).size(), 100u);
}

TEST(FanIndex, CandidatesHoldEveryFaceTheRayMeets) {
    // Stronger than equal answers: a ray that meets many faces must find each of them among
    // the candidates, not just one.
    for (const Shape& shape : fan_shapes()) {
        SCOPED_TRACE(shape.name);
        const core::Mesh& mesh = shape.mesh;
        const core::EdgeTable table = core::build_edge_table(mesh);
        const double scale = internal::raycast_scale(mesh.positions);
        const internal::FanIndex fans(mesh, table, scale);
        ASSERT_FALSE(fans.empty());
        const Queries r = random_queries(mesh, table, 12, 300, 21);
        const double reach = core::occlusion_reach(mesh.positions);
        size_t met = 0;
        for (const glm::dvec3& eye : r.eyes) {
            for (const core::OcclusionQuery& q : r.queries) {
                const internal::ScaledRay ray = internal::occlusion_ray(q.p_object, eye, reach, scale);
                const internal::RayTriangleTest test(ray);
                for (uint32_t fan = 0; fan < fans.fan_count(); ++fan) {
                    std::set<uint32_t> candidates;
                    fans.find_face(fan, glm::dvec3(ray.origin), glm::dvec3(ray.direction), double(ray.tnear),
                                   double(ray.tfar),
                                   [&](uint32_t face, const glm::dvec3&, const glm::dvec3&, const glm::dvec3&) {
                                       candidates.insert(face);
                                       return false;
                                   });
                    for (const uint32_t f : fans.faces(fan)) {
                        const glm::uvec3 t = mesh.triangles[f];
                        if (!test.meets(glm::dvec3(mesh.positions[t.x]) * scale,
                                        glm::dvec3(mesh.positions[t.y]) * scale,
                                        glm::dvec3(mesh.positions[t.z]) * scale)) {
                            continue;
                        }
                        ++met;
                        EXPECT_TRUE(candidates.count(f)) << "face " << f << " met but not a candidate";
                    }
                }
            }
        }
        EXPECT_GT(met, 300u) << "the rays must meet faces";
    }
}

// Mean faces visited by `rays` segments from `from(i)` to `to(i)` in the fans of `mesh`.
template <class From, class To>
double mean_visits(const core::Mesh& mesh, int rays, From from, To to) {
    const core::EdgeTable table = core::build_edge_table(mesh);
    const internal::FanIndex fans(mesh, table, 1.0);
    size_t visited = 0;
    for (int i = 0; i < rays; ++i) {
        const glm::dvec3 a = from(i), b = to(i);
        for (uint32_t fan = 0; fan < fans.fan_count(); ++fan) {
            // As a query ray: from the point, past the end gap, to the eye.
            fans.find_face(fan, a, b - a, 1e-6, 1.0,
                           [&](uint32_t, const glm::dvec3&, const glm::dvec3&, const glm::dvec3&) {
                               ++visited;
                               return false;
                           });
        }
    }
    return double(visited) / rays;
}

TEST(FanIndex, ARayVisitsFewFaces) {
    // A cone of 20000 sides: a ray not through the apex crosses the rim's plane twice, so it
    // visits a few leaves' faces, not a share of all; nor does a ray from the apex itself
    // (the tilt test), nor one from a silhouette (its rim plane touches the cone).
    const core::Mesh cone = test::closed_cone(20000);
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> unit(-1.5, 1.5);
    std::normal_distribution<double> gauss;
    const auto anywhere = [&](int) { return glm::dvec3(unit(rng), 0.5 + unit(rng), unit(rng)); };
    EXPECT_LT(mean_visits(cone, 2000, anywhere, anywhere), 64.0);
    const glm::dvec3 apex(cone.positions[0]);
    const auto outwards = [&](int) {
        return apex + glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng))) * 4.0;
    };
    EXPECT_LT(mean_visits(
                  cone, 2000, [&](int) { return apex; }, outwards),
              64.0);
    // From points of the generators towards eyes in their tangent planes.
    const auto on_generator = [&](int i) {
        const glm::dvec3 rim(cone.positions[2 + 37 * i % 20000]);
        return apex + (rim - apex) * 0.3;
    };
    const auto along_tangent = [&](int i) {
        const glm::dvec3 rim(cone.positions[2 + 37 * i % 20000]);
        const glm::dvec3 tangent = glm::cross(rim - apex, glm::dvec3(rim.x, 1.0, rim.z));
        return on_generator(i) + glm::normalize(tangent) * 4.0 + (rim - apex) * (unit(rng) / 3.0);
    };
    EXPECT_LT(mean_visits(cone, 2000, on_generator, along_tangent), 64.0);

    // A flat polygon's first corner is in every face: rays leaving the plane from there.
    const core::Mesh polygon = test::fan_polygon(20000);
    const glm::dvec3 corner(polygon.positions[0]);
    const auto up = [&](int) { return corner + glm::dvec3(unit(rng), 2.0 + unit(rng), unit(rng)); };
    EXPECT_LT(mean_visits(
                  polygon, 2000, [&](int) { return corner; }, up),
              64.0);
}

// On every fan shape, `Occlusion` answers random queries as `brute_force` does, and some are hidden.
template <typename Occlusion, typename BruteForce>
void expect_brute_force_answers(BruteForce brute_force, int eyes, int queries, uint32_t seed) {
    for (const Shape& shape : fan_shapes()) {
        SCOPED_TRACE(shape.name);
        const core::EdgeTable table = core::build_edge_table(shape.mesh);
        const Queries r = random_queries(shape.mesh, table, eyes, queries, seed);
        const Occlusion occlusion(shape.mesh, table);
        size_t occluded = 0;
        EXPECT_EQ(count_differences(shape.mesh, table, r, occlusion, brute_force, occluded), 0u);
        EXPECT_GT(occluded, r.eyes.size() * r.queries.size() / 20) << "some points must be hidden";
    }
}

TEST(FanVisibility, RaycastEqualsBruteForceOnFans) {
    SKIP_WITHOUT_EMBREE();
    expect_brute_force_answers<core::RaycastOcclusion>(brute_force_raycast, 16, 500, 1);
}

TEST(FanVisibility, ExactEqualsBruteForceOnFans) {
    expect_brute_force_answers<core::ExactOcclusion>(brute_force_exact, 8, 150, 2);
}

TEST(FanVisibility, RaysThroughAndNearTheApex) {
    SKIP_WITHOUT_EMBREE();
    for (const Shape& shape : fan_shapes()) {
        SCOPED_TRACE(shape.name);
        const core::EdgeTable table = core::build_edge_table(shape.mesh);
        const internal::FanIndex fans(shape.mesh, table, 1.0);
        ASSERT_FALSE(fans.empty());
        for (uint32_t fan = 0; fan < fans.fan_count(); ++fan) {
            const Queries r =
                through_the_apex(shape.mesh, table, glm::dvec3(shape.mesh.positions[fans.apex(fan)]), 3 + fan);
            const core::RaycastOcclusion raycast(shape.mesh, table);
            const core::ExactOcclusion exact(shape.mesh, table);
            size_t occluded = 0;
            EXPECT_EQ(count_differences(shape.mesh, table, r, raycast, brute_force_raycast, occluded), 0u);
            EXPECT_EQ(count_differences(shape.mesh, table, r, exact, brute_force_exact, occluded), 0u);
        }
    }
}

TEST(FanVisibility, RaysAlongAnEdge) {
    SKIP_WITHOUT_EMBREE();
    // From points on the apex's edges and on rim edges, towards eyes on the same line beyond
    // either end: the ray runs along its own faces' edge, grazing the faces around it.
    for (const Shape& shape : fan_shapes()) {
        SCOPED_TRACE(shape.name);
        const core::Mesh& mesh = shape.mesh;
        const core::EdgeTable table = core::build_edge_table(mesh);
        const core::RaycastOcclusion raycast(mesh, table);
        const core::ExactOcclusion exact(mesh, table);
        size_t differ_raycast = 0, differ_exact = 0;
        for (uint32_t e = 0; e < table.edge_count(); e += 7) {
            const glm::dvec3 a(mesh.positions[table.edge_vertices[e].x]), b(mesh.positions[table.edge_vertices[e].y]);
            const std::vector<core::OcclusionQuery> queries = {{a + (b - a) * 0.25, e}, {a + (b - a) * 0.75, e}};
            for (const glm::dvec3& eye : {a + (b - a) * 3.0, b + (a - b) * 3.0, a + (b - a) * 1.5}) {
                std::vector<uint8_t> actual(queries.size());
                raycast.occluded(eye, queries, actual);
                differ_raycast += actual != brute_force_raycast(mesh, table, eye, queries);
                exact.occluded(eye, queries, actual);
                differ_exact += actual != brute_force_exact(mesh, table, eye, queries);
            }
        }
        EXPECT_EQ(differ_raycast, 0u);
        EXPECT_EQ(differ_exact, 0u);
    }
}

TEST(FanVisibility, OwnFacesAtTheApexNeverOcclude) {
    SKIP_WITHOUT_EMBREE();
    // The points of the cone's apex edges, the apex itself included, seen from outside over
    // their own faces: only those two faces touch the rays at first, and they never count.
    const core::Mesh cone = test::closed_cone(500);
    const core::EdgeTable table = core::build_edge_table(cone);
    const core::RaycastOcclusion raycast(cone, table);
    const core::ExactOcclusion exact(cone, table);
    std::vector<core::OcclusionQuery> queries;
    std::vector<glm::dvec3> eyes;
    for (const uint32_t e : table.edges_around(0)) {
        const glm::dvec3 apex(cone.positions[0]), rim(cone.positions[table.other_vertex(e, 0)]);
        if (rim.y != 0.0) continue;  // the apex's edges go to the rim (y = 0)
        // Straight out from the cone's side, through the middle of the edge.
        const glm::dvec3 out = glm::normalize(glm::dvec3(rim.x, 1.0, rim.z));
        for (const double t : {0.0, 0.001, 0.5, 0.999}) {
            queries.push_back({apex + (rim - apex) * t, e});
            eyes.push_back(apex + (rim - apex) * 0.5 + out * 4.0);
        }
    }
    ASSERT_EQ(queries.size(), 2000u);
    size_t occluded = 0;
    for (size_t i = 0; i < queries.size(); ++i) {
        uint8_t hidden = 1;
        raycast.occluded(eyes[i], {&queries[i], 1}, {&hidden, 1});
        occluded += hidden;
        exact.occluded(eyes[i], {&queries[i], 1}, {&hidden, 1});
        occluded += hidden;
    }
    EXPECT_EQ(occluded, 0u);

    // The same points seen from below the base are behind it.
    std::vector<uint8_t> hidden(queries.size(), 0);
    raycast.occluded(glm::dvec3{0.1, -3.0, 0.2}, queries, hidden);
    EXPECT_EQ(std::count(hidden.begin(), hidden.end(), uint8_t(1)), 2000);
    exact.occluded(glm::dvec3{0.1, -3.0, 0.2}, queries, hidden);
    EXPECT_EQ(std::count(hidden.begin(), hidden.end(), uint8_t(1)), 2000);
}

TEST(FanVisibility, DeformedFansFollowTheirPositions) {
    SKIP_WITHOUT_EMBREE();
    for (const Shape& shape : {Shape{"cone", test::closed_cone(300)}, Shape{"umbrella", umbrella(200, 4)},
                               Shape{"twin cones", test::twin_cones(120)}}) {
        SCOPED_TRACE(shape.name);
        const core::EdgeTable table = core::build_edge_table(shape.mesh);
        core::RaycastOcclusion raycast(shape.mesh, table);
        // The first update rebuilds in the refittable form, the later ones refit.
        for (const double amount : {0.8, -0.5, 1.2}) {
            const core::Mesh moved = deformed(shape.mesh, amount);
            raycast.update_positions(moved);
            const Queries r = random_queries(moved, table, 8, 400, 13);
            size_t occluded = 0;
            EXPECT_EQ(count_differences(moved, table, r, raycast, brute_force_raycast, occluded), 0u);
            EXPECT_GT(occluded, 0u);
            const core::ExactOcclusion exact(moved, table);
            const Queries few = random_queries(moved, table, 4, 100, 14);
            EXPECT_EQ(count_differences(moved, table, few, exact, brute_force_exact, occluded), 0u);
        }
    }
}

TEST(FanVisibility, FansBesideOrdinaryFaces) {
    SKIP_WITHOUT_EMBREE();
    // A cone over a torus: the torus's faces stay Embree triangles and the CGAL tree's, the
    // cone's go to fans. Exact visibility is exact on both; ray casting answers as the double
    // test does on these generic rays (Embree's float test decides the torus's faces).
    const core::Mesh mesh = test::combine(test::torus(1.0, 0.35, 48, 24), test::closed_cone(300), {0.2f, 0.1f, 0.0f});
    const core::EdgeTable table = core::build_edge_table(mesh);
    const internal::FanIndex fans(mesh, table, 1.0);
    ASSERT_EQ(fans.fan_count(), 2u);
    const core::RaycastOcclusion raycast(mesh, table);
    const core::ExactOcclusion exact(mesh, table);
    size_t occluded = 0;
    const Queries r = random_queries(mesh, table, 12, 400, 17);
    EXPECT_EQ(count_differences(mesh, table, r, raycast, brute_force_raycast, occluded), 0u);
    const Queries few = random_queries(mesh, table, 6, 150, 18);
    EXPECT_EQ(count_differences(mesh, table, few, exact, brute_force_exact, occluded), 0u);
    EXPECT_GT(occluded, 0u);
}

TEST(FanVisibility, ManySheetsOnOneEdge) {
    SKIP_WITHOUT_EMBREE();
    // 1000 faces on one edge: its points have every face as their own, and are never hidden
    // by them; the points of the other edges are hidden as the brute force says.
    const core::Mesh mesh = sheets(1000);
    const core::EdgeTable table = core::build_edge_table(mesh);
    const uint32_t spine = core::find_edge(table, 0, 1);
    ASSERT_EQ(table.faces_of(spine).size(), 1000u);
    const core::RaycastOcclusion raycast(mesh, table);
    const core::ExactOcclusion exact(mesh, table);
    std::vector<core::OcclusionQuery> on_spine;
    for (const double z : {-0.9, -0.3, 0.0, 0.4, 0.95}) on_spine.push_back({{0.0, 0.0, z}, spine});
    for (const glm::dvec3& eye : {glm::dvec3(3.0, 0.5, 0.2), glm::dvec3(-0.2, 2.0, 2.0), glm::dvec3(0.3, 0.1, 0.0)}) {
        std::vector<uint8_t> hidden(on_spine.size(), 1);
        raycast.occluded(eye, on_spine, hidden);
        EXPECT_EQ(hidden, std::vector<uint8_t>(on_spine.size(), 0));
        exact.occluded(eye, on_spine, hidden);
        EXPECT_EQ(hidden, std::vector<uint8_t>(on_spine.size(), 0));
    }
    size_t occluded = 0;
    const Queries r = random_queries(mesh, table, 6, 200, 19);
    EXPECT_EQ(count_differences(mesh, table, r, exact, brute_force_exact, occluded), 0u);
    EXPECT_GT(occluded, 0u);
}

TEST(OwnFaces, LongListsAnswerAsALinearSearch) {
    std::mt19937 rng(6);
    for (const size_t n :
         {size_t(0), size_t(1), size_t(2), internal::kLinearOwnFaces, internal::kLinearOwnFaces + 1, size_t(5000)}) {
        std::set<uint32_t> chosen;
        std::uniform_int_distribution<uint32_t> face(0, uint32_t(4 * n + 10));
        while (chosen.size() < n) chosen.insert(face(rng));
        const std::vector<uint32_t> own(chosen.begin(), chosen.end());
        for (uint32_t f = 0; f < 4 * n + 12; ++f) {
            EXPECT_EQ(internal::is_own_face(own, f), chosen.count(f) == 1) << n << " faces, face " << f;
        }
    }
}

TEST(RayTriangleTest, AnswersAsEmbreeOnOrdinaryMeshes) {
    SKIP_WITHOUT_EMBREE();
    // No fans here: Embree's float test decides every face. The double test agrees but for
    // rays that graze a face within float rounding (2 in 96,000 on these shapes when measured).
    const core::Mesh mesh =
        test::combine(test::torus(1.0, 0.35, 48, 24), test::uv_sphere(32, 16, 0.6), {0.3f, -0.2f, -1.2f});
    const core::EdgeTable table = core::build_edge_table(mesh);
    ASSERT_TRUE(internal::FanIndex(mesh, table, 1.0).empty());
    const core::RaycastOcclusion raycast(mesh, table);
    const Queries r = random_queries(mesh, table, 8, 1500, 5);
    size_t occluded = 0;
    const size_t total = r.eyes.size() * r.queries.size();
    EXPECT_LE(count_differences(mesh, table, r, raycast, brute_force_raycast, occluded), total / 2000);
    EXPECT_GT(occluded, total / 5);
}

TEST(RayTriangleTest, NoRayThroughASharedEdgeSlipsBetween) {
    // Rays that cross the folded surface of an umbrella at a point of an edge between two of
    // its faces (float rounding puts them a hair to either side): each meets one of the two.
    const core::Mesh mesh = umbrella(200, 12);
    std::mt19937 rng(10);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> gauss;
    auto corner = [&](uint32_t v) { return glm::dvec3(mesh.positions[v]); };
    size_t crossing = 0, slipped = 0;
    for (uint32_t i = 0; i < 200; ++i) {
        const glm::uvec3 f = mesh.triangles[i], g = mesh.triangles[(i + 1) % 200];
        ASSERT_EQ(f.y, g.z) << "faces i and i + 1 share the edge (apex, f.y)";
        const glm::dvec3 apex = corner(0), shared = corner(f.y);
        for (int k = 0; k < 50; ++k) {
            const glm::dvec3 target = apex + (shared - apex) * (0.05 + 0.9 * unit(rng));
            const glm::dvec3 from = target + glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng))) * 2.0;
            // Only rays that cross the surface there: the two faces' far corners lie on either
            // side of the plane through the ray and the edge (else the ray grazes a fold).
            const glm::dvec3 side = glm::cross(target - from, shared - apex);
            if (glm::dot(side, corner(f.z) - apex) * glm::dot(side, corner(g.y) - apex) >= 0.0) continue;
            ++crossing;
            internal::ScaledRay ray;
            ray.origin = glm::vec3(from);
            ray.direction = glm::vec3((target - from) * 2.0);
            const internal::RayTriangleTest test(ray);
            const bool a = test.meets(corner(f.x), corner(f.y), corner(f.z));
            const bool b = test.meets(corner(g.x), corner(g.y), corner(g.z));
            slipped += !a && !b;
        }
    }
    EXPECT_GT(crossing, 2000u);
    EXPECT_EQ(slipped, 0u);
}

}  // namespace
}  // namespace inkline
