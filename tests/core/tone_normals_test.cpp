// SPDX-License-Identifier: MIT
// The normals tone reads its light from (core/lines/smooth_pieces.h, core/tone/tone_normals.h):
// on a smooth surface they are the vertex normals, exactly; across a crease each side has its
// own, so that a box is shaded face by face, with stipples and with hatches, and a smooth part
// beside a crease stays round.
#include "core/lines/smooth_pieces.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/tone/tone.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace inkline {
namespace {

core::VisibilityMode raycast_or_exact() {
    return core::raycast_available() ? core::VisibilityMode::kRaycast : core::VisibilityMode::kExact;
}

core::SmoothPieces pieces_of(const core::Mesh& mesh, double crease_angle_deg) {
    const core::EdgeTable table = core::build_edge_table(mesh);
    core::SmoothPieces pieces;
    core::smooth_pieces(mesh, table, core::face_edges(mesh, table), crease_angle_deg, pieces);
    return pieces;
}

// The unit axis a cube face's normal lies along, as 0..5 (+x, -x, +y, -y, +z, -z).
int side_of(const core::Mesh& mesh, uint32_t face) {
    const glm::dvec3 n = glm::normalize(core::face_normal(mesh.positions, mesh.triangles[face]));
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(n[axis]) > 0.999) return 2 * axis + (n[axis] > 0.0 ? 0 : 1);
    }
    return -1;
}

// Smallest and largest of a value per cube side.
struct Range {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    size_t count = 0;
    void add(double v) { lo = std::min(lo, v), hi = std::max(hi, v), ++count; }
};

// A cube seen from a corner, lit so that its three visible sides take three different tones.
core::Scene box_scene(const core::Mesh& mesh, core::ToneMode mode, double crease_angle_deg,
                      std::optional<double> tone_crease_angle_deg = {}) {
    core::Scene scene = test::scene_for({.eye = {3.0, 2.4, 3.6}, .size = 384, .ortho_height = 3.2}, mesh);
    scene.light = {.direction = glm::normalize(glm::dvec3(-0.3, -1.0, -0.55))};
    scene.lines.silhouette = scene.lines.boundary = scene.lines.crease = scene.lines.intersection = false;
    scene.lines.crease_angle_deg = crease_angle_deg;
    scene.tone = {.mode = mode, .curve = {.min = 0.05, .max = 0.7}, .line_width_px = 1.0,
                  .direction = glm::normalize(glm::dvec3(1.0, 0.3, 0.5)),
                  .crease_angle_deg = tone_crease_angle_deg};
    return scene;
}

core::FrameResult first_frame(const core::Scene& scene, const core::Mesh& mesh) {
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(raycast_or_exact()));
    return pipeline.run(scene.first_frame);
}

TEST(SmoothPieces, OnASmoothSurfaceEachVertexIsOneGroupWithItsVertexNormal) {
    for (const core::Mesh& mesh : {test::torus(1.0, 0.35, 48, 24), test::uv_sphere(32, 16, 1.0)}) {
        const core::SmoothPieces pieces = pieces_of(mesh, 60.0);
        const std::vector<glm::dvec3> vertex = core::vertex_normals(mesh);
        ASSERT_EQ(pieces.normals.size(), mesh.positions.size());
        for (size_t g = 0; g < pieces.normals.size(); ++g) {
            ASSERT_EQ(pieces.normals[g], vertex[pieces.group_vertex[g]]) << "group " << g;  // bit for bit
        }
        for (size_t f = 0; f < mesh.triangles.size(); ++f) {
            for (int c = 0; c < 3; ++c) ASSERT_EQ(pieces.group_vertex[pieces.face_groups[f][c]], mesh.triangles[f][c]);
            ASSERT_EQ(pieces.joined[f], 7u);
        }
    }
}

TEST(SmoothPieces, ACubesCornersSplitIntoOneFlatGroupPerSide) {
    const core::Mesh cube = test::cube(1.0);
    const core::SmoothPieces pieces = pieces_of(cube, 60.0);
    EXPECT_EQ(pieces.normals.size(), 24u);  // 8 corners, 3 sides each
    for (uint32_t f = 0; f < cube.triangles.size(); ++f) {
        const glm::dvec3 n = glm::normalize(core::face_normal(cube.positions, cube.triangles[f]));
        for (int c = 0; c < 3; ++c) EXPECT_LT(glm::distance(pieces.normals[pieces.face_groups[f][c]], n), 1e-12);
        // Only the side's diagonal joins.
        EXPECT_EQ(std::popcount(pieces.joined[f]), 1) << "face " << f;
    }
    // At 180 degrees nothing is a crease: one group per vertex, with its vertex normal.
    const core::SmoothPieces round = pieces_of(cube, 180.0);
    const std::vector<glm::dvec3> vertex = core::vertex_normals(cube);
    ASSERT_EQ(round.normals.size(), 8u);
    for (size_t g = 0; g < 8; ++g) EXPECT_EQ(round.normals[g], vertex[round.group_vertex[g]]);
}

// Every dot of a side has the side's tone: a box's sides are flat. Without creases (180 degrees)
// the normals bend round the corners and the tone runs across each side, as it did before tone
// read the smooth pieces.
TEST(ToneNormals, StipplesShadeABoxSideBySide) {
    const core::Mesh cube = test::cube(1.0);
    const auto tones = [&](double crease_angle_deg, std::optional<double> tone_crease_angle_deg = {}) {
        const core::FrameResult r =
            first_frame(box_scene(cube, core::ToneMode::kStipple, crease_angle_deg, tone_crease_angle_deg), cube);
        std::map<int, Range> per_side;
        for (const core::Dot& dot : r.tone.dots) per_side[side_of(cube, dot.face)].add(dot.tone);
        return per_side;
    };
    const std::map<int, Range> flat = tones(60.0);
    ASSERT_EQ(flat.size(), 3u);  // the three sides in view
    std::vector<double> side_tones;
    for (const auto& [side, range] : flat) {
        std::printf("side %d: %zu dots, tone %.6f to %.6f\n", side, range.count, range.lo, range.hi);
        EXPECT_GT(range.count, 50u);
        EXPECT_LT(range.hi - range.lo, 1e-9) << "side " << side;
        side_tones.push_back(range.lo);
    }
    std::sort(side_tones.begin(), side_tones.end());
    EXPECT_GT(side_tones[1] - side_tones[0], 0.05);
    EXPECT_GT(side_tones[2] - side_tones[1], 0.05);

    double widest = 0.0;
    for (const auto& [side, range] : tones(180.0)) widest = std::max(widest, range.hi - range.lo);
    std::printf("without creases: tone runs %.3f across a side\n", widest);
    EXPECT_GT(widest, 0.1);

    // tone.crease_angle_deg decides over the lines' angle, both ways.
    const auto spread = [](const std::map<int, Range>& per_side) {
        double most = 0.0;
        for (const auto& [side, range] : per_side) most = std::max(most, range.hi - range.lo);
        return most;
    };
    EXPECT_LT(spread(tones(180.0, 60.0)), 1e-9);
    EXPECT_EQ(spread(tones(60.0, 180.0)), widest);
}

// Hatch widths follow the tone and the level: under an orthographic camera a flat side of one
// tone draws each level's lines at one width wherever they cross the side's diagonal.
TEST(ToneNormals, HatchesShadeABoxSideBySide) {
    const core::Mesh cube = test::cube(1.0);
    const core::EdgeTable table = core::build_edge_table(cube);
    const auto widths = [&](double crease_angle_deg) {
        const core::FrameResult r = first_frame(box_scene(cube, core::ToneMode::kHatch, crease_angle_deg), cube);
        std::map<int, Range> per_side;
        for (const core::Hatch& hatch : r.tone.hatches) {
            for (size_t k = 0; k < hatch.edges.size(); ++k) {
                const std::span<const uint32_t> faces = table.faces_of(hatch.edges[k]);
                if (faces.size() != 2 || side_of(cube, faces[0]) != side_of(cube, faces[1])) continue;  // a crease
                per_side[8 * int(hatch.level) + side_of(cube, faces[0])].add(hatch.width_px[k]);
            }
        }
        return per_side;
    };
    const std::map<int, Range> flat = widths(60.0);
    std::set<int> sides;
    for (const auto& [key, range] : flat) {
        std::printf("side %d, level %d: %zu points on its diagonal, width %.6f to %.6f px\n", key % 8, key / 8,
                    range.count, range.lo, range.hi);
        sides.insert(key % 8);
        EXPECT_LT(range.hi - range.lo, 1e-6) << "side " << key % 8 << ", level " << key / 8;
    }
    EXPECT_EQ(sides.size(), 3u);
    double widest = 0.0;
    for (const auto& [side, range] : widths(180.0)) widest = std::max(widest, range.hi - range.lo);
    std::printf("without creases: width runs %.3f px along a side's diagonal\n", widest);
    EXPECT_GT(widest, 0.05);
}

// At 0 degrees every edge is a crease: each face is flat, one tone for all its dots.
TEST(ToneNormals, AtZeroDegreesEveryFaceIsFlat) {
    const core::Mesh torus = test::torus(1.0, 0.35, 24, 12);
    core::Scene scene = box_scene(torus, core::ToneMode::kStipple, 60.0, 0.0);
    const core::FrameResult r = first_frame(scene, torus);
    std::map<uint32_t, Range> per_face;
    for (const core::Dot& dot : r.tone.dots) per_face[dot.face].add(dot.tone);
    size_t faces = 0;
    for (const auto& [face, range] : per_face) {
        EXPECT_LT(range.hi - range.lo, 1e-9) << "face " << face;
        faces += range.count > 1 ? 1 : 0;
    }
    EXPECT_GT(faces, 50u);
}

// A cone's side stays round beside its flat base: each rim vertex has a normal for the side,
// bent round with the rim, and one for the base, the base's own.
TEST(SmoothPieces, AConesSideStaysRoundBesideItsFlatBase) {
    const uint32_t sides = 48;
    const core::Mesh cone = test::closed_cone(sides);  // apex 0, base centre 1, rim 2..
    const core::SmoothPieces pieces = pieces_of(cone, 60.0);
    ASSERT_EQ(pieces.normals.size(), 2u + 2u * sides);
    for (uint32_t f = 0; f < cone.triangles.size(); ++f) {
        const glm::uvec3 t = cone.triangles[f];
        const bool base = t.x == 1;
        for (int c = 0; c < 3; ++c) {
            const glm::dvec3& n = pieces.normals[pieces.face_groups[f][c]];
            if (base) {
                EXPECT_LT(glm::distance(n, glm::dvec3(0.0, -1.0, 0.0)), 1e-12);
            } else if (t[c] >= 2) {
                // The side's normal at a rim vertex: outward along the rim's radius, 45 degrees up.
                const glm::dvec3 p(cone.positions[t[c]]);
                EXPECT_LT(glm::distance(n, glm::normalize(p + glm::dvec3(0.0, 1.0, 0.0))), 1e-6);
            }
        }
    }
}

}  // namespace
}  // namespace inkline
