// SPDX-License-Identifier: MIT
#include "core/lines/chaining.h"

#include "core/lines/features.h"
#include "core/mesh/topology.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
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
        const auto features = core::extract_feature_edges(mesh, table, glm::dvec3{0.0, 3.0, 3.0}, lines);
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
    EXPECT_EQ(core::chain_feature_edges(core::extract_feature_edges(hemi, table, glm::dvec3{0, 3, 3}, lines), table)[0].edges.size(), 32u);
}

TEST(Chaining, SplitsWhereThreeEdgesMeet) {
    // Three triangles fanned around one shared edge: that edge is non-manifold (boundary), and
    // its end vertices each meet more than two boundary edges, so chains end there.
    core::Mesh m;
    m.positions = {{0, 0, 0}, {0, 1, 0}, {1, 0.5f, 0}, {-1, 0.5f, 0}, {0, 0.5f, 1}};
    m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    const core::EdgeTable table = core::build_edge_table(m);
    const auto features = core::extract_feature_edges(m, table, glm::dvec3{0.2, 0.3, 3.0}, {});
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

namespace inkline {
namespace {

TEST(Chaining, ThousandsOfFeatureEdgesAtOneVertexEachEndThere) {
    // Every spoke of a fan of 20000 faces marked a crease: 20000 creases meet at the apex, one at
    // each rim vertex, so every spoke is a chain of its own from the apex; the rim, marked a
    // boundary (another kind), is one closed chain through vertices where two of its edges meet.
    constexpr uint32_t kSpokes = 20000;
    core::Mesh fan;
    fan.positions.push_back({0.0f, 0.0f, 0.0f});
    for (uint32_t i = 0; i < kSpokes; ++i) {
        const double a = 6.283185307179586 * double(i) / kSpokes;
        fan.positions.push_back({float(std::cos(a)), float(std::sin(a)), 0.0f});
    }
    for (uint32_t i = 0; i < kSpokes; ++i) fan.triangles.push_back({0, 1 + i, 1 + (i + 1) % kSpokes});
    const core::EdgeTable table = core::build_edge_table(fan);
    core::FeatureEdges features;
    for (uint32_t e = 0; e < table.edge_count(); ++e) {
        features.edges.push_back({e, table.edge_vertices[e].x == 0 ? core::LineKind::kCrease : core::LineKind::kBoundary});
    }
    const std::vector<core::Chain> chains = core::chain_feature_edges(features, table);
    ASSERT_EQ(chains.size(), kSpokes + 1);
    size_t spokes = 0, loops = 0;
    for (const core::Chain& chain : chains) {
        if (chain.kind == core::LineKind::kCrease) {
            ++spokes;
            EXPECT_EQ(chain.edges.size(), 1u);
            EXPECT_EQ(chain.vertices.front(), 0u) << "chains start at the end where the count is not 2";
        } else {
            ++loops;
            EXPECT_TRUE(chain.closed);
            EXPECT_EQ(chain.edges.size(), kSpokes);
        }
    }
    EXPECT_EQ(spokes, kSpokes);
    EXPECT_EQ(loops, 1u);
}

}  // namespace
}  // namespace inkline
