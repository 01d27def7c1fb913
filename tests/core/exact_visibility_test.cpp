// SPDX-License-Identifier: MIT
// Visible feature lines of analytic shapes against their known answers.
#include "core/visibility/exact_visibility.h"

#include "core/mesh/topology.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace inkline {
namespace {

using core::LineKind;

// Every point of every visible stroke, resampled at most `step` px apart.
std::vector<glm::dvec2> resample(const core::FrameLines& frame, double step) {
    std::vector<glm::dvec2> out;
    for (const core::Polyline& line : frame.polylines) {
        if (!line.visible) continue;
        for (size_t i = 0; i + 1 < line.points_px.size(); ++i) {
            const glm::dvec2 a = line.points_px[i], b = line.points_px[i + 1];
            const int n = std::max(1, int(std::ceil(glm::length(b - a) / step)));
            for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (double(k) / n));
        }
        out.push_back(line.points_px.back());
    }
    return out;
}

TEST(ExactVisibility, SphereSilhouetteIsTheAnalyticCircle) {
    const core::Mesh sphere = test::uv_sphere(64, 32, 1.0);
    const test::View view{.eye = {0.0, 0.0, 4.0}, .fov_y_deg = 35.0, .size = 1024};
    const core::FrameLines frame = test::trace(sphere, view);

    // The silhouette cone has half-angle asin(1/d); its image is a circle about the centre.
    const double d = 4.0;
    const double expected_px = std::tan(std::asin(1.0 / d)) / std::tan(glm::radians(35.0 / 2.0)) * 512.0;
    const std::vector<glm::dvec2> points = resample(frame, 0.5);
    ASSERT_GT(points.size(), 1000u);
    double error_sum = 0.0;
    for (const glm::dvec2& p : points) error_sum += std::abs(glm::length(p - glm::dvec2(512.0)) - expected_px);
    EXPECT_LT(error_sum / double(points.size()), 0.5);

    double length = 0.0;
    for (const core::Polyline& line : frame.polylines) {
        EXPECT_EQ(line.kind, LineKind::kSilhouette) << "no crease or boundary on a smooth sphere";
        EXPECT_TRUE(line.visible);
        length += line.length_px();
    }
    EXPECT_NEAR(length, 2.0 * M_PI * expected_px, 0.01 * 2.0 * M_PI * expected_px);
}

TEST(ExactVisibility, CubeShowsExactlyTheEdgesOfItsThreeFrontFaces) {
    const core::Mesh cube = test::cube(1.0);
    const core::EdgeTable table = core::build_edge_table(cube);
    core::LineOptions lines;
    lines.hidden = true;
    const core::FrameLines frame = test::trace(cube, {.eye = {3.0, 2.5, 4.0}, .fov_y_deg = 40.0}, lines);

    // The camera sees the +x, +y and +z faces. Cube vertex i has coordinate bits (x, y, z).
    auto on_front_face = [](glm::uvec2 e) {
        for (unsigned bit : {1u, 2u, 4u}) {
            if ((e.x & bit) && (e.y & bit)) return true;
        }
        return false;
    };
    std::set<uint32_t> visible, hidden;
    for (const core::Polyline& line : frame.polylines) {
        EXPECT_NE(line.kind, LineKind::kBoundary);
        for (uint32_t e : line.edges) (line.visible ? visible : hidden).insert(e);
    }
    std::set<uint32_t> expected_visible, expected_hidden;
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        const glm::uvec2 v = table.edge_vertices[e];
        if (std::popcount(v.x ^ v.y) != 1) continue;  // a diagonal inside a face
        (on_front_face(v) ? expected_visible : expected_hidden).insert(e);
    }
    EXPECT_EQ(expected_visible.size(), 9u);
    EXPECT_EQ(visible, expected_visible);
    EXPECT_EQ(hidden, expected_hidden);
    // 6 outline edges are silhouettes; the 6 others are creases.
    EXPECT_EQ(frame.stats.feature_edges[size_t(LineKind::kSilhouette)], 6u);
    EXPECT_EQ(frame.stats.feature_edges[size_t(LineKind::kCrease)], 6u);
}

TEST(ExactVisibility, CubeHasTwelveCreases) {
    core::LineOptions lines;
    lines.silhouette = false;
    const core::FrameLines frame = test::trace(test::cube(1.0), {.eye = {3.0, 2.5, 4.0}}, lines);
    EXPECT_EQ(frame.stats.feature_edges[size_t(LineKind::kCrease)], 12u);
}

// Independent oracle: Moller-Trumbore against every triangle, same definition of occlusion.
bool occluded_brute(const core::Mesh& mesh, const core::EdgeTable& table, const glm::dvec3& eye,
                    const glm::dvec3& p, uint32_t edge) {
    const auto own = table.faces_of(edge);
    const glm::dvec3 dir = p - eye;
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (std::find(own.begin(), own.end(), f) != own.end()) continue;
        const glm::uvec3 t = mesh.triangles[f];
        const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
        const glm::dvec3 e1 = b - a, e2 = c - a, h = glm::cross(dir, e2);
        const double det = glm::dot(e1, h);
        if (std::abs(det) < 1e-14) continue;
        const glm::dvec3 s = eye - a;
        const double u = glm::dot(s, h) / det;
        if (u < 0.0 || u > 1.0) continue;
        const glm::dvec3 q = glm::cross(s, e1);
        const double v = glm::dot(dir, q) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        const double t_hit = glm::dot(e2, q) / det;
        if (t_hit > 0.0 && t_hit < 1.0 - 1e-6) return true;
    }
    return false;
}

TEST(ExactVisibility, TorusVisibleLengthMatchesDenseRayCast) {
    const core::Mesh torus = test::torus(1.0, 0.35, 48, 24);
    const core::EdgeTable table = core::build_edge_table(torus);
    const test::View view{.eye = {0.0, 2.2, 3.2}, .fov_y_deg = 40.0, .size = 1024};
    core::LineOptions lines;
    lines.hidden = true;
    const core::FrameLines frame = test::trace(torus, view, lines);

    double visible = 0.0, hidden = 0.0;
    for (const core::Polyline& line : frame.polylines) (line.visible ? visible : hidden) += line.length_px();
    EXPECT_GT(hidden, 50.0) << "the inner silhouette is partly occluded from this view";

    // Dense oracle over the same feature chains: midpoints of 0.5 px steps.
    const core::Camera camera = test::camera_for(view, torus);
    const core::Projection projection(camera, {view.size, view.size}, glm::dmat4(1.0));
    double oracle = 0.0;
    for (const core::Chain& chain : test::feature_chains(torus, view, lines)) {
        for (size_t s = 0; s < chain.edges.size(); ++s) {
            const glm::dvec3 a(torus.positions[chain.vertices[s]]), b(torus.positions[chain.vertices[s + 1]]);
            const double len = glm::length(projection.pixel(b) - projection.pixel(a));
            const int n = std::max(1, int(std::ceil(len / 0.5)));
            for (int k = 0; k < n; ++k) {
                const glm::dvec3 p0 = a + (b - a) * (double(k) / n), p1 = a + (b - a) * (double(k + 1) / n);
                const glm::dvec3 mid = 0.5 * (p0 + p1);
                if (!projection.inside_image(projection.pixel(mid))) continue;
                if (!occluded_brute(torus, table, view.eye, mid, chain.edges[s]))
                    oracle += glm::length(projection.pixel(p1) - projection.pixel(p0));
            }
        }
    }
    ASSERT_GT(oracle, 1000.0);
    EXPECT_NEAR(visible, oracle, 0.01 * oracle);
}

TEST(ExactVisibility, OwnFacesNeverOccludeTheirEdge) {
    // A single triangle: all three boundary edges are fully visible from either side.
    core::Mesh tri;
    tri.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    tri.triangles = {{0, 1, 2}};
    for (double z : {4.0, -4.0}) {
        const core::FrameLines frame = test::trace(tri, {.eye = {0.3, 0.2, z}});
        ASSERT_EQ(frame.polylines.size(), 1u);
        EXPECT_TRUE(frame.polylines[0].closed);
        EXPECT_EQ(frame.polylines[0].edges.size(), 3u);
    }
}

TEST(ExactVisibility, PartsOutsideTheImageAreClipped) {
    // Camera close to a big grid: its boundary runs outside the image and is cut at the border.
    const core::Mesh g = test::grid(4, 2.0);
    const core::FrameLines frame = test::trace(g, {.eye = {0.0, 0.0, 3.0}, .fov_y_deg = 70.0, .size = 256});
    ASSERT_FALSE(frame.polylines.empty());
    for (const core::Polyline& line : frame.polylines) {
        for (const glm::dvec2& p : line.points_px) {
            EXPECT_GE(p.x, -0.2);
            EXPECT_LE(p.x, 256.2);
            EXPECT_GE(p.y, -0.2);
            EXPECT_LE(p.y, 256.2);
        }
    }
}

}  // namespace
}  // namespace inkline
