// SPDX-License-Identifier: MIT
#include "core/lines/features.h"

#include "core/mesh/topology.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

namespace inkline {
namespace {

using core::LineKind;

TEST(Features, SphereSilhouetteSeparatesFrontFromBackFaces) {
    const core::Mesh sphere = test::uv_sphere(48, 24, 1.0);
    const core::EdgeTable table = core::build_edge_table(sphere);
    const glm::dvec3 eye(0.5, 1.0, 4.0);
    const core::FeatureEdges features = core::extract_feature_edges(sphere, table, eye, {});
    ASSERT_FALSE(features.edges.empty());
    EXPECT_EQ(features.edges_tested, table.edge_count());
    for (const core::FeatureEdge& fe : features.edges) {
        EXPECT_EQ(fe.kind, LineKind::kSilhouette);
        const auto faces = table.faces_of(fe.edge);
        EXPECT_NE(core::facing_value(sphere, faces[0], eye) > 0.0, core::facing_value(sphere, faces[1], eye) > 0.0);
    }
}

TEST(Features, BoundaryTakesPriorityOverSilhouetteAndCrease) {
    const core::Mesh g = test::grid(3, 1.0);
    const core::EdgeTable table = core::build_edge_table(g);
    const core::FeatureEdges features = core::extract_feature_edges(g, table, glm::dvec3{0.0, 0.0, 3.0}, {});
    EXPECT_EQ(features.count_by_kind()[size_t(LineKind::kBoundary)], 12u);
    EXPECT_EQ(features.edges.size(), 12u) << "a flat grid has no silhouette or crease inside";
}

TEST(Features, DisabledKindsAreNotReported) {
    const core::Mesh cube = test::cube(1.0);
    const core::EdgeTable table = core::build_edge_table(cube);
    core::LineOptions lines;
    lines.crease = false;
    const auto counts = core::extract_feature_edges(cube, table, glm::dvec3{3, 2.5, 4}, lines).count_by_kind();
    EXPECT_EQ(counts[size_t(LineKind::kCrease)], 0u);
    EXPECT_EQ(counts[size_t(LineKind::kSilhouette)], 6u);
}

TEST(Features, CreaseAngleThreshold) {
    // Two triangles folded by 90 degrees: a crease at 60, none at 100.
    core::Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}, {0, 3, 1}};
    const core::EdgeTable table = core::build_edge_table(m);
    const auto faces = table.faces_of(0);
    ASSERT_EQ(faces.size(), 2u);
    EXPECT_TRUE(core::is_crease(m, faces[0], faces[1], std::cos(60.0 * M_PI / 180.0)));
    EXPECT_FALSE(core::is_crease(m, faces[0], faces[1], std::cos(100.0 * M_PI / 180.0)));
}

}  // namespace
}  // namespace inkline
