// SPDX-License-Identifier: MIT
// Hatched tone (core/tone/hatch.h) through core::FramePipeline, measured independently of it:
// ink coverage per band of N.L against the tone asked for (the hatches' outlines filled here,
// the surface's N.L from tests/support/tone_raster.h), lines on their planes, nesting of tones,
// coherence on a turntable, no hatch on hidden surface or on a stroke's ink.
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/tone/tone.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/ground_plane.h"
#include "tests/support/pipeline.h"
#include "tests/support/segment_occlusion.h"
#include "tests/support/shapes.h"
#include "tests/support/tone_raster.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace inkline {
namespace {

constexpr double kCoverageTolerance = 0.10;  // as the stipples (docs/tone.md)
constexpr double kMinAssertedTone = 0.05;

const core::Light kSideLight{.direction = {-1.0, 0.0, 0.0}};

core::VisibilityMode raycast_or_exact() {
    return core::raycast_available() ? core::VisibilityMode::kRaycast : core::VisibilityMode::kExact;
}

core::Scene sphere_scene(const core::Mesh& mesh, core::ToneMode mode, double max, int size = 512) {
    core::Scene scene = test::scene_for({.eye = {0.0, 0.0, 4.0}, .fov_y_deg = 35.0, .size = size}, mesh);
    scene.light = kSideLight;
    scene.lines.silhouette = scene.lines.boundary = scene.lines.crease = scene.lines.intersection = false;
    scene.tone = {.mode = mode, .curve = {.max = max}};
    return scene;
}

std::vector<core::FrameResult> run_frames(const core::Scene& scene, const core::Mesh& mesh) {
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(raycast_or_exact()));
    std::vector<core::FrameResult> out;
    for (int frame = scene.first_frame; frame <= scene.last_frame; ++frame) out.push_back(pipeline.run(frame));
    return out;
}

// Per pixel, the share of its n x n samples inside the union of the rings (each filled with the
// nonzero rule), rows from the top.
std::vector<double> ring_coverage(const std::vector<core::Hatch>& hatches, core::ImageSize image, int n = 8) {
    const int w = image.width * n, h = image.height * n;
    std::vector<uint8_t> inked(size_t(w) * size_t(h), 0);
    for (const core::Hatch& hatch : hatches) {
        for (const core::Ring& ring : hatch.outline) {
            double y_lo = 1e300, y_hi = -1e300;
            for (const glm::dvec2& p : ring) y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
            const int r0 = std::max(0, int(std::floor(y_lo * n))), r1 = std::min(h - 1, int(std::ceil(y_hi * n)));
            for (int r = r0; r <= r1; ++r) {
                const double y = (r + 0.5) / n;
                std::vector<std::pair<double, int>> crossings;  // x, winding change
                for (size_t i = 0; i < ring.size(); ++i) {
                    const glm::dvec2 a = ring[i], b = ring[(i + 1) % ring.size()];
                    if ((a.y <= y) == (b.y <= y)) continue;
                    crossings.emplace_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x), b.y > a.y ? 1 : -1);
                }
                std::sort(crossings.begin(), crossings.end());
                int winding = 0;
                for (size_t k = 0; k + 1 < crossings.size(); ++k) {
                    winding += crossings[k].second;
                    if (winding == 0) continue;
                    const int c0 = std::max(0, int(std::ceil(crossings[k].first * n - 0.5)));
                    const int c1 = std::min(w - 1, int(std::floor(crossings[k + 1].first * n - 0.5)));
                    for (int c = c0; c <= c1; ++c) inked[size_t(r) * size_t(w) + size_t(c)] = 1;
                }
            }
        }
    }
    std::vector<double> out(size_t(image.width) * size_t(image.height), 0.0);
    for (int r = 0; r < h; ++r) {
        for (int c = 0; c < w; ++c) {
            if (inked[size_t(r) * size_t(w) + size_t(c)]) out[size_t(r / n) * size_t(image.width) + size_t(c / n)] += 1.0;
        }
    }
    for (double& v : out) v /= double(n * n);
    return out;
}

// How far p lies off a face: from its plane, or outside it (the least barycentric coordinate's
// shortfall, in units of the face's size).
double off_face(const core::Mesh& mesh, uint32_t face, const glm::dvec3& p) {
    const glm::uvec3 t = mesh.triangles[face];
    const glm::dvec3 a(mesh.positions[t.x]), u = glm::dvec3(mesh.positions[t.y]) - a, v = glm::dvec3(mesh.positions[t.z]) - a;
    const glm::dvec3 n = glm::normalize(glm::cross(u, v)), d = p - a;
    const double uu = glm::dot(u, u), uv = glm::dot(u, v), vv = glm::dot(v, v), gram = uu * vv - uv * uv;
    const double b1 = (vv * glm::dot(d, u) - uv * glm::dot(d, v)) / gram;
    const double b2 = (uu * glm::dot(d, v) - uv * glm::dot(d, u)) / gram;
    return std::max({std::abs(glm::dot(d, n)), -b1, -b2, b1 + b2 - 1.0, 0.0});
}

// Hatching in screen space at 30 and -60 degrees: off the sampling grid's diagonals, where
// straight, evenly spaced lines alias with ring_coverage's 8 x 8 samples of a pixel (-6% at 0 or
// 45 degrees, within 0.1% at 17 and 30).
void hatch_on_screen(core::Scene& r_scene) {
    r_scene.tone.space = core::HatchSpace::kScreen;
    r_scene.tone.angle_deg = 30.0;
    r_scene.tone.cross_angle_deg = -60.0;
}

void expect_coverage_follows_tone(core::ToneMode mode, double max, core::HatchSpace space = core::HatchSpace::kObject) {
    const core::Mesh mesh = test::uv_sphere(160, 80, 1.0);
    core::Scene scene = sphere_scene(mesh, mode, max);
    if (space == core::HatchSpace::kScreen) hatch_on_screen(scene);
    const std::vector<core::FrameResult> frames = run_frames(scene, mesh);
    const core::FrameResult& r = frames.front();
    ASSERT_FALSE(r.tone.hatches.empty());
    const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
    const test::SurfacePixels surface = test::sphere_pixels(glm::dvec3(0.0), 1.0, projection, scene.light);
    const std::vector<double> coverage = ring_coverage(r.tone.hatches, scene.image);
    const std::vector<test::ToneBand> bands = test::tone_bands(surface, coverage, {}, scene.tone);
    std::printf("%s, %s space, max %.2f: %zu hatches\n%s", core::tone_mode_name(mode), core::hatch_space_name(space),
                max, r.tone.hatches.size(), test::band_table(bands).c_str());
    size_t asserted = 0;
    for (const test::ToneBand& band : bands) {
        if (band.pixels < 200 || band.target < kMinAssertedTone) continue;
        ++asserted;
        EXPECT_LE(std::abs(band.relative_error()), kCoverageTolerance)
            << "N.L in [" << band.lo << ", " << band.hi << "): target " << band.target << ", coverage " << band.coverage;
    }
    EXPECT_GE(asserted, 5u);
}

TEST(Hatch, CoverageFollowsTheToneOnALitSphere) { expect_coverage_follows_tone(core::ToneMode::kHatch, 0.4); }

TEST(Hatch, CrosshatchCoverageFollowsTheToneOnALitSphere) {
    expect_coverage_follows_tone(core::ToneMode::kCrosshatch, 0.6);
}

TEST(Hatch, ScreenSpaceCoverageFollowsTheToneOnALitSphere) {
    expect_coverage_follows_tone(core::ToneMode::kHatch, 0.4, core::HatchSpace::kScreen);
    expect_coverage_follows_tone(core::ToneMode::kCrosshatch, 0.6, core::HatchSpace::kScreen);
}

// In screen space each hatch is a straight line on the image at its family's angle, wherever
// the surface under it turns: every point of a hatch, projected from its world point, lies on
// one line across the family's normal, the lines in order of their plane numbers; and the
// points lie on the surface: on their faces, and on the edges they cross.
TEST(Hatch, ScreenSpaceLinesAreStraightOnThePageAtTheirAngles) {
    const core::Mesh mesh = test::torus(1.0, 0.35, 96, 48);
    core::Scene scene = sphere_scene(mesh, core::ToneMode::kCrosshatch, 0.6);
    scene.camera.pose.eye = {0.0, 2.0, 3.5};
    hatch_on_screen(scene);
    const std::vector<core::FrameResult> frames = run_frames(scene, mesh);
    const core::FrameResult& r = frames.front();
    ASSERT_FALSE(r.tone.hatches.empty());
    const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
    const core::EdgeTable table = core::build_edge_table(mesh);
    std::map<std::pair<uint32_t, uint64_t>, double> offset;  // (family, plane) -> its line's offset
    std::set<uint32_t> families;
    size_t points = 0, inside = 0;
    for (const core::Hatch& hatch : r.tone.hatches) {
        families.insert(hatch.family);
        // On the page (y down) the lines run at the angle anticlockwise from x: their normal.
        const double angle = glm::radians(hatch.family == 0 ? scene.tone.angle_deg : scene.tone.cross_angle_deg);
        const glm::dvec2 across(std::sin(angle), std::cos(angle));
        const auto [it, inserted] =
            offset.try_emplace({hatch.family, hatch.plane}, glm::dot(across, hatch.points_px.front()));
        for (size_t k = 0; k < hatch.points_px.size(); ++k) {
            ++points;
            const glm::dvec2 px = projection.pixel(hatch.points_world[k]);
            EXPECT_NEAR(glm::distance(px, hatch.points_px[k]), 0.0, 1e-6);
            EXPECT_NEAR(glm::dot(across, px), it->second, 2e-3)
                << "family " << hatch.family << " plane " << hatch.plane;
            // On the surface: on its face, and where it names an edge it crosses, on that edge.
            EXPECT_LE(off_face(mesh, hatch.faces[k], hatch.points_world[k]), 1e-9);
            const glm::uvec2 ends = table.edge_vertices[hatch.edges[k]];
            const glm::dvec3 a(mesh.positions[ends.x]), b(mesh.positions[ends.y]);
            const double t = glm::dot(hatch.points_world[k] - a, b - a) / glm::dot(b - a, b - a);
            if (glm::distance(a + t * (b - a), hatch.points_world[k]) < 1e-9) {
                EXPECT_TRUE(t >= -1e-9 && t <= 1.0 + 1e-9) << t;
            } else {
                ++inside;
            }
        }
    }
    EXPECT_EQ(families.size(), 2u) << "crosshatch draws both families";
    for (auto a = offset.begin(), b = std::next(a); b != offset.end(); ++a, ++b) {
        if (a->first.first == b->first.first) {
            EXPECT_LT(a->second, b->second);
        }
    }
    std::printf("screen space: %zu hatches, %zu points (%zu inside faces), %zu lines\n", r.tone.hatches.size(), points,
                inside, offset.size());
}

// In screen space the lines stay on the page as the object turns under them: a frame's lines
// lie on lines of the page a frame before drew, at the same offsets.
TEST(Hatch, ScreenSpaceLinesStayOnThePage) {
    const core::Mesh mesh = test::torus(1.0, 0.35, 96, 48);
    core::Scene scene = sphere_scene(mesh, core::ToneMode::kHatch, 0.5);
    scene.camera.pose.eye = {0.0, 2.0, 3.5};
    scene.tone.space = core::HatchSpace::kScreen;
    scene.first_frame = 0;
    scene.last_frame = 3;
    scene.object_rotation = core::Rotation{{0.0, 1.0, 0.0}, 2.0 * 3.0, {0.0, 0.0, 0.0}};
    const std::vector<core::FrameResult> frames = run_frames(scene, mesh);
    const glm::dvec2 across(std::sin(glm::radians(45.0)), std::cos(glm::radians(45.0)));
    std::map<uint64_t, double> offset;
    for (const core::FrameResult& r : frames) {
        ASSERT_FALSE(r.tone.hatches.empty());
        for (const core::Hatch& hatch : r.tone.hatches) {
            const auto [it, inserted] = offset.try_emplace(hatch.plane, glm::dot(across, hatch.points_px.front()));
            for (const glm::dvec2& p : hatch.points_px) EXPECT_NEAR(glm::dot(across, p), it->second, 2e-3);
        }
    }
}

// The ground hatched at a constant tone of 0.3 (lines across z, or on the image at 30 degrees),
// its ink within 10% of the tone in four bands of rows from far to near; the scene it was drawn
// with.
core::Scene ground_hatched_evenly(const core::Mesh& plane, core::HatchSpace space = core::HatchSpace::kObject) {
    core::Scene scene = test::ground_scene(plane, {480, 320});
    scene.tone = {.mode = core::ToneMode::kHatch, .curve = {.min = 0.3, .max = 0.3}, .line_width_px = 1.0,
                  .direction = {0.0, 0.0, 1.0}};
    if (space == core::HatchSpace::kScreen) hatch_on_screen(scene);
    const core::FrameResult r = run_frames(scene, plane).front();
    EXPECT_FALSE(r.tone.hatches.empty());
    const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
    const std::vector<double> bands = test::ground_band_ink(plane, projection, ring_coverage(r.tone.hatches, scene.image), 4);
    EXPECT_EQ(bands.size(), 4u);
    for (size_t band = 0; band < bands.size(); ++band) {
        std::printf("band %zu of rows from far to near: ink %.4f against the tone 0.3\n", band, bands[band]);
        EXPECT_NEAR(bands[band], 0.3, 0.03) << "band " << band;
    }
    return scene;
}

// A ground plane of two triangles seen in strong perspective, as real shots have them: hatched
// across the whole image at the spacing its constant tone asks for, near and far (the lines'
// spacing followed point by point, not per face), and with a box standing on it, no hatch point
// on the plane behind the box.
TEST(Hatch, ALargeFaceIsHatchedPointByPointUnderPerspective) {
    const core::Mesh plane = test::ground_plane(4.0f, -12.0f, 2.0f);
    core::Scene scene = ground_hatched_evenly(plane);
    // A box on the plane, in front of its middle: nothing of the plane behind it is hatched.
    const core::Mesh with_box = test::combine(plane, test::cube(0.6), {0.0f, 0.6f, -2.0f});
    scene.tone.curve = {.min = 0.3, .max = 0.3};
    const core::FrameResult boxed = run_frames(scene, with_box).front();
    const test::SegmentOcclusion exact(with_box);
    size_t points = 0, hidden = 0;
    for (const core::Hatch& hatch : boxed.tone.hatches) {
        for (size_t k = 0; k < hatch.points_world.size(); ++k) {
            ++points;
            if (exact.hidden(boxed.lines.camera.eye, hatch.points_world[k], hatch.faces[k])) ++hidden;
        }
    }
    std::printf("plane and box: %zu hatch points, %zu hidden by the exact test\n", points, hidden);
    ASSERT_GT(points, 1000u);
    EXPECT_LE(double(hidden), 0.005 * double(points));
}

// A ground plane of two triangles running from far ahead to behind the camera, as a shot's
// ground does: hatched where it is seen, evenly in perspective, in object space and on the image
// (each face was left unshaded while a corner of it lay behind the camera: in screen space, where
// a corner behind the camera has no image position to lay the lines by, until its lines were
// found as planes through the eye).
TEST(Hatch, AGroundPlaneRunningBehindTheCameraIsHatchedWhereItIsSeen) {
    const core::Mesh plane = test::ground_plane(6.0f, -14.0f, 8.0f);
    for (const core::HatchSpace space : {core::HatchSpace::kObject, core::HatchSpace::kScreen}) {
        SCOPED_TRACE(space == core::HatchSpace::kObject ? "object space" : "screen space");
        const core::Scene scene = ground_hatched_evenly(plane, space);
        const core::FrameResult r = run_frames(scene, plane).front();
        const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
        // Every drawn point is in front of the camera and on the image.
        for (const core::Hatch& hatch : r.tone.hatches) {
            for (const glm::dvec2& p : hatch.points_px) ASSERT_TRUE(projection.inside_image(p)) << p.x << ", " << p.y;
            for (const glm::dvec3& p : hatch.points_world) {
                ASSERT_TRUE(projection.in_front(
                    projection.clip(glm::dvec3(glm::inverse(r.world_from_object) * glm::dvec4(p, 1.0)))));
            }
        }
    }
}

// A ground far wider than the image (600 units across, 0.2 in front of the camera at its near
// side), hatched evenly: its faces are traced on their part in view, so only the lines the view
// asks for are traced. Before, each face's planes and finest level came from its corners, far
// outside the image and magnified many times: each face traced its cap of 4,096 lines (8,192
// segments, 20 times as many) and spread its lines' inner points along their whole length.
TEST(Hatch, AGroundFarWiderThanTheImageIsTracedWhereItIsSeen) {
    const core::Mesh plane = test::ground_plane(300.0f, -14.0f, 2.8f);
    const core::Scene scene = ground_hatched_evenly(plane);
    const core::FrameResult r = run_frames(scene, plane).front();
    std::printf("wide ground: %zu segments traced, %zu points\n", r.tone.hatch_stats.segments,
                r.tone.hatch_stats.points);
    EXPECT_LT(r.tone.hatch_stats.segments, 2048u);
}

// Lines run up to the strokes: a box's sides, each of one tone and two triangles, drawn with
// their outline and creases, are hatched as evenly next to the strokes as in their middles. A
// line that crosses a triangle in one short segment (where the diagonal meets an edge) ends
// where it meets the stroke's ink, not at its last point before it: before, those corners of
// each side were left blank.
TEST(Hatch, LinesRunUpToTheStrokesInk) {
    const core::Mesh cube = test::cube(0.8);
    core::Scene scene = test::scene_for({.eye = {2.2, 1.7, 3.0}, .fov_y_deg = 40.0, .size = 512}, cube);
    scene.light = {.direction = glm::normalize(glm::dvec3(-0.3, -1.0, -0.55))};
    scene.tone = {.mode = core::ToneMode::kHatch, .curve = {.min = 0.3, .max = 0.3}, .line_width_px = 0.8,
                  .direction = glm::normalize(glm::dvec3(0.2, 1.0, 0.1))};
    const core::FrameResult r = run_frames(scene, cube).front();
    ASSERT_FALSE(r.tone.hatches.empty());
    const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
    double half_ink = 0.0;
    for (const core::Stroke& stroke : r.strokes.strokes) {
        for (const double w : stroke.centerline_width) half_ink = std::max(half_ink, 0.5 * w);
    }
    const std::vector<double> coverage = ring_coverage(r.tone.hatches, scene.image);
    // Each visible side: its corners on the image, and the mean ink of its pixels between
    // `near` and `far` px inside its edges.
    size_t sides = 0;
    for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 n(0.0);
        n[axis] = 1.0;  // the sides facing +x, +y, +z face the eye
        glm::dvec2 corner[4];
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const double s[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (int k = 0; k < 4; ++k) {
            glm::dvec3 p = 0.8 * n;
            p[u] = 0.8 * s[k][0];
            p[v] = 0.8 * s[k][1];
            corner[k] = projection.pixel(p);
        }
        const auto inside_by = [&](const glm::dvec2& p) {  // least distance inside the quad's edges
            double least = 1e300;
            const double orientation =
                (corner[1].x - corner[0].x) * (corner[2].y - corner[0].y) - (corner[1].y - corner[0].y) * (corner[2].x - corner[0].x);
            for (int k = 0; k < 4; ++k) {
                const glm::dvec2 a = corner[k], b = corner[(k + 1) % 4];
                const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
                least = std::min(least, (orientation > 0.0 ? cross : -cross) / glm::length(b - a));
            }
            return least;
        };
        const auto mean_ink = [&](double near, double far) {
            double sum = 0.0;
            size_t count = 0;
            for (int y = 0; y < scene.image.height; ++y) {
                for (int x = 0; x < scene.image.width; ++x) {
                    const double d = inside_by({x + 0.5, y + 0.5});
                    if (d < near || d >= far) continue;
                    sum += coverage[size_t(y) * size_t(scene.image.width) + size_t(x)];
                    ++count;
                }
            }
            return std::pair{count > 0 ? sum / double(count) : 0.0, count};
        };
        const double edge_band = half_ink + 1.0;
        const auto [near_ink, near_px] = mean_ink(edge_band, edge_band + 6.0);
        const auto [middle_ink, middle_px] = mean_ink(edge_band + 6.0, 1e300);
        std::printf("side +%c: ink %.4f within 6 px of the strokes' ink (%zu px), %.4f inside (%zu px)\n", "xyz"[axis],
                    near_ink, near_px, middle_ink, middle_px);
        if (near_px < 500 || middle_px < 500) continue;
        ++sides;
        EXPECT_NEAR(near_ink, 0.3, 0.03) << "side +" << "xyz"[axis];
        EXPECT_NEAR(middle_ink, 0.3, 0.03) << "side +" << "xyz"[axis];
        // (Lines that stopped at their last point before the ink left 0.035 less next to it.)
        EXPECT_NEAR(near_ink, middle_ink, 0.005) << "side +" << "xyz"[axis];
    }
    EXPECT_EQ(sides, 3u);
}

// Each hatch lies on one plane across its family's direction: the world points (the object does
// not move) all at the same height along it.
TEST(Hatch, LinesLieOnTheirPlanes) {
    const core::Mesh mesh = test::torus(1.0, 0.35, 96, 48);
    core::Scene scene = sphere_scene(mesh, core::ToneMode::kCrosshatch, 0.6);
    scene.tone.direction = glm::normalize(glm::dvec3(0.0, 1.0, 0.3));
    scene.tone.cross_direction = glm::dvec3(1.0, 0.0, 0.0);
    scene.camera.pose.eye = {0.0, 2.0, 3.5};
    const std::vector<core::FrameResult> frames = run_frames(scene, mesh);
    const core::FrameResult& r = frames.front();
    ASSERT_FALSE(r.tone.hatches.empty());
    std::map<std::pair<uint32_t, uint64_t>, double> height;  // (family, plane) -> its height
    std::set<uint32_t> families;
    for (const core::Hatch& hatch : r.tone.hatches) {
        families.insert(hatch.family);
        const glm::dvec3 d = hatch.family == 0 ? scene.tone.direction : scene.tone.cross_direction;
        ASSERT_EQ(hatch.points_world.size(), hatch.points_px.size());
        ASSERT_EQ(hatch.width_px.size(), hatch.points_px.size());
        const auto [it, inserted] = height.try_emplace({hatch.family, hatch.plane}, glm::dot(d, hatch.points_world.front()));
        for (const glm::dvec3& p : hatch.points_world) {
            EXPECT_NEAR(glm::dot(d, p), it->second, 1e-5) << "family " << hatch.family << " plane " << hatch.plane;
        }
        for (double width : hatch.width_px) EXPECT_LE(width, scene.tone.line_width_px + 1e-12);
    }
    EXPECT_EQ(families.size(), 2u) << "crosshatch draws both families";
    // Planes in order of their number are in order of height, within a family.
    for (auto a = height.begin(), b = std::next(a); b != height.end(); ++a, ++b) {
        if (a->first.first == b->first.first) {
            EXPECT_LT(a->second, b->second);
        }
    }
}

// A darker tone draws every line a lighter one draws (by family and plane), and more.
TEST(Hatch, DarkerToneAddsLinesBetweenTheOthers) {
    const core::Mesh mesh = test::uv_sphere(128, 64, 1.0);
    std::set<std::pair<uint32_t, uint64_t>> light_planes, dark_planes;
    const std::vector<core::FrameResult> light = run_frames(sphere_scene(mesh, core::ToneMode::kHatch, 0.2), mesh);
    const std::vector<core::FrameResult> dark = run_frames(sphere_scene(mesh, core::ToneMode::kHatch, 0.5), mesh);
    for (const core::Hatch& h : light.front().tone.hatches) light_planes.insert({h.family, h.plane});
    for (const core::Hatch& h : dark.front().tone.hatches) dark_planes.insert({h.family, h.plane});
    ASSERT_FALSE(light_planes.empty());
    EXPECT_GT(dark_planes.size(), light_planes.size());
    for (const auto& plane : light_planes) EXPECT_TRUE(dark_planes.count(plane)) << "plane " << plane.second;
}

// Turning 2 degrees a frame under a fixed light, the lines stay on the surface: at least 95% of
// a frame's hatch length lies on planes drawn the frame before.
TEST(Hatch, TurntableKeepsItsLines) {
    const core::Mesh mesh = test::torus(1.0, 0.35, 96, 48);
    core::Scene scene = sphere_scene(mesh, core::ToneMode::kCrosshatch, 0.5);
    scene.camera.pose.eye = {0.0, 2.0, 3.5};
    scene.first_frame = 0;
    scene.last_frame = 8;
    scene.camera.orbit = core::Rotation{{0.0, 1.0, 0.0}, 2.0 * 9.0, {0.0, 0.0, 0.0}};
    const std::vector<core::FrameResult> frames = run_frames(scene, mesh);
    double least = 1.0;
    for (size_t i = 1; i < frames.size(); ++i) {
        std::set<std::pair<uint32_t, uint64_t>> before;
        for (const core::Hatch& h : frames[i - 1].tone.hatches) before.insert({h.family, h.plane});
        double kept = 0.0, total = 0.0;
        for (const core::Hatch& h : frames[i].tone.hatches) {
            double length = 0.0;
            for (size_t k = 1; k < h.points_px.size(); ++k) length += glm::length(h.points_px[k] - h.points_px[k - 1]);
            total += length;
            if (before.count({h.family, h.plane})) kept += length;
        }
        ASSERT_GT(total, 0.0);
        least = std::min(least, kept / total);
    }
    std::printf("turntable: least share of hatch length on last frame's planes %.4f\n", least);
    EXPECT_GE(least, 0.95);
}

// No hatch point on hidden surface (an independent double-precision segment test, the point's
// edge's first face its own), none on a drawn stroke's ink.
TEST(Hatch, NoneOnHiddenSurfaceOrOnTheLines) {
    const core::Mesh mesh =
        test::combine(test::torus(1.0, 0.35, 96, 48), test::uv_sphere(48, 24, 0.45), {0.2f, 0.3f, 1.2f});
    core::Scene scene = test::scene_for({.eye = {0.4, 1.6, 4.2}, .fov_y_deg = 40.0, .size = 512}, mesh);
    scene.light = kSideLight;
    for (const core::HatchSpace space : {core::HatchSpace::kObject, core::HatchSpace::kScreen}) {
        SCOPED_TRACE(core::hatch_space_name(space));
        scene.tone = {.mode = core::ToneMode::kCrosshatch, .curve = {.max = 0.5}, .space = space};
        const core::FrameResult r = run_frames(scene, mesh).front();
        ASSERT_FALSE(r.tone.hatches.empty());
        ASSERT_FALSE(r.strokes.strokes.empty());
        const core::EdgeTable table = core::build_edge_table(mesh);
        const test::SegmentOcclusion exact(mesh);
        const glm::dvec3 eye = r.lines.camera.eye;  // the object does not move: object space is world space
        size_t points = 0, hidden = 0;
        for (const core::Hatch& hatch : r.tone.hatches) {
            for (size_t k = 0; k < hatch.points_world.size(); ++k) {
                ++points;
                // Off both faces of its edge: the segment's end gap keeps the other one from meeting it.
                if (exact.hidden(eye, hatch.points_world[k], hatch.faces[k])) ++hidden;
                for (const core::Stroke& stroke : r.strokes.strokes) {
                    if (!stroke.drawn || !stroke.geometry.visible) continue;
                    for (size_t i = 0; i + 1 < stroke.centerline_px.size(); ++i) {
                        const glm::dvec2 a = stroke.centerline_px[i], b = stroke.centerline_px[i + 1];
                        const glm::dvec2 d = b - a;
                        const double t = std::clamp(
                            glm::dot(hatch.points_px[k] - a, d) / std::max(glm::dot(d, d), 1e-300), 0.0, 1.0);
                        const double reach = 0.5 * std::min(stroke.centerline_width[i], stroke.centerline_width[i + 1]);
                        ASSERT_GE(glm::length(a + t * d - hatch.points_px[k]), reach)
                            << "a hatch point on a stroke's ink";
                    }
                }
            }
        }
        std::printf("%s space: hatch points %zu, hidden by the exact test %zu (%.3f%%)\n",
                    core::hatch_space_name(space), points, hidden, 100.0 * hidden / points);
        EXPECT_LE(double(hidden), 0.005 * double(points));
    }
}

// Crosshatch's second family only where the tone passes cross_from.
TEST(Hatch, CrosshatchCrossesOnlyTheDarkerTones) {
    const core::Mesh mesh = test::uv_sphere(128, 64, 1.0);
    const core::Scene scene = sphere_scene(mesh, core::ToneMode::kCrosshatch, 0.6);
    const core::FrameResult r = run_frames(scene, mesh).front();
    const core::Projection projection(r.lines.camera, scene.image, r.world_from_object);
    size_t cross_points = 0;
    for (const core::Hatch& hatch : r.tone.hatches) {
        if (hatch.family != 1) continue;
        for (const glm::dvec3& p : hatch.points_world) {
            ++cross_points;
            const double tone = core::tone_of(glm::dot(glm::normalize(p), -kSideLight.direction), scene.tone);
            EXPECT_GT(tone, scene.tone.cross_from - 0.02) << "a cross line where the tone is " << tone;
        }
    }
    EXPECT_GT(cross_points, 0u);
}

}  // namespace
}  // namespace inkline

namespace inkline {
namespace {

// Odd but drawable meshes (a non-manifold vertex, a fin, degenerate and repeated faces, a flat
// open grid, a mesh of nothing but degenerate faces) get tone without failing: every mark on a
// valid face, every number finite.
TEST(Tone, OddMeshesAreShadedWithoutFailing) {
    core::Mesh folded = test::grid(12, 1.0);
    const auto base = uint32_t(folded.positions.size());
    folded.positions.push_back({0.0f, 0.0f, 0.5f});  // a fin standing on the grid's middle edge
    folded.triangles.push_back({0, 1, base});
    folded.triangles.push_back({0, 1, base});         // repeated
    folded.triangles.push_back({2, 2, 3});            // degenerate
    core::Mesh flat;
    flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    flat.triangles = {{0, 1, 2}, {1, 2, 3}};  // zero area: nothing to shade
    const std::vector<core::Mesh> meshes = {test::twin_cones(64), folded, test::disc_cap(200), flat};
    for (const core::ToneMode mode : {core::ToneMode::kStipple, core::ToneMode::kHatch, core::ToneMode::kCrosshatch}) {
        for (size_t m = 0; m < meshes.size(); ++m) {
            SCOPED_TRACE(std::string(core::tone_mode_name(mode)) + ", mesh " + std::to_string(m));
            core::Scene scene = test::scene_for({.eye = {0.6, 1.8, 2.5}, .fov_y_deg = 45.0, .size = 256}, meshes[m]);
            scene.light = kSideLight;
            scene.tone = {.mode = mode, .curve = {.max = 0.6}};
            const std::vector<core::FrameResult> frames = run_frames(scene, meshes[m]);
            const core::FrameTone& tone = frames.front().tone;
            for (const core::Dot& d : tone.dots) {
                ASSERT_LT(d.face, meshes[m].triangles.size());
                ASSERT_TRUE(std::isfinite(d.point_px.x) && std::isfinite(d.point_px.y) && std::isfinite(d.radius_px));
            }
            for (const core::Hatch& h : tone.hatches) {
                for (size_t k = 0; k < h.points_px.size(); ++k) {
                    ASSERT_TRUE(std::isfinite(h.points_px[k].x) && std::isfinite(h.points_px[k].y));
                    ASSERT_TRUE(std::isfinite(h.width_px[k]));
                }
                for (const core::Ring& ring : h.outline) {
                    for (const glm::dvec2& p : ring) ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
                }
            }
            if (m == 3) {
                EXPECT_TRUE(tone.dots.empty() && tone.hatches.empty()) << "nothing to shade";
            }
        }
    }
}

}  // namespace
}  // namespace inkline
