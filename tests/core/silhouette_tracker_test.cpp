// SPDX-License-Identifier: MIT
#include "core/lines/silhouette_tracker.h"

#include "core/lines/features.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/scene/camera.h"
#include "core/scene/scene.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>

namespace inkline {
namespace {

using core::FeatureEdges;
using core::LineKind;

constexpr double kPi = std::numbers::pi;

// Empty when equal, else where the two edge lists first differ.
std::string difference(const FeatureEdges& brute, const FeatureEdges& tracked) {
    const size_t n = std::min(brute.edges.size(), tracked.edges.size());
    for (size_t i = 0; i < n; ++i) {
        const core::FeatureEdge a = brute.edges[i], b = tracked.edges[i];
        if (a.edge != b.edge || a.kind != b.kind) {
            std::ostringstream out;
            out << "at #" << i << ": brute edge " << a.edge << " " << core::line_kind_name(a.kind) << ", tracker edge "
                << b.edge << " " << core::line_kind_name(b.kind);
            return out.str();
        }
    }
    if (brute.edges.size() == tracked.edges.size()) return {};
    return "brute has " + std::to_string(brute.edges.size()) + " edges, tracker " +
           std::to_string(tracked.edges.size());
}

struct RunTotals {
    size_t frames = 0;
    size_t mismatched_frames = 0;
    size_t edges_tested = 0;  // frames after the first
    size_t edges = 0;         // frames after the first, times the edge count
    size_t kept = 0, walked = 0, proven = 0;
    size_t max_silhouette_edges = 0;
};

using MeshAt = std::function<const core::Mesh&(int frame)>;
using EyeAt = std::function<core::Viewpoint(int frame)>;

// Runs the tracker over frames [0, frames) and compares every frame with brute force.
RunTotals run_against_brute(core::SilhouetteTracker& tracker, const core::EdgeTable& table, int frames,
                            const MeshAt& mesh_at, const EyeAt& eye_at, const core::LineOptions& lines = {},
                            bool expect_equal = true) {
    RunTotals t;
    for (int frame = 0; frame < frames; ++frame) {
        const core::Mesh& mesh = mesh_at(frame);
        const core::Viewpoint eye = eye_at(frame);
        const FeatureEdges brute = core::extract_feature_edges(mesh, table, eye, lines);
        const FeatureEdges tracked = tracker.update(mesh, eye, lines);
        const std::string diff = difference(brute, tracked);
        if (expect_equal) {
            EXPECT_EQ(diff, "") << "frame " << frame;
        }
        ++t.frames;
        if (!diff.empty()) ++t.mismatched_frames;
        EXPECT_LE(tracked.edges_tested, table.edge_count());
        EXPECT_LE(tracked.faces_tested, mesh.triangles.size());
        if (frame > 0) {
            t.edges_tested += tracked.edges_tested;
            t.edges += table.edge_count();
        }
        const core::TrackerStats& s = tracker.stats();
        t.kept += s.kept;
        t.walked += s.walked;
        t.proven += s.proven;
        t.max_silhouette_edges = std::max(t.max_silhouette_edges, s.silhouette_edges);
    }
    return t;
}

// Both exact searches must give brute force's result.
constexpr core::TrackerSearch kExactSearches[] = {core::TrackerSearch::kHierarchy,
                                                  core::TrackerSearch::kWalkAndHierarchy};

const char* search_name(core::TrackerSearch search) {
    switch (search) {
        case core::TrackerSearch::kHierarchy: return "hierarchy";
        case core::TrackerSearch::kWalkAndHierarchy: return "walk and hierarchy";
        case core::TrackerSearch::kWalkOnly: return "walk only";
    }
    return "?";
}

// A point at `distance` from the origin, `degrees` around a tilted orbit.
glm::dvec3 orbit_eye(double degrees, double distance) {
    const double a = glm::radians(degrees);
    const glm::dvec3 flat(std::sin(a), 0.35 * std::cos(0.7 * a), std::cos(a));
    return distance * glm::normalize(flat);
}

// A UV sphere with Gaussian bumps of height `height` and width `width` (radians on the unit
// sphere) pushed out along the normal at `count` spread-out points.
core::Mesh bumpy_sphere(int segments, int rings, int count, double height, double width) {
    core::Mesh m = test::uv_sphere(segments, rings, 1.0);
    std::vector<glm::dvec3> centres;
    for (int k = 0; k < count; ++k) {
        // Fibonacci points: spread evenly, deterministic.
        const double y = 1.0 - 2.0 * (k + 0.5) / count;
        const double phi = k * kPi * (3.0 - std::sqrt(5.0));
        const double rho = std::sqrt(1.0 - y * y);
        centres.emplace_back(rho * std::cos(phi), y, rho * std::sin(phi));
    }
    for (glm::vec3& p : m.positions) {
        const glm::dvec3 dir = glm::normalize(glm::dvec3(p));
        double r = 1.0;
        for (const glm::dvec3& c : centres) {
            const double angle = std::acos(std::clamp(glm::dot(dir, c), -1.0, 1.0));
            r += height * std::exp(-(angle * angle) / (width * width));
        }
        p = glm::vec3(dir * r);
    }
    return m;
}

TEST(SilhouetteTracker, TorusTurntableSampleMatchesBruteEveryFrame) {
    const core::Scene scene = core::load_scene(std::string(INKLINE_SAMPLES) + "/torus/scene.json");
    core::MeshFrames meshes(scene.mesh, scene.first_frame);
    const core::EdgeTable& table = meshes.edges();
    auto eye_at = [&](int i) {
        const int frame = scene.first_frame + i;
        const glm::dmat4 world_from_object = core::world_from_object_at(scene, frame);
        const core::Bounds bounds = core::bounds_of(meshes.at(frame).positions);
        const core::Camera camera = core::camera_at(scene, frame, bounds);
        return core::Projection(camera, scene.image, world_from_object).eye_object();
    };
    const int frames = scene.last_frame - scene.first_frame + 1;
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker tracker(table, meshes.at(scene.first_frame), {.search = search});
        const RunTotals t = run_against_brute(
            tracker, table, frames, [&](int i) -> const core::Mesh& { return meshes.at(scene.first_frame + i); },
            eye_at, scene.lines);
        EXPECT_EQ(t.frames, 48u);
        EXPECT_EQ(t.mismatched_frames, 0u);
        EXPECT_LT(t.edges_tested, t.edges / 2) << "the tracker should test well under half the edges";
    }
}

TEST(SilhouetteTracker, FastOrbitAroundSphereMatchesBrute) {
    // 41 degrees a frame and a varying distance, down to just above the surface.
    const core::Mesh sphere = test::uv_sphere(96, 48, 1.0);
    const core::EdgeTable table = core::build_edge_table(sphere);
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker tracker(table, sphere, {.search = search});
        const RunTotals t = run_against_brute(
            tracker, table, 60, [&](int) -> const core::Mesh& { return sphere; },
            [](int i) { return orbit_eye(41.0 * i, 1.02 + 3.0 * (0.5 + 0.5 * std::sin(0.9 * i))); });
        EXPECT_EQ(t.mismatched_frames, 0u);
        EXPECT_LT(t.edges_tested, t.edges / 3);
    }
}

TEST(SilhouetteTracker, BumpsEnteringAndLeavingSilhouetteMatchBrute) {
    const core::Mesh mesh = bumpy_sphere(128, 64, 40, 0.06, 0.12);
    const core::EdgeTable table = core::build_edge_table(mesh);
    auto eye_at = [](int i) { return orbit_eye(3.0 * i, 3.5); };
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker tracker(table, mesh, {.search = search});
        const RunTotals t =
            run_against_brute(tracker, table, 120, [&](int) -> const core::Mesh& { return mesh; }, eye_at);
        EXPECT_EQ(t.mismatched_frames, 0u);
        EXPECT_LT(t.edges_tested, t.edges / 4);
        if (search == core::TrackerSearch::kWalkAndHierarchy) {
            EXPECT_GT(t.walked, 0u);
            EXPECT_GT(t.proven, 0u) << "bumps turning to the side should open loops the walk cannot reach";
        }
    }
}

TEST(SilhouetteTracker, WalkAloneLosesLinesThatTheHierarchyFinds) {
    // The walk alone (kWalkOnly) misses loops that open away from last frame's
    // silhouette; this is the failure the cone hierarchy exists to prevent.
    const core::Mesh mesh = bumpy_sphere(128, 64, 40, 0.06, 0.12);
    const core::EdgeTable table = core::build_edge_table(mesh);
    core::SilhouetteTracker walk_only(table, mesh, {.search = core::TrackerSearch::kWalkOnly});
    auto eye_at = [](int i) { return orbit_eye(3.0 * i, 3.5); };
    const RunTotals t = run_against_brute(
        walk_only, table, 60, [&](int) -> const core::Mesh& { return mesh; }, eye_at, {}, false);
    EXPECT_GT(t.mismatched_frames, 0u);
}

TEST(SilhouetteTracker, OpenMeshSeenFromBothSidesMatchesBrute) {
    // A hemisphere orbited so that the eye passes below its rim and sees the inside.
    const core::Mesh mesh = test::hemisphere(96, 48, 1.0);
    const core::EdgeTable table = core::build_edge_table(mesh);
    auto eye_at = [](int i) {
        const double a = glm::radians(7.0 * i);
        return glm::dvec3(3.0 * std::sin(a), 2.5 * std::sin(0.37 * i), 3.0 * std::cos(a));
    };
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker tracker(table, mesh, {.search = search});
        const RunTotals t =
            run_against_brute(tracker, table, 90, [&](int) -> const core::Mesh& { return mesh; }, eye_at);
        EXPECT_EQ(t.mismatched_frames, 0u);
        EXPECT_GT(t.max_silhouette_edges, 0u);
    }
}

TEST(SilhouetteTracker, DeformingSequenceMatchesBrute) {
    // A torus whose tube swells and twists over time: same topology, new positions each frame.
    const std::vector<core::Mesh> frames = test::swelling_torus(40);
    const core::EdgeTable table = core::build_edge_table(frames[0]);
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker tracker(table, frames[0], {.deforming = true, .search = search});
        const RunTotals t = run_against_brute(
            tracker, table, int(frames.size()), [&](int i) -> const core::Mesh& { return frames[size_t(i)]; },
            [](int i) { return orbit_eye(5.0 * i, 4.0); });
        EXPECT_EQ(t.mismatched_frames, 0u);
        EXPECT_LT(t.edges_tested, t.edges);
    }
}

TEST(SilhouetteTracker, CameraCutMatchesBruteWithAndWithoutReset) {
    const core::Mesh mesh = bumpy_sphere(96, 48, 24, 0.08, 0.15);
    const core::EdgeTable table = core::build_edge_table(mesh);
    auto eye_at = [](int i) {
        // A slow orbit, then a cut to an unrelated close view below, then a slow orbit there.
        return i < 20 ? orbit_eye(2.0 * i, 4.0) : glm::dvec3(0.4, -1.8, 0.9) + 0.01 * double(i - 20);
    };
    const MeshAt same = [&](int) -> const core::Mesh& { return mesh; };
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker no_reset(table, mesh, {.search = search});
        EXPECT_EQ(run_against_brute(no_reset, table, 40, same, eye_at).mismatched_frames, 0u);
    }

    core::SilhouetteTracker with_reset(table, mesh);
    const core::LineOptions lines;
    for (int i = 0; i < 40; ++i) {
        if (i == 20) with_reset.reset();
        const FeatureEdges tracked = with_reset.update(mesh, eye_at(i), lines);
        EXPECT_EQ(with_reset.stats().full_pass, i == 0 || i == 20) << "frame " << i;
        EXPECT_EQ(difference(core::extract_feature_edges(mesh, table, eye_at(i), lines), tracked), "")
            << "frame " << i;
    }
}

TEST(SilhouetteTracker, LineOptionsAndCreaseAngleChangesMatchBrute) {
    // A faceted bumpy sphere has creases; switch kinds and the crease angle between frames.
    const core::Mesh mesh = bumpy_sphere(24, 12, 12, 0.2, 0.3);
    const core::EdgeTable table = core::build_edge_table(mesh);
    for (const bool deforming : {false, true}) {
        core::SilhouetteTracker tracker(table, mesh, {.deforming = deforming});
        for (int i = 0; i < 30; ++i) {
            core::LineOptions lines;
            lines.crease_angle_deg = i < 10 ? 60.0 : i < 20 ? 20.0 : 8.0;
            lines.silhouette = i % 7 != 3;
            lines.crease = i % 5 != 2;
            const glm::dvec3 eye = orbit_eye(9.0 * i, 3.0);
            const FeatureEdges brute = core::extract_feature_edges(mesh, table, eye, lines);
            EXPECT_EQ(difference(brute, tracker.update(mesh, eye, lines)), "") << "frame " << i;
            if (i == 25) {
                EXPECT_GT(brute.count_by_kind()[size_t(LineKind::kCrease)], 0u);
            }
        }
    }
}

TEST(SilhouetteTracker, DegenerateAndNonManifoldFacesMatchBrute) {
    // A grid folded into a ridge, plus a zero-area face and a fin sharing an edge with two faces.
    core::Mesh mesh = test::grid(12, 1.0);
    for (glm::vec3& p : mesh.positions) p.z = 0.6f * std::abs(p.x) - 0.3f * p.y * p.y;
    const uint32_t a = mesh.triangles[40].x, b = mesh.triangles[40].y;
    const uint32_t top = uint32_t(mesh.positions.size());
    mesh.positions.push_back(mesh.positions[a] + glm::vec3(0.0f, 0.0f, 0.5f));
    mesh.triangles.emplace_back(a, b, top);  // fin: its base edge now has three faces
    mesh.triangles.emplace_back(a, b, a);    // degenerate
    const core::EdgeTable table = core::build_edge_table(mesh);
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker tracker(table, mesh, {.search = search});
        const RunTotals t = run_against_brute(
            tracker, table, 40, [&](int) -> const core::Mesh& { return mesh; },
            [](int i) { return orbit_eye(11.0 * i, 2.5); });
        EXPECT_EQ(t.mismatched_frames, 0u);
    }
}

}  // namespace
}  // namespace inkline

namespace inkline {
namespace {

TEST(SilhouetteTracker, StarConeWithThousandsOfSilhouettesAtItsApexMatchesBrute) {
    // A cone over a star of 4000 points (radii 1 and 0.8 in turn), seen from near its axis:
    // about every other spoke is a silhouette, all through the apex, which the walk then visits
    // from each of them.
    constexpr uint32_t kPoints = 4000;
    core::Mesh star;
    star.positions = {{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    for (uint32_t i = 0; i < kPoints; ++i) {
        const double a = 2.0 * std::numbers::pi * double(i) / kPoints, r = i % 2 ? 0.8 : 1.0;
        star.positions.push_back({float(r * std::cos(a)), 0.0f, float(r * std::sin(a))});
    }
    for (uint32_t i = 0; i < kPoints; ++i) {
        const uint32_t a = 2 + i, b = 2 + (i + 1) % kPoints;
        star.triangles.push_back({0, b, a});
        star.triangles.push_back({1, a, b});
    }
    const core::EdgeTable table = core::build_edge_table(star);
    for (const core::TrackerSearch search : kExactSearches) {
        SCOPED_TRACE(search_name(search));
        core::SilhouetteTracker tracker(table, star, {.search = search});
        const RunTotals t = run_against_brute(
            tracker, table, 24, [&](int) -> const core::Mesh& { return star; },
            [](int i) { return glm::dvec3(0.3 * std::cos(0.5 * i), 6.0, 0.3 * std::sin(0.5 * i)); });
        EXPECT_EQ(t.mismatched_frames, 0u);
    }
}

}  // namespace
}  // namespace inkline
