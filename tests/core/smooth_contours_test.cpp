// SPDX-License-Identifier: MIT
// Smooth contours (core/lines/smooth_contours.h): against the analytic contours of a sphere and
// a torus, their chains (loops, open curves on a boundary), their visibility (a contour point is
// not hidden by the faces around it, raycast agrees with exact) and their strokes.
#include "core/lines/smooth_contours.h"

#include "core/lines/chaining.h"
#include "core/lines/features.h"

#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/camera.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <numbers>
#include <tuple>
#include <vector>

namespace inkline {
namespace {

constexpr double kPi = std::numbers::pi;

// (x, y, z) -> (x, -z, y): a quarter turn about x, so a torus around y turns around z.
core::Mesh around_z(core::Mesh mesh) {
    for (glm::vec3& p : mesh.positions) p = {p.x, -p.z, p.y};
    return mesh;
}

// A circle around the z axis (radius, height), which a view down the z axis sees as a circle.
struct Circle {
    double radius = 0.0;
    double z = 0.0;
};

// The analytic contours of a torus around z (major radius R, minor r) seen from (0, 0, d):
// with p = ((R + r cos f) cos t, (R + r cos f) sin t, r sin f) and its normal, n . (p - eye) =
// R cos f + r - d sin f, zero where cos(f + b) = -r / A, A = sqrt(R^2 + d^2), b = atan2(d, R).
std::vector<Circle> torus_contours(double R, double r, double d) {
    const double a = std::sqrt(R * R + d * d), b = std::atan2(d, R), c = std::acos(-r / a);
    std::vector<Circle> out;
    for (const double f : {c - b, -c - b}) out.push_back({R + r * std::cos(f), r * std::sin(f)});
    return out;
}

// Largest image distance (px) from a chain point to the nearest of the circles, as projected.
double worst_px(const std::vector<core::Chain>& chains, const core::Projection& projection,
                const std::vector<Circle>& circles) {
    double worst = 0.0;
    for (const core::Chain& chain : chains) {
        for (const glm::dvec3& p : chain.points) {
            const glm::dvec2 px = projection.pixel(p);
            double best = HUGE_VAL;
            for (const Circle& c : circles) {
                const glm::dvec2 center = projection.pixel({0.0, 0.0, c.z});
                const double radius = glm::length(projection.pixel({c.radius, 0.0, c.z}) - center);
                best = std::min(best, std::abs(glm::length(px - center) - radius));
            }
            worst = std::max(worst, best);
        }
    }
    return worst;
}

struct Traced {
    std::vector<core::Chain> chains;
    core::Projection projection;
};

Traced trace(const core::Mesh& mesh, const test::View& view) {
    const core::EdgeTable table = core::build_edge_table(mesh);
    core::SmoothContourTracer tracer(mesh, table);
    const core::Camera camera = test::camera_for(view, mesh);
    return {tracer.trace(mesh, table, view.eye), core::Projection(camera, {view.size, view.size}, glm::dmat4(1.0))};
}

TEST(SmoothContours, SphereContourLiesOnTheAnalyticCircle) {
    // Unit sphere seen from (0, 0, 4): the contour is where p . (p - eye) = 0, the circle
    // z = 1/4 of radius sqrt(1 - 1/16).
    const std::vector<Circle> analytic = {{std::sqrt(1.0 - 1.0 / 16.0), 0.25}};
    double coarse_px = 0.0;
    for (const int levels : {3, 6}) {
        const core::Mesh sphere = test::icosphere(levels);
        const Traced t = trace(sphere, {});
        ASSERT_EQ(t.chains.size(), 1u) << levels;
        EXPECT_TRUE(t.chains[0].closed);
        EXPECT_EQ(t.chains[0].points.front(), t.chains[0].points.back());
        EXPECT_EQ(t.chains[0].edges.size() + 1, t.chains[0].points.size());
        EXPECT_EQ(t.chains[0].faces.size(), t.chains[0].edges.size());
        const double px = worst_px(t.chains, t.projection, analytic);
        if (levels == 3) {
            coarse_px = px;
        } else {
            EXPECT_LE(px, 0.25) << "81,920 faces";
        }
    }
    EXPECT_GT(coarse_px, 0.25) << "a 1,280-face sphere is not that close: the check can fail";
}

TEST(SmoothContours, TorusSeenAlongItsAxisHasItsTwoAnalyticCircles) {
    const double R = 1.0, r = 0.35, d = 4.0;
    const core::Mesh torus = around_z(test::torus(R, r, 400, 200));
    const Traced t = trace(torus, {.eye = {0.0, 0.0, d}});
    ASSERT_EQ(t.chains.size(), 2u);
    for (const core::Chain& chain : t.chains) EXPECT_TRUE(chain.closed);
    EXPECT_LE(worst_px(t.chains, t.projection, torus_contours(R, r, d)), 0.25);
}

TEST(SmoothContours, ChainsEndOnBoundaryEdges) {
    // A hemisphere (y >= 0) seen from the side: the contour runs from the rim over the top and
    // back to the rim.
    const core::Mesh half = test::hemisphere(64, 32, 1.0);
    const core::EdgeTable table = core::build_edge_table(half);
    core::SmoothContourTracer tracer(half, table);
    const std::vector<core::Chain>& chains = tracer.trace(half, table, glm::dvec3{0.0, 0.0, 4.0});
    ASSERT_EQ(chains.size(), 1u);
    const core::Chain& c = chains[0];
    EXPECT_FALSE(c.closed);
    EXPECT_EQ(table.faces_of(c.edges.front()).size(), 1u) << "starts on the rim";
    EXPECT_NEAR(c.points.front().y, 0.0, 1e-6);
    EXPECT_NEAR(c.points.back().y, 0.0, 1e-6);
    EXPECT_GT(c.points[c.points.size() / 2].y, 0.9) << "over the top";
    // Every segment crosses a face of which its start edge is an edge.
    for (size_t i = 0; i < c.edges.size(); ++i) {
        const auto faces = table.faces_of(c.edges[i]);
        EXPECT_NE(std::find(faces.begin(), faces.end(), c.faces[i]), faces.end()) << i;
    }
    EXPECT_EQ(tracer.stats().segments, c.faces.size());
    EXPECT_LT(tracer.stats().faces_tested, half.triangles.size()) << "the cones rule out the rest";
    core::SmoothContourTracer brute(half, table, {.mode = core::TrackerMode::kBrute});
    brute.trace(half, table, glm::dvec3{0.0, 0.0, 4.0});
    EXPECT_EQ(brute.stats().faces_tested, half.triangles.size());
}

// Empty when the two tracers' chains are the same bit for bit, else the first difference.
std::string difference(const std::vector<core::Chain>& brute, const std::vector<core::Chain>& incremental) {
    if (brute.size() != incremental.size()) {
        return "brute has " + std::to_string(brute.size()) + " chains, incremental " +
               std::to_string(incremental.size());
    }
    for (size_t i = 0; i < brute.size(); ++i) {
        const core::Chain &a = brute[i], &b = incremental[i];
        if (a.points != b.points) return "chain " + std::to_string(i) + ": points differ";
        if (a.edges != b.edges) return "chain " + std::to_string(i) + ": edges differ";
        if (a.faces != b.faces) return "chain " + std::to_string(i) + ": faces differ";
        if (a.closed != b.closed || a.kind != b.kind) return "chain " + std::to_string(i) + ": kind or closure";
    }
    return {};
}

struct Sequence {
    size_t frames = 0, mismatched = 0;
    size_t faces_tested = 0, faces = 0;  // frames after the first
    size_t max_chains = 0;
};

// Traces frames [0, count) of mesh_at(i) from eye_at(i) with both modes and compares them.
template <class MeshAt, class EyeAt>
Sequence against_brute(const core::EdgeTable& table, int count, bool deforming, MeshAt mesh_at, EyeAt eye_at,
                       double crease_angle_deg = 180.0) {
    core::SmoothContourTracer brute(mesh_at(0), table,
                                    {.mode = core::TrackerMode::kBrute, .crease_angle_deg = crease_angle_deg});
    core::SmoothContourTracer incremental(mesh_at(0), table,
                                          {.deforming = deforming, .crease_angle_deg = crease_angle_deg});
    Sequence out;
    for (int i = 0; i < count; ++i) {
        const core::Mesh& mesh = mesh_at(i);
        const std::vector<core::Chain> expected = brute.trace(mesh, table, eye_at(i));
        const std::vector<core::Chain>& got = incremental.trace(mesh, table, eye_at(i));
        const std::string diff = difference(expected, got);
        EXPECT_EQ(diff, "") << "frame " << i;
        EXPECT_EQ(incremental.stats().segments, brute.stats().segments) << "frame " << i;
        ++out.frames;
        out.mismatched += diff.empty() ? 0 : 1;
        out.max_chains = std::max(out.max_chains, got.size());
        if (i > 0) {
            out.faces_tested += incremental.stats().faces_tested;
            out.faces += brute.stats().faces_tested;
        }
    }
    return out;
}

glm::dvec3 orbit(double degrees, double distance, double lift) {
    const double a = degrees * kPi / 180.0;
    return {distance * std::sin(a), lift, distance * std::cos(a)};
}

TEST(SmoothContours, IncrementalEqualsBruteForceOnEveryFrame) {
    // A bumpy sphere (many contour loops, some appearing and vanishing) orbited, then a cut to a
    // close view; a hemisphere seen from outside and inside; a noisy terrain from low angles.
    struct Case {
        const char* name;
        core::Mesh mesh;
        std::function<glm::dvec3(int)> eye_at;
        bool smooth = true;  // a surface the cones can bound (not noise)
    };
    std::vector<Case> cases;
    cases.push_back({"bumpy sphere", test::bumpy_sphere(test::icosphere(5), {.count = 60, .height_max = 0.12}),
                     [](int i) { return i < 40 ? orbit(3.0 * i, 3.5, 0.4) : glm::dvec3(0.3, -1.6, 0.9) + 0.01 * (i - 40); }});
    cases.push_back({"hemisphere", test::hemisphere(96, 48, 1.0),
                     [](int i) { return orbit(7.0 * i, 3.0, 2.5 * std::sin(0.37 * i)); }});
    cases.push_back({"terrain", test::noise_terrain(64, 0.15), [](int i) { return orbit(5.0 * i, 3.0, 0.3); }, false});
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const core::EdgeTable table = core::build_edge_table(c.mesh);
        const Sequence s = against_brute(table, 60, false, [&](int) -> const core::Mesh& { return c.mesh; }, c.eye_at);
        EXPECT_EQ(s.mismatched, 0u);
        // With creases splitting the normals (the terrain has many).
        EXPECT_EQ(against_brute(table, 20, false, [&](int) -> const core::Mesh& { return c.mesh; }, c.eye_at, 30.0)
                      .mismatched,
                  0u);
        EXPECT_GT(s.max_chains, 0u);
        if (c.smooth) {
            EXPECT_LT(s.faces_tested, s.faces / 3) << "the cones rule out most faces";
        }
        std::printf("%s: %zu of %zu faces tested\n", c.name, s.faces_tested, s.faces);
    }
}

TEST(SmoothContours, IncrementalEqualsBruteForceOnADeformingMesh) {
    // A torus whose tube swells and twists over time, orbited: new positions and normals each frame.
    const std::vector<core::Mesh> frames = test::swelling_torus(40);
    const core::EdgeTable table = core::build_edge_table(frames[0]);
    const Sequence s = against_brute(
        table, int(frames.size()), true, [&](int i) -> const core::Mesh& { return frames[size_t(i)]; },
        [](int i) { return orbit(5.0 * i, 4.0, 1.0); });
    EXPECT_EQ(s.mismatched, 0u);
    EXPECT_LT(s.faces_tested, s.faces);
    // Creases that come and go as the tube folds.
    const Sequence creased = against_brute(
        table, int(frames.size()), true, [&](int i) -> const core::Mesh& { return frames[size_t(i)]; },
        [](int i) { return orbit(5.0 * i, 4.0, 1.0); }, 12.0);
    EXPECT_EQ(creased.mismatched, 0u);
}

TEST(SmoothContours, DegenerateAndNonManifoldFacesMatchBruteForce) {
    // A folded grid with a zero-area face and a fin: a third face on one of its edges.
    core::Mesh mesh = test::grid(12, 1.0);
    for (glm::vec3& p : mesh.positions) p.z = 0.6f * std::abs(p.x) - 0.3f * p.y * p.y;
    const uint32_t a = mesh.triangles[40].x, b = mesh.triangles[40].y;
    mesh.positions.push_back(mesh.positions[a] + glm::vec3(0.0f, 0.0f, 0.5f));
    mesh.triangles.push_back({a, b, uint32_t(mesh.positions.size() - 1)});
    mesh.triangles.push_back({a, a, b});
    const core::EdgeTable table = core::build_edge_table(mesh);
    const Sequence s =
        against_brute(table, 36, false, [&](int) -> const core::Mesh& { return mesh; },
                      [](int i) { return orbit(10.0 * i, 3.0, 1.5 * std::cos(0.2 * i)); });
    EXPECT_EQ(s.mismatched, 0u);
    EXPECT_GT(s.max_chains, 0u);
}

// A closed cylinder around y (radius 1, height 2) of `sides` sides, its caps fans around a centre:
// the rims are creases of 90 degrees.
core::Mesh closed_cylinder(uint32_t sides) {
    core::Mesh m;
    for (uint32_t i = 0; i < sides; ++i) {
        const double a = 2.0 * kPi * i / sides;
        m.positions.emplace_back(float(std::cos(a)), -1.0f, float(std::sin(a)));
        m.positions.emplace_back(float(std::cos(a)), 1.0f, float(std::sin(a)));
    }
    const uint32_t bottom = uint32_t(m.positions.size()), top = bottom + 1;
    m.positions.emplace_back(0.0f, -1.0f, 0.0f);
    m.positions.emplace_back(0.0f, 1.0f, 0.0f);
    for (uint32_t i = 0; i < sides; ++i) {
        const uint32_t b0 = 2 * i, t0 = b0 + 1, b1 = 2 * ((i + 1) % sides), t1 = b1 + 1;
        m.triangles.push_back({b0, t0, t1});  // outward: the side faces away from the axis
        m.triangles.push_back({b0, t1, b1});
        m.triangles.push_back({bottom, b0, b1});
        m.triangles.push_back({top, t1, t0});
    }
    return m;
}

// Whether every point of a chain lies on one of the closed cylinder's rims.
bool on_a_rim(const core::Chain& chain) {
    return std::all_of(chain.points.begin(), chain.points.end(), [](const glm::dvec3& p) { return std::abs(p.y) == 1.0; });
}

// The ends of open chains, each once.
std::vector<glm::dvec3> chain_ends(const std::vector<core::Chain>& chains) {
    std::vector<glm::dvec3> ends;
    for (const core::Chain& chain : chains) {
        if (chain.closed) continue;
        ends.push_back(chain.points.front());
        ends.push_back(chain.points.back());
    }
    std::sort(ends.begin(), ends.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    return ends;
}

TEST(SmoothContours, CreasesSplitTheNormalsAndEndTheContour) {
    // Seen from the side, a cylinder's contour runs up its side from rim to rim. With its rims as
    // creases, each of the two lines is one open chain on the side, ending on the rims, and the
    // outline goes on along the front half of each rim, where the side faces the eye and the cap
    // away: a chain of the rim's edges from one contour's end to the other's, bit for bit. With
    // normals averaged across the rims, the contour runs on into the caps.
    const core::Mesh cylinder = closed_cylinder(48);
    const core::EdgeTable table = core::build_edge_table(cylinder);
    const glm::dvec3 eye(0.0, 0.0, 5.0);
    const double inner = std::cos(kPi / 48.0);  // the side's least distance from the axis
    auto radius = [](const glm::dvec3& p) { return std::hypot(p.x, p.z); };
    core::SmoothContourTracer split(cylinder, table, {.crease_angle_deg = 60.0});
    const std::vector<core::Chain>& chains = split.trace(cylinder, table, eye);
    ASSERT_EQ(chains.size(), 4u);
    std::vector<core::Chain> contours, rims;
    for (const core::Chain& chain : chains) {
        EXPECT_EQ(chain.kind, core::LineKind::kSilhouette);
        EXPECT_FALSE(chain.closed);
        EXPECT_EQ(chain.faces.size(), chain.edges.size());
        EXPECT_EQ(chain.points.size(), chain.edges.size() + 1);
        (on_a_rim(chain) ? rims : contours).push_back(chain);
    }
    ASSERT_EQ(contours.size(), 2u);
    for (const core::Chain& chain : contours) {
        EXPECT_NEAR(std::abs(chain.points.front().y), 1.0, 1e-6);
        EXPECT_NEAR(std::abs(chain.points.back().y), 1.0, 1e-6);
        EXPECT_NE(chain.points.front().y, chain.points.back().y) << "from one rim to the other";
        for (const glm::dvec3& p : chain.points) EXPECT_GE(radius(p), inner - 1e-6) << "on the side";
    }
    // With radial normals, g on the side would be 1 - 5 z at a rim point (x, +-1, z): the side
    // faces the eye for z > 0.2. The triangulated side's normals lean a little, so the contour
    // meets the rims near z = 0.2, and the rims' vertices beyond are on the outline.
    ASSERT_EQ(rims.size(), 2u);
    for (const core::Chain& chain : rims) {
        EXPECT_EQ(chain.points.front().y, chain.points.back().y) << "along one rim";
        EXPECT_NEAR(chain.points.front().z, 0.2, 0.03);
        EXPECT_NEAR(chain.points.back().z, 0.2, 0.03);
        for (size_t i = 1; i + 1 < chain.points.size(); ++i) EXPECT_GT(chain.points[i].z, 0.2) << "round the front";
        EXPECT_EQ(chain.points.size(), 23u) << "the 21 rim vertices with z > 0.2 and the two ends";
    }
    EXPECT_EQ(chain_ends(rims), chain_ends(contours)) << "the rims' stretches end where the contours end";
    EXPECT_EQ(split.crease_outline().size(), rims[0].edges.size() + rims[1].edges.size());
    core::SmoothContourTracer averaged(cylinder, table, {.crease_angle_deg = 180.0});
    bool on_a_cap = false;
    for (const core::Chain& chain : averaged.trace(cylinder, table, eye)) {
        for (const glm::dvec3& p : chain.points) on_a_cap |= radius(p) < inner - 1e-3;
    }
    EXPECT_TRUE(on_a_cap) << "the check can fail";
    core::SmoothContourTracer brute(cylinder, table, {.mode = core::TrackerMode::kBrute, .crease_angle_deg = 60.0});
    EXPECT_EQ(difference(brute.trace(cylinder, table, eye), chains), "");
}

TEST(SmoothContours, TheOutlineIsCutOutOfTheCreases) {
    // The cylinder's rims as crease lines lose the stretches on the outline: each rim is left as
    // one open chain round its back, of points, from one contour's end to the other's; with the
    // stretches it covers each rim's edges once.
    const core::Mesh cylinder = closed_cylinder(48);
    const core::EdgeTable table = core::build_edge_table(cylinder);
    const glm::dvec3 eye(0.0, 0.0, 5.0);
    core::SmoothContourTracer tracer(cylinder, table, {.crease_angle_deg = 60.0});
    const std::vector<core::Chain> contours = tracer.trace(cylinder, table, eye);
    const core::LineOptions creases_only{.silhouette = false, .boundary = false, .crease_angle_deg = 60.0};
    const std::vector<core::Chain> rims =
        core::chain_feature_edges(core::extract_feature_edges(cylinder, table, eye, creases_only), table);
    ASSERT_EQ(rims.size(), 2u);
    for (const core::Chain& rim : rims) EXPECT_TRUE(rim.closed);
    const std::vector<core::Chain> cut = core::cut_crease_outline(rims, tracer.crease_outline(), cylinder, table);
    ASSERT_EQ(cut.size(), 2u);
    std::vector<uint32_t> edges;
    for (const core::Chain& chain : cut) {
        EXPECT_EQ(chain.kind, core::LineKind::kCrease);
        EXPECT_FALSE(chain.closed);
        EXPECT_TRUE(chain.vertices.empty());
        EXPECT_EQ(chain.points.size(), chain.edges.size() + 1);
        EXPECT_TRUE(on_a_rim(chain));
        EXPECT_EQ(chain.points.front().y, chain.points.back().y);
        for (size_t i = 1; i + 1 < chain.points.size(); ++i) EXPECT_LT(chain.points[i].z, 0.2) << "round the back";
        edges.insert(edges.end(), chain.edges.begin(), chain.edges.end());
    }
    std::vector<core::Chain> outline;
    for (const core::Chain& chain : contours) {
        if (on_a_rim(chain)) outline.push_back(chain);
    }
    EXPECT_EQ(chain_ends(cut), chain_ends(outline));
    for (const core::CreaseOutline& stretch : tracer.crease_outline()) edges.push_back(stretch.edge);
    std::sort(edges.begin(), edges.end());
    EXPECT_EQ(edges.size(), 2u * 48u + 4u) << "every rim edge once, and the four cut in two twice";
    std::vector<uint32_t> all;
    for (const core::Chain& rim : rims) all.insert(all.end(), rim.edges.begin(), rim.edges.end());
    std::sort(all.begin(), all.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    EXPECT_EQ(edges, all);
    // A crease chain without a stretch on the outline stays as it was.
    const std::vector<core::Chain> far = core::cut_crease_outline(rims, {}, cylinder, table);
    ASSERT_EQ(far.size(), 2u);
    EXPECT_EQ(far[0].vertices, rims[0].vertices);
}

// Frame 1 of `mesh` seen from `view` with smooth contours, under a visibility mode.
core::FrameResult render(const core::Mesh& mesh, const test::View& view, core::VisibilityMode mode,
                         core::ContourMode contour = core::ContourMode::kSmooth) {
    return test::render_frame(mesh, view, mode, contour);
}

using test::visible_length;

TEST(SmoothContours, TheOutlineRunsOnAlongCreasesWithOrWithoutCreaseLines) {
    // A closed cylinder seen from above: its outline is the back of the top rim, the two side
    // contours and the front of the bottom rim, a crease edge between a face turned to the eye
    // and one turned away being on the outline, as mesh mode draws it. With crease lines or
    // without, smooth contours draw it whole, as one closed silhouette stroke as long as mesh
    // mode's, and only the rims' other halves as creases.
    const core::Mesh cylinder = closed_cylinder(96);
    const test::View view{.eye = {0.0, 2.5, 4.0}};
    for (const bool creases : {true, false}) {
        double length[2] = {0.0, 0.0};
        for (const core::ContourMode contour : {core::ContourMode::kMesh, core::ContourMode::kSmooth}) {
            core::Scene scene = test::scene_for(view, cylinder);
            scene.lines.contour = contour;
            scene.lines.crease = creases;
            core::MeshFrames meshes(cylinder);
            core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
            const core::FrameResult r = pipeline.run(scene.first_frame);
            size_t outline = 0, crease = 0;
            for (const core::Stroke& stroke : r.strokes.strokes) {
                if (!stroke.drawn) continue;
                const core::LineKind kind = stroke.geometry.kind;
                if (kind == core::LineKind::kSilhouette) {
                    ++outline;
                    length[contour == core::ContourMode::kSmooth] += stroke.geometry.length_px();
                    if (contour == core::ContourMode::kSmooth) {
                        EXPECT_TRUE(stroke.geometry.closed);
                    }
                }
                crease += kind == core::LineKind::kCrease;
            }
            if (contour == core::ContourMode::kSmooth) {
                EXPECT_EQ(outline, 1u) << "creases " << creases;
                EXPECT_EQ(crease, creases ? 1u : 0u) << "the top rim's front";
            }
        }
        EXPECT_GT(length[0], 1000.0);
        EXPECT_NEAR(length[1], length[0], 0.01 * length[0]) << "creases " << creases;
    }
}

TEST(SmoothContours, APointIsNotHiddenByTheFacesAroundIt) {
    // A coarse sphere's smooth contour crosses faces that the mesh calls back-facing, behind
    // their front-facing neighbours: still the whole contour is visible, and one stroke.
    for (const int levels : {1, 2, 3}) {
        const core::Mesh sphere = test::icosphere(levels);
        const core::FrameResult r = render(sphere, {}, core::VisibilityMode::kExact);
        double total = 0.0;
        for (const core::Polyline& line : r.lines.polylines) total += line.length_px();
        for (const core::Polyline& line : r.lines.occluded) total += line.length_px();
        EXPECT_NEAR(visible_length(r.lines), total, 1e-9 * total) << levels;
        ASSERT_EQ(r.strokes.strokes.size(), 1u) << levels;
        EXPECT_TRUE(r.strokes.strokes[0].geometry.closed);
        EXPECT_EQ(r.lines.polylines[0].faces.size(), r.lines.polylines[0].edges.size());
    }
}

TEST(SmoothContours, RaycastAgreesWithExact) {
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree";
    // A torus from above at an angle: the inner contour is partly hidden behind the tube.
    const core::Mesh torus = test::torus(1.0, 0.35, 96, 48);
    for (const glm::dvec3 eye : {glm::dvec3(0.0, 2.0, 3.5), glm::dvec3(1.0, 1.0, 3.0), glm::dvec3(0.3, 0.6, 4.0)}) {
        const core::FrameResult exact = render(torus, {.eye = eye}, core::VisibilityMode::kExact);
        const core::FrameResult raycast = render(torus, {.eye = eye}, core::VisibilityMode::kRaycast);
        const double e = visible_length(exact.lines), c = visible_length(raycast.lines);
        ASSERT_GT(e, 0.0);
        EXPECT_NEAR(c, e, 0.005 * e) << eye.x << " " << eye.y << " " << eye.z;
    }
}

TEST(SmoothContours, FewerStrokesThanMeshEdgesOnACoarseTorus) {
    // Seen at an angle, a coarse torus's edge silhouette zig-zags and breaks; the smooth
    // contour draws each visible piece as one stroke.
    const core::Mesh torus = test::torus(1.0, 0.35, 48, 24);
    const test::View view{.eye = {0.0, 3.0, 6.0}};
    const core::FrameResult smooth = render(torus, view, core::VisibilityMode::kExact);
    const core::FrameResult mesh = render(torus, view, core::VisibilityMode::kExact, core::ContourMode::kMesh);
    size_t smooth_drawn = 0, mesh_drawn = 0;
    for (const core::Stroke& s : smooth.strokes.strokes) smooth_drawn += s.drawn;
    for (const core::Stroke& s : mesh.strokes.strokes) mesh_drawn += s.drawn;
    EXPECT_LE(smooth_drawn, 3u) << "the outer loop and the inner contour's two visible arcs";
    EXPECT_LE(smooth_drawn, mesh_drawn);
    EXPECT_NEAR(visible_length(smooth.lines), visible_length(mesh.lines), 0.05 * visible_length(mesh.lines));
}

TEST(SmoothContours, StrokesKnowTheFaceEachSegmentCrosses) {
    const core::Mesh torus = test::torus(1.0, 0.35, 48, 24);
    const core::EdgeTable table = core::build_edge_table(torus);
    const core::FrameResult r = render(torus, {.eye = {0.0, 3.0, 6.0}}, core::VisibilityMode::kExact);
    // The lines carry the tracer's faces; recovered from their points and edges they agree.
    size_t segments = 0;
    for (const core::Polyline& line : r.lines.polylines) {
        ASSERT_EQ(line.faces.size(), line.edges.size());
        // Scene and object space are one here (no object transform).
        EXPECT_EQ(core::faces_crossed(torus, table, line.points_world, line.edges), line.faces);
        segments += line.faces.size();
    }
    EXPECT_GT(segments, 100u);
    ASSERT_FALSE(r.strokes.strokes.empty());
    for (const core::Stroke& s : r.strokes.strokes) {
        ASSERT_EQ(s.faces.size(), s.geometry.edges.size());
        for (size_t i = 0; i < s.faces.size(); ++i) {
            const auto faces = table.faces_of(s.geometry.edges[i]);
            EXPECT_NE(std::find(faces.begin(), faces.end(), s.faces[i]), faces.end()) << "stroke " << s.id << " segment " << i;
        }
    }
}

}  // namespace
}  // namespace inkline
