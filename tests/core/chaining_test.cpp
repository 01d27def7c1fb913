// SPDX-License-Identifier: MIT
#include "core/chaining.h"

#include "core/features.h"
#include "core/topology.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <map>

namespace inkline {
namespace {

struct Case {
    const char* name;
    core::Mesh mesh;
    glm::dvec3 eye;
};

std::vector<Case> cases() {
    return {{"sphere", test::uv_sphere(32, 16, 1.0), {0.3, 1.0, 4.0}},
            {"torus", test::torus(1.0, 0.35, 40, 20), {0.0, 2.0, 3.0}},
            {"cube", test::cube(1.0), {3.0, 2.5, 4.0}},
            {"hemisphere", test::hemisphere(32, 16, 1.0), {1.0, 3.0, 2.0}},
            {"grid", test::grid(6, 1.0), {0.5, 0.5, 3.0}}};
}

TEST(Chaining, EveryFeatureEdgeUsedOnce) {
    for (const Case& c : cases()) {
        const core::EdgeTable table = core::build_edge_table(c.mesh);
        const core::FeatureEdges features = core::extract_feature_edges(c.mesh, table, c.eye, {});
        std::map<uint32_t, int> uses;
        for (const core::Chain& chain : core::chain_feature_edges(features, table)) {
            ASSERT_EQ(chain.edges.size() + 1, chain.vertices.size()) << c.name;
            for (size_t i = 0; i < chain.edges.size(); ++i) {
                ++uses[chain.edges[i]];
                // Consecutive vertices are the ends of the segment's edge.
                const glm::uvec2 ev = table.edge_vertices[chain.edges[i]];
                const uint32_t a = chain.vertices[i], b = chain.vertices[i + 1];
                EXPECT_TRUE((ev.x == a && ev.y == b) || (ev.x == b && ev.y == a)) << c.name;
            }
        }
        EXPECT_EQ(uses.size(), features.edges.size()) << c.name;
        for (const auto& [edge, n] : uses) EXPECT_EQ(n, 1) << c.name << " edge " << edge;
    }
}

TEST(Chaining, OpenMeshBoundaryIsOneClosedLoop) {
    for (const core::Mesh& mesh : {test::hemisphere(32, 16, 1.0), test::grid(5, 1.0)}) {
        const core::EdgeTable table = core::build_edge_table(mesh);
        core::LineOptions lines;
        lines.silhouette = lines.crease = false;
        const auto features = core::extract_feature_edges(mesh, table, {0.0, 3.0, 3.0}, lines);
        const auto chains = core::chain_feature_edges(features, table);
        ASSERT_EQ(chains.size(), 1u);
        EXPECT_TRUE(chains[0].closed);
        EXPECT_EQ(chains[0].kind, core::LineKind::kBoundary);
        EXPECT_EQ(chains[0].vertices.front(), chains[0].vertices.back());
    }
    const core::Mesh hemi = test::hemisphere(32, 16, 1.0);
    const core::EdgeTable table = core::build_edge_table(hemi);
    core::LineOptions lines;
    lines.silhouette = lines.crease = false;
    EXPECT_EQ(core::chain_feature_edges(core::extract_feature_edges(hemi, table, {0, 3, 3}, lines), table)[0].edges.size(), 32u);
}

TEST(Chaining, SplitsWhereThreeEdgesMeet) {
    // Three triangles fanned around one shared edge: that edge is non-manifold (boundary), and
    // its end vertices each meet more than two boundary edges, so chains end there.
    core::Mesh m;
    m.positions = {{0, 0, 0}, {0, 1, 0}, {1, 0.5f, 0}, {-1, 0.5f, 0}, {0, 0.5f, 1}};
    m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    const core::EdgeTable table = core::build_edge_table(m);
    const auto features = core::extract_feature_edges(m, table, {0.2, 0.3, 3.0}, {});
    const auto chains = core::chain_feature_edges(features, table);
    for (const core::Chain& chain : chains) {
        EXPECT_FALSE(chain.closed);
        for (size_t i = 1; i + 1 < chain.vertices.size(); ++i) {
            EXPECT_NE(chain.vertices[i], 0u);
            EXPECT_NE(chain.vertices[i], 1u);
        }
    }
}

}  // namespace
}  // namespace inkline
