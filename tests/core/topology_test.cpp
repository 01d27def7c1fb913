// SPDX-License-Identifier: MIT
#include "core/mesh/topology.h"

#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace inkline {
namespace {

TEST(Topology, ClosedShapesHaveNoBoundary) {
    for (const core::Mesh& mesh : {test::cube(1.0), test::uv_sphere(16, 8, 1.0), test::torus(1.0, 0.3, 12, 8)}) {
        const core::EdgeTable table = core::build_edge_table(mesh);
        const core::MeshReport r = core::describe_mesh(mesh, table);
        EXPECT_EQ(r.edges * 2, r.faces * 3) << "closed triangle mesh: E = 3F/2";
        EXPECT_EQ(r.boundary_edges, 0u);
        EXPECT_EQ(r.non_manifold_edges, 0u);
        EXPECT_EQ(r.inconsistent_edges, 0u);
        EXPECT_EQ(r.connected_components, 1u);
        EXPECT_EQ(r.degenerate_faces, 0u);
    }
}

TEST(Topology, EdgesAreSortedAndAdjacencyIsConsistent) {
    const core::Mesh mesh = test::torus(1.0, 0.3, 10, 6);
    const core::EdgeTable t = core::build_edge_table(mesh);
    const std::vector<glm::uvec3> face_edges = core::face_edges(mesh, t);
    for (uint32_t e = 0; e < t.edge_count(); ++e) {
        EXPECT_LT(t.edge_vertices[e].x, t.edge_vertices[e].y);
        EXPECT_EQ(core::find_edge(t, t.edge_vertices[e].y, t.edge_vertices[e].x), e);
        if (e > 0) {
            const auto prev = t.edge_vertices[e - 1], cur = t.edge_vertices[e];
            EXPECT_TRUE(prev.x < cur.x || (prev.x == cur.x && prev.y < cur.y));
        }
        for (uint32_t f : t.faces_of(e)) {
            const glm::uvec3 fe = face_edges[f];
            EXPECT_TRUE(fe.x == e || fe.y == e || fe.z == e);
        }
        for (uint32_t v : {t.edge_vertices[e].x, t.edge_vertices[e].y}) {
            const auto around = t.edges_around(v);
            EXPECT_NE(std::find(around.begin(), around.end(), e), around.end());
        }
    }
}

TEST(Topology, FanOfManyFacesAroundOneVertex_quadratic_bucket_sort) {
    // Every side at the apex lands in the apex's bucket; sorting that bucket by insertion takes
    // minutes when its sides arrive in descending order.
    constexpr uint32_t kSpokes = 100000;
    core::Mesh fan;
    fan.positions.push_back({0.0f, 0.0f, 0.0f});
    for (uint32_t i = 0; i < kSpokes; ++i) {
        const double a = 6.283185307179586 * double(i) / kSpokes;
        fan.positions.push_back({float(std::cos(a)), float(std::sin(a)), 1.0f});
    }
    // Listed clockwise from the last spoke, so that the apex's sides arrive in descending order.
    for (uint32_t i = kSpokes; i-- > 0;) fan.triangles.push_back({0, 1 + i, 1 + (i + 1) % kSpokes});
    const core::EdgeTable table = core::build_edge_table(fan);
    ASSERT_EQ(table.edge_count(), 2u * kSpokes);
    for (uint32_t e = 0; e < kSpokes; ++e) {  // the spokes (0, v) come first, each between two faces
        ASSERT_EQ(table.edge_vertices[e], glm::uvec2(0, e + 1));
        ASSERT_EQ(table.faces_of(e).size(), 2u);
    }
}

TEST(Topology, ReportsOddities) {
    core::Mesh m = test::grid(2, 1.0);  // 8 triangles, 16 edges, 8 on the boundary
    const size_t base_vertices = m.positions.size();
    m.triangles.push_back({0, 1, 1});  // repeated vertex: degenerate
    // A second component: a triangle fan of three faces around one edge (non-manifold).
    m.positions.insert(m.positions.end(), {{5, 0, 0}, {5, 1, 0}, {6, 0.5f, 0}, {4, 0.5f, 0}, {5, 0.5f, 1}});
    const auto v = [&](unsigned i) { return unsigned(base_vertices) + i; };
    m.triangles.push_back({v(0), v(1), v(2)});
    m.triangles.push_back({v(1), v(0), v(3)});
    m.triangles.push_back({v(0), v(1), v(4)});
    const core::EdgeTable table = core::build_edge_table(m);
    const core::MeshReport r = core::describe_mesh(m, table);
    EXPECT_EQ(r.degenerate_faces, 1u);
    EXPECT_EQ(r.non_manifold_edges, 1u);
    EXPECT_EQ(r.non_manifold_vertices, 2u) << "the two ends of the non-manifold edge";
    EXPECT_EQ(r.connected_components, 2u);
    EXPECT_EQ(r.boundary_edges, 8u + 6u);
    EXPECT_EQ(core::mesh_warnings(r).size(), 3u);
}

TEST(Topology, SheetsTouchingAtAVertexAreNonManifold) {
    // Two fans of four triangles around the origin, one above and one below, touching only there:
    // no edge has more than two faces, but the origin's faces form two fans.
    core::Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 1}, {0, 1, 1}, {-1, 0, 1}, {0, -1, 1}, {1, 0, -1}, {0, 1, -1}, {-1, 0, -1}, {0, -1, -1}};
    for (unsigned k = 0; k < 4; ++k) {
        m.triangles.push_back({0, 1 + k, 1 + (k + 1) % 4});
        m.triangles.push_back({0, 5 + (k + 1) % 4, 5 + k});
    }
    const core::EdgeTable table = core::build_edge_table(m);
    const core::MeshReport r = core::describe_mesh(m, table);
    EXPECT_EQ(r.non_manifold_edges, 0u);
    EXPECT_EQ(r.non_manifold_vertices, 1u);
    ASSERT_EQ(core::mesh_warnings(r).size(), 1u);
    EXPECT_NE(core::mesh_warnings(r)[0].find("1 non-manifold vertex"), std::string::npos);
    // A closed surface and an open grid have none: a boundary vertex's faces are one fan too.
    for (const core::Mesh& manifold : {test::cube(1.0), test::grid(3, 1.0)}) {
        EXPECT_EQ(core::describe_mesh(manifold, core::build_edge_table(manifold)).non_manifold_vertices, 0u);
    }
}

TEST(Topology, NonManifoldVerticesCountedOnMeshesWhereTheCountIsKnown) {
    // A closed cone of 200000 faces: its apex and base centre, each with 100000 faces, are one
    // fan each (the count is linear in the faces at a vertex, not quadratic).
    const core::Mesh cone = test::closed_cone(100000);
    core::MeshReport r = core::describe_mesh(cone, core::build_edge_table(cone));
    EXPECT_EQ(r.non_manifold_vertices, 0u);
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.connected_components, 1u);

    // Two such cones touching apex to apex (the second mirrored through the apex): one
    // non-manifold vertex, however many faces meet there.
    const core::Mesh two = test::twin_cones(5000);
    r = core::describe_mesh(two, core::build_edge_table(two));
    EXPECT_EQ(r.non_manifold_vertices, 1u);
    EXPECT_EQ(r.non_manifold_edges, 0u);
    EXPECT_EQ(r.connected_components, 2u) << "joined at the apex only, not along an edge";
    EXPECT_EQ(r.inconsistent_edges, 0u);

    // A fan of sheets around one edge of the cone: both ends of that edge become non-manifold.
    core::Mesh sheets = test::closed_cone(3000);
    for (int k = 0; k < 3; ++k) {
        sheets.positions.push_back({0.5f, 0.5f, float(k + 1)});
        sheets.triangles.push_back({0, 2, uint32_t(sheets.positions.size() - 1)});
    }
    r = core::describe_mesh(sheets, core::build_edge_table(sheets));
    EXPECT_EQ(r.non_manifold_edges, 1u);
    EXPECT_EQ(r.non_manifold_vertices, 2u);
}

TEST(Topology, WarningsScopeCountsAllButComponents) {
    // Large enough that the edge and vertex passes run on every core.
    const core::Mesh two = test::twin_cones(60000);
    const core::EdgeTable table = core::build_edge_table(two);
    const core::MeshReport all = core::describe_mesh(two, table);
    const core::MeshReport warnings = core::describe_mesh(two, table, core::MeshReportScope::kWarnings);
    EXPECT_EQ(all.connected_components, 2u);
    EXPECT_EQ(warnings.connected_components, 0u);
    EXPECT_EQ(warnings.non_manifold_vertices, all.non_manifold_vertices);
    EXPECT_EQ(warnings.non_manifold_edges, all.non_manifold_edges);
    EXPECT_EQ(warnings.boundary_edges, all.boundary_edges);
    EXPECT_EQ(warnings.inconsistent_edges, all.inconsistent_edges);
    EXPECT_EQ(core::mesh_warnings(warnings), core::mesh_warnings(all));
}

TEST(Topology, FindEdgeAtAVertexWithManyEdges) {
    // The apex of a cone has an edge to each of its 20000 ring vertices and none to the base
    // centre; a ring vertex has its two ring neighbours, the apex and the centre.
    constexpr uint32_t kSides = 20000;
    const core::Mesh cone = test::closed_cone(kSides);
    const core::EdgeTable table = core::build_edge_table(cone);
    for (uint32_t i = 0; i < kSides; ++i) {
        const uint32_t e = core::find_edge(table, 2 + i, 0);
        ASSERT_NE(e, core::kNoIndex) << i;
        ASSERT_EQ(table.edge_vertices[e], glm::uvec2(0, 2 + i));
        ASSERT_EQ(core::find_edge(table, 0, 2 + i), e);
        const uint32_t next = 2 + (i + 1) % kSides;
        const uint32_t ring = core::find_edge(table, 2 + i, next);
        ASSERT_NE(ring, core::kNoIndex);
        ASSERT_EQ(table.edge_vertices[ring], glm::uvec2(std::min(2 + i, next), std::max(2 + i, next)));
    }
    EXPECT_EQ(core::find_edge(table, 0, 1), core::kNoIndex);
    EXPECT_EQ(core::find_edge(table, 2, 4), core::kNoIndex);
    EXPECT_EQ(core::find_edge(table, 0, 0), core::kNoIndex);
    EXPECT_EQ(core::find_edge(table, 0, kSides + 2), core::kNoIndex) << "no such vertex";
    EXPECT_EQ(core::find_edge(table, kSides + 2, kSides + 9), core::kNoIndex) << "no such vertices";
    // Every face's edges, as face_edges finds them, join that face's corners.
    const std::vector<glm::uvec3> fe = core::face_edges(cone, table);
    for (size_t f = 0; f < fe.size(); ++f) {
        const glm::uvec3 t = cone.triangles[f];
        for (int c = 0; c < 3; ++c) {
            const glm::uvec2 v = table.edge_vertices[fe[f][c]];
            ASSERT_EQ(v, glm::uvec2(std::min(t[c], t[(c + 1) % 3]), std::max(t[c], t[(c + 1) % 3]))) << f;
        }
    }
}

TEST(Topology, DuplicateFacesAreIgnoredWithAWarning) {
    core::Mesh m = test::cube(1.0);
    m.triangles.push_back(m.triangles[3]);                                   // same order
    m.triangles.push_back({m.triangles[5].z, m.triangles[5].y, m.triangles[5].x});  // flipped copy
    const core::EdgeTable table = core::build_edge_table(m);
    const core::MeshReport r = core::describe_mesh(m, table);
    EXPECT_EQ(r.duplicate_faces, 2u);
    EXPECT_EQ(r.degenerate_faces, 0u);
    EXPECT_EQ(r.non_manifold_edges, 0u) << "the copies do not make edges non-manifold";
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(table.face_valid[12], 0);
    EXPECT_EQ(table.face_valid[13], 0);
    EXPECT_EQ(core::mesh_warnings(r).size(), 1u);
}

TEST(Topology, ManySheetsOnOneEdgeStayFast) {
    // 20000 triangles sharing edge (0, 1), each once and one of them twice: linear work per edge.
    core::Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}};
    for (int i = 0; i < 20000; ++i) {
        m.positions.emplace_back(0.5f, std::cos(i * 1e-4f), std::sin(i * 1e-4f));
        m.triangles.push_back({0, 1, unsigned(i + 2)});
    }
    m.triangles.push_back({1, 0, 7});
    const core::EdgeTable table = core::build_edge_table(m);
    EXPECT_EQ(table.duplicate_faces, 1u);
    EXPECT_EQ(table.face_valid.back(), 0);
}

TEST(Topology, DetectsInconsistentOrientation) {
    core::Mesh m = test::cube(1.0);
    std::swap(m.triangles[0].y, m.triangles[0].z);  // flip one face
    const core::MeshReport r = core::describe_mesh(m, core::build_edge_table(m));
    EXPECT_EQ(r.inconsistent_edges, 3u);
}

}  // namespace
}  // namespace inkline
