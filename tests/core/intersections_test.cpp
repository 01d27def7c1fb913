// SPDX-License-Identifier: MIT
// Intersection lines (core/lines/intersections.h): against analytic curves (a sphere through a
// plane, two crossing cylinders), their chains, ties, self intersections, objects that turn them
// off, and tracing over frames.
#include "core/lines/intersections.h"

#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/objects.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace inkline {
namespace {

constexpr double kPi = std::numbers::pi;

core::Mesh moved(core::Mesh mesh, const glm::dvec3& offset) {
    for (glm::vec3& p : mesh.positions) p = glm::vec3(glm::dvec3(p) + offset);
    return mesh;
}

// (x, y, z) -> (y, -x, z): a quarter turn about z, so a tube along y runs along x.
core::Mesh along_x(core::Mesh mesh) {
    for (glm::vec3& p : mesh.positions) p = {p.y, -p.x, p.z};
    return mesh;
}

// (x, y, z) -> (x, -z, y): a quarter turn about x, so a tube along y runs along z.
core::Mesh along_z(core::Mesh mesh) {
    for (glm::vec3& p : mesh.positions) p = {p.x, -p.z, p.y};
    return mesh;
}

// One mesh of the parts and the object of each face, as MeshFrames holds them.
struct Joined {
    core::Mesh mesh;
    std::vector<uint32_t> face_objects;
};
Joined join(const std::vector<core::Mesh>& parts) {
    Joined j;
    for (uint32_t o = 0; o < parts.size(); ++o) {
        const auto base = uint32_t(j.mesh.positions.size());
        j.mesh.positions.insert(j.mesh.positions.end(), parts[o].positions.begin(), parts[o].positions.end());
        for (const glm::uvec3& t : parts[o].triangles) {
            j.mesh.triangles.push_back(t + glm::uvec3(base));
            j.face_objects.push_back(o);
        }
    }
    return j;
}

std::vector<core::Chain> crossings(const Joined& j, const core::IntersectionOptions& options = {}) {
    const core::EdgeTable table = core::build_edge_table(j.mesh);
    return core::trace_intersections(j.mesh, table, j.face_objects, options);
}

// The analytic curve as dense world-space samples, one polyline per branch.
using Curve = std::vector<std::vector<glm::dvec3>>;

// Sphere of radius 1 at the origin and the plane z = h: a circle.
Curve sphere_plane_curve(double h) {
    const double r = std::sqrt(1.0 - h * h);
    std::vector<glm::dvec3> loop;
    for (int i = 0; i <= 40000; ++i) {
        const double a = 2.0 * kPi * i / 40000;
        loop.emplace_back(r * std::cos(a), r * std::sin(a), h);
    }
    return {loop};
}

// Tube of radius r1 along x and tube of radius r2 > r1 along z: two loops, x = +-sqrt(r2^2 - y^2).
Curve tubes_curve(double r1, double r2) {
    Curve out;
    for (double side : {-1.0, 1.0}) {
        std::vector<glm::dvec3> loop;
        for (int i = 0; i <= 40000; ++i) {
            const double a = 2.0 * kPi * i / 40000;
            const double y = r1 * std::sin(a), z = r1 * std::cos(a);
            loop.emplace_back(side * std::sqrt(r2 * r2 - y * y), y, z);
        }
        out.push_back(loop);
    }
    return out;
}

double distance_to_segment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 d = b - a;
    const double len2 = glm::dot(d, d);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + d * t));
}

// Largest pixel distance of the drawn intersection points from the projected analytic curve.
double largest_distance_px(const std::vector<core::Polyline>& lines, const Curve& curve,
                           const core::Projection& projection) {
    std::vector<std::vector<glm::dvec2>> projected;
    for (const auto& branch : curve) {
        std::vector<glm::dvec2> px;
        for (const glm::dvec3& p : branch) px.push_back(projection.pixel(p));
        projected.push_back(px);
    }
    double worst = 0.0;
    for (const core::Polyline& line : lines) {
        for (const glm::dvec2& p : line.points_px) {
            double best = HUGE_VAL;
            for (const auto& px : projected) {
                for (size_t i = 0; i + 1 < px.size(); ++i) best = std::min(best, distance_to_segment(p, px[i], px[i + 1]));
            }
            worst = std::max(worst, best);
        }
    }
    return worst;
}

// Pixel length of the analytic curve where `visible` holds, from its dense samples.
double visible_length_px(const Curve& curve, const core::Projection& projection,
                         const std::function<bool(const glm::dvec3&)>& visible) {
    double length = 0.0;
    for (const auto& branch : curve) {
        for (size_t i = 0; i + 1 < branch.size(); ++i) {
            const glm::dvec3 mid = 0.5 * (branch[i] + branch[i + 1]);
            if (visible(mid)) length += glm::length(projection.pixel(branch[i + 1]) - projection.pixel(branch[i]));
        }
    }
    return length;
}

std::vector<core::Polyline> of_kind(const std::vector<core::Polyline>& lines, core::LineKind kind) {
    std::vector<core::Polyline> out;
    for (const core::Polyline& l : lines) {
        if (l.kind == kind) out.push_back(l);
    }
    return out;
}

double total_length_px(const std::vector<core::Polyline>& lines) {
    double sum = 0.0;
    for (const core::Polyline& l : lines) sum += l.length_px();
    return sum;
}

// One frame of the parts through core::FramePipeline with exact visibility.
core::FrameResult draw_parts(std::vector<test::Part> parts, const test::View& view,
                             const std::function<void(core::Scene&)>& edit = {},
                             core::VisibilityMode mode = core::VisibilityMode::kExact) {
    core::Mesh whole;
    for (const test::Part& p : parts) whole = test::combine(whole, p.mesh, {0.0f, 0.0f, 0.0f});
    core::Scene scene = test::scene_for(view, whole);
    if (edit) edit(scene);
    const auto frames = test::objects_frames(std::move(parts));
    core::FramePipeline pipeline(scene, *frames, core::make_cpu_occlusion(mode));
    return pipeline.run(scene.first_frame);
}

TEST(Intersections, SphereThroughPlaneIsOneClosedLoopOnBothSurfaces) {
    const double h = 0.3;
    const Joined j = join({test::uv_sphere(256, 128, 1.0), moved(test::grid(40, 2.0), {0.0, 0.0, h})});
    const core::EdgeTable table = core::build_edge_table(j.mesh);
    const std::vector<core::Chain> chains = core::trace_intersections(j.mesh, table, j.face_objects, {});
    ASSERT_EQ(chains.size(), 1u);
    const core::Chain& c = chains[0];
    EXPECT_EQ(c.kind, core::LineKind::kIntersection);
    EXPECT_TRUE(c.closed);
    EXPECT_TRUE(c.vertices.empty());
    ASSERT_EQ(c.edges.size() + 1, c.points.size());
    ASSERT_EQ(c.crossing_faces.size(), c.edges.size());
    EXPECT_EQ(c.points.front(), c.points.back());
    const double r = std::sqrt(1.0 - h * h);
    // The sphere's faces lie inside it by at most its sagitta (1 - cos(pi / 128) at the equator).
    const double sagitta = 1.0 - std::cos(kPi / 128.0);
    for (const glm::dvec3& p : c.points) {
        EXPECT_NEAR(p.z, h, 1e-6);
        const double radial = std::hypot(p.x, p.y);
        EXPECT_LE(radial, r + 1e-6);
        EXPECT_GE(radial, std::sqrt(std::pow(1.0 - sagitta, 2) - h * h) - 1e-6);
    }
    // The first surface is the sphere (object 0): each segment names one of its edges; the
    // crossing face is the plane's.
    for (size_t i = 0; i < c.edges.size(); ++i) {
        EXPECT_EQ(j.face_objects[table.faces_of(c.edges[i]).front()], 0u);
        EXPECT_EQ(j.face_objects[c.crossing_faces[i]], 1u);
    }
    // Segments cover the circle once: length close to 2 pi r.
    double length = 0.0;
    for (size_t i = 0; i + 1 < c.points.size(); ++i) length += glm::length(c.points[i + 1] - c.points[i]);
    EXPECT_NEAR(length, 2.0 * kPi * r, 2e-3 * 2.0 * kPi * r);
}

TEST(Intersections, SphereAndPlaneDrawWithinAQuarterPixelOfTheCircle) {
    const double h = 0.3;
    const test::View view{.eye = {0.0, -2.2, 3.4}, .fov_y_deg = 40.0, .size = 1024};
    const core::FrameResult frame =
        draw_parts({{"Ball", test::uv_sphere(512, 256, 1.0)}, {"Ground", moved(test::grid(48, 2.0), {0.0, 0.0, h})}}, view);
    const auto lines = of_kind(frame.lines.polylines, core::LineKind::kIntersection);
    ASSERT_FALSE(lines.empty());
    const core::Projection projection(frame.lines.camera, frame.lines.image, glm::dmat4(1.0));
    const Curve curve = sphere_plane_curve(h);
    EXPECT_LE(largest_distance_px(lines, curve, projection), 0.25);
    // Visible where the ball's cap above the plane does not stand in front of the circle.
    const glm::dvec3 eye = frame.lines.camera.eye;
    const double expected =
        visible_length_px(curve, projection, [&](const glm::dvec3& p) { return glm::dot(eye - p, p) >= 0.0; });
    EXPECT_GT(expected, 100.0);
    EXPECT_NEAR(total_length_px(lines), expected, 0.01 * expected);
    for (const core::Polyline& l : lines) {
        EXPECT_TRUE(l.visible);
        EXPECT_EQ(l.crossing_faces.size(), l.edges.size());
        EXPECT_EQ(frame.lines.objects[size_t(l.object)].name, "Ball");
    }
    // Ray casting agrees with the exact test.
    if (core::raycast_available()) {
        const core::FrameResult cast =
            draw_parts({{"Ball", test::uv_sphere(512, 256, 1.0)}, {"Ground", moved(test::grid(48, 2.0), {0.0, 0.0, h})}},
                       view, {}, core::VisibilityMode::kRaycast);
        EXPECT_NEAR(total_length_px(of_kind(cast.lines.polylines, core::LineKind::kIntersection)), total_length_px(lines),
                    1e-3 * total_length_px(lines));
    }
}

// Where a ball's outline goes into the ground, the intersection line with the ground goes behind
// the ball: the two meet in one point. Smooth contours lie off the facets' own outline, so the
// intersection line is hidden by the smooth surface's back as its contour takes it, and by
// nothing within two of its edges in front of it: on a coarse ball (48 x 24) both lines end in
// the same place, and the strokes end there as junctions, not tapered. (Before, the
// intersection line ended where the facets hid it, 1-2 px short, on a real shot too.)
TEST(Intersections, WithSmoothContoursTheLinesMeetWhereTheOutlineGoesIntoTheGround) {
    const double h = 0.3;
    const test::View view{.eye = {0.0, -2.2, 3.4}, .fov_y_deg = 40.0, .size = 1024};
    std::vector<core::VisibilityMode> modes = {core::VisibilityMode::kExact};
    if (core::raycast_available()) modes.push_back(core::VisibilityMode::kRaycast);
    for (const core::VisibilityMode mode : modes) {
        SCOPED_TRACE(int(mode));
        const core::FrameResult frame = draw_parts(
            {{"Ball", test::uv_sphere(48, 24, 1.0)}, {"Ground", moved(test::grid(8, 2.0), {0.0, 0.0, h})}}, view,
            [&](core::Scene& s) { s.lines.contour = core::ContourMode::kSmooth; }, mode);
        const auto crossings = of_kind(frame.lines.polylines, core::LineKind::kIntersection);
        const auto outline = of_kind(frame.lines.polylines, core::LineKind::kSilhouette);
        ASSERT_FALSE(crossings.empty());
        // Each end of a visible intersection line is an end of a visible outline.
        size_t ends = 0;
        for (const core::Polyline& l : crossings) {
            if (!l.visible || l.closed) continue;
            for (const glm::dvec2& end : {l.points_px.front(), l.points_px.back()}) {
                double nearest = HUGE_VAL;
                for (const core::Polyline& o : outline) {
                    if (!o.visible) continue;
                    nearest = std::min(
                        {nearest, glm::length(o.points_px.front() - end), glm::length(o.points_px.back() - end)});
                }
                EXPECT_LE(nearest, 0.25);
                ++ends;
            }
        }
        EXPECT_EQ(ends, 2u);
        // And the strokes end there as junctions, not tapered.
        for (const core::Stroke& s : frame.strokes.strokes) {
            if (s.geometry.kind != core::LineKind::kIntersection || !s.geometry.visible) continue;
            EXPECT_EQ(s.geometry.ends[0], core::StrokeEnd::kJunction);
            EXPECT_EQ(s.geometry.ends[1], core::StrokeEnd::kJunction);
        }
    }
}

TEST(Intersections, CrossingTubesDrawWithinAQuarterPixelOfTheirCurve) {
    const double r1 = 0.5, r2 = 0.8;
    const test::View view{.eye = {1.4, 2.2, 3.0}, .fov_y_deg = 40.0, .size = 1024};
    const core::FrameResult frame = draw_parts({{"Thin", along_x(test::tube(512, 96, r1, 1.6))},
                                                {"Thick", along_z(test::tube(768, 96, r2, 1.6))}},
                                               view);
    const auto lines = of_kind(frame.lines.polylines, core::LineKind::kIntersection);
    ASSERT_FALSE(lines.empty());
    const core::Projection projection(frame.lines.camera, frame.lines.image, glm::dmat4(1.0));
    const Curve curve = tubes_curve(r1, r2);
    EXPECT_LE(largest_distance_px(lines, curve, projection), 0.25);
    // Open tubes: a point of the curve is hidden where the segment to the eye passes through
    // either tube's wall first.
    const glm::dvec3 eye = frame.lines.camera.eye;
    auto crosses_tube = [&](const glm::dvec3& p, int axis, double radius, double half_length) {
        // Points of the segment p -> eye (beyond p) on the tube's surface, within its length.
        const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;
        const glm::dvec3 d = eye - p;
        const double qa = d[a] * d[a] + d[b] * d[b];
        const double qb = 2.0 * (p[a] * d[a] + p[b] * d[b]);
        const double qc = p[a] * p[a] + p[b] * p[b] - radius * radius;
        const double disc = qb * qb - 4.0 * qa * qc;
        if (qa == 0.0 || disc < 0.0) return false;
        for (double s : {-1.0, 1.0}) {
            const double t = (-qb + s * std::sqrt(disc)) / (2.0 * qa);
            if (t > 1e-7 && t < 1.0 && std::abs(p[axis] + t * d[axis]) <= half_length) return true;
        }
        return false;
    };
    const double expected = visible_length_px(curve, projection, [&](const glm::dvec3& p) {
        return !crosses_tube(p, 0, r1, 1.6) && !crosses_tube(p, 2, r2, 1.6);
    });
    EXPECT_GT(expected, 100.0);
    EXPECT_NEAR(total_length_px(lines), expected, 0.01 * expected);
}

TEST(Intersections, OneObjectCrossesItselfOnlyWhenAsked) {
    // Two spheres of radius 1 at x = -0.5 and 0.5, one object: they cross in the circle x = 0,
    // radius sqrt(3) / 2.
    core::Mesh both = moved(test::uv_sphere(128, 64, 1.0), {-0.5, 0.0, 0.0});
    const core::Mesh right = moved(test::uv_sphere(128, 64, 1.0), {0.5, 0.0, 0.0});
    both = test::combine(both, right, {0.0f, 0.0f, 0.0f});
    const Joined j{both, {}};
    EXPECT_TRUE(crossings(j).empty());
    const std::vector<core::Chain> chains = crossings(j, {.between_objects = true, .self = true});
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_TRUE(chains[0].closed);
    for (const glm::dvec3& p : chains[0].points) {
        EXPECT_NEAR(p.x, 0.0, 0.01);
        EXPECT_NEAR(std::hypot(p.y, p.z), std::sqrt(3.0) / 2.0, 0.01);
    }
}

TEST(Intersections, FacesThatOnlyTouchGiveClosedLoopsOrNothing) {
    // A cube standing on a plane: its bottom lies in the plane, its side edges end on it. The
    // tie is broken one way for either object order; the answer is never a broken line.
    const core::Mesh ground = test::grid(10, 2.0);                // z = 0
    const core::Mesh box = moved(test::cube(0.5), {0.1, 0.2, 0.5});  // z in [0, 1]
    // The object with the higher index counts as a step along +z (kNudge's z is positive): a box
    // after the ground stands just above it and crosses nothing; a box before it sinks in, and
    // the ground crosses it along the square of its bottom edges.
    EXPECT_TRUE(crossings(join({ground, box})).empty());
    const std::vector<core::Chain> sunk = crossings(join({box, ground}));
    ASSERT_EQ(sunk.size(), 1u);
    EXPECT_TRUE(sunk[0].closed);
    double perimeter = 0.0;
    for (size_t i = 0; i + 1 < sunk[0].points.size(); ++i) {
        const glm::dvec3& p = sunk[0].points[i];
        EXPECT_EQ(p.z, 0.0);
        EXPECT_NEAR(std::max(std::abs(p.x - 0.1), std::abs(p.y - 0.2)), 0.5, 1e-6);
        perimeter += glm::length(sunk[0].points[i + 1] - p);
    }
    EXPECT_NEAR(perimeter, 4.0, 1e-6);
    // Two cubes sharing a face exactly, and a cube resting on another's corner edge.
    const core::Mesh a = test::cube(0.5);
    const core::Mesh b = moved(test::cube(0.5), {1.0, 0.0, 0.0});
    for (const core::Chain& c : crossings(join({a, b}))) EXPECT_TRUE(c.closed);
}

TEST(Intersections, ObjectsCanTurnThemOff) {
    const test::View view{.eye = {0.0, -2.2, 3.4}, .fov_y_deg = 40.0, .size = 512};
    auto parts = [] {
        return std::vector<test::Part>{{"Ball", test::uv_sphere(64, 32, 1.0)},
                                       {"Ground", moved(test::grid(8, 2.0), {0.0, 0.0, 0.3})}};
    };
    auto count = [](const core::FrameResult& f) { return of_kind(f.lines.polylines, core::LineKind::kIntersection).size(); };
    EXPECT_GT(count(draw_parts(parts(), view)), 0u);
    // A holdout draws no intersection lines, nor does an object that turns the kind off.
    EXPECT_EQ(count(draw_parts(parts(), view, [](core::Scene& s) { core::ObjectRule rule;
        rule.pattern = "Ground";
        rule.lines = false;
        s.objects.push_back(rule); })), 0u);
    EXPECT_EQ(count(draw_parts(parts(), view,
                               [](core::Scene& s) { core::ObjectRule rule;
        rule.pattern = "B*";
        rule.intersection = false;
        s.objects.push_back(rule); })),
              0u);
    EXPECT_EQ(count(draw_parts(parts(), view, [](core::Scene& s) { s.lines.intersection = false; })), 0u);
    // The other kinds are untouched by it.
    const auto off = draw_parts(parts(), view, [](core::Scene& s) { s.lines.intersection = false; });
    const auto on = draw_parts(parts(), view);
    EXPECT_EQ(of_kind(off.lines.polylines, core::LineKind::kSilhouette).size(),
              of_kind(on.lines.polylines, core::LineKind::kSilhouette).size());
    EXPECT_TRUE(on.lines.stats.intersections);
    EXPECT_GT(on.lines.stats.feature_edges[size_t(core::LineKind::kIntersection)], 0u);
}

TEST(Intersections, AMovingBallIsTracedEveryFrame) {
    // The ball sinks through the plane z = 0 from z = 1.2 by 0.2 a frame: no line, then circles
    // of radius sqrt(1 - c^2) for the ball's centre at height c.
    const test::View view{.eye = {0.0, -3.0, 4.0}, .fov_y_deg = 40.0, .size = 512};
    std::vector<test::Part> parts{{"Ball", moved(test::uv_sphere(128, 64, 1.0), {0.0, 0.0, 1.2}), {0.0, 0.0, -0.2}},
                                  {"Ground", test::grid(16, 2.0)}};
    core::Mesh whole = test::combine(parts[0].mesh, parts[1].mesh, {0.0f, 0.0f, 0.0f});
    core::Scene scene = test::scene_for(view, whole);
    scene.last_frame = 8;
    scene.camera.near.reset();
    scene.camera.far.reset();
    const auto frames = test::objects_frames(parts);
    core::FramePipeline pipeline(scene, *frames, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    for (int frame = 1; frame <= scene.last_frame; ++frame) {
        const core::FrameResult r = pipeline.run(frame);
        const double c = 1.2 - 0.2 * (frame - 1);
        const core::EdgeTable table = core::build_edge_table(*r.mesh);
        const std::vector<core::Chain> fresh = core::trace_intersections(*r.mesh, table, frames->face_objects(), {});
        const size_t found = r.lines.stats.feature_edges[size_t(core::LineKind::kIntersection)];
        size_t expected_segments = 0;
        for (const core::Chain& ch : fresh) expected_segments += ch.edges.size();
        EXPECT_EQ(found, expected_segments) << "frame " << frame;
        if (std::abs(c) >= 1.0) {
            EXPECT_EQ(found, 0u) << "frame " << frame;
            continue;
        }
        ASSERT_EQ(fresh.size(), 1u) << "frame " << frame;
        for (const glm::dvec3& p : fresh[0].points) EXPECT_NEAR(std::hypot(p.x, p.y), std::sqrt(1.0 - c * c), 2e-3);
    }
}

}  // namespace
}  // namespace inkline
