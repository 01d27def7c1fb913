// SPDX-License-Identifier: MIT
// core::FramePipeline: the frame-to-frame state the CLI relies on (tracker, occlusion test,
// stroke coherence), the modes parsed from their names, and the steps it reports.
#include "core/pipeline/frame_pipeline.h"

#include "core/error.h"
#include "core/mesh/mesh_frames.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/obj.h"
#include "tests/support/pipeline.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace inkline {
namespace {

namespace fs = std::filesystem;

// Raycast and exact must agree on at least this fraction of the visible length (as in
// raycast_visibility_test).
constexpr double kMinAgreement = 0.999;

// A torus with a sphere in front of it, the sphere moved along x by `shift`: the sphere hides
// parts of the torus's silhouettes and creases.
core::Mesh torus_behind_sphere(float shift) {
    return test::combine(test::torus(1.0, 0.35, 48, 24), test::uv_sphere(32, 16, 0.45), {shift, 0.3f, 1.2f});
}

const test::View kView{.eye = {0.4, 1.6, 4.2}, .fov_y_deg = 40.0, .size = 512};

// A turntable of `frames` frames around `mesh` as seen from kView, 360 degrees in all.
core::Scene turntable(const core::Mesh& mesh, int frames) {
    core::Scene scene = test::scene_for(kView, mesh);
    scene.last_frame = frames;
    scene.camera.orbit = core::Rotation{.axis = {0.0, 1.0, 0.0}, .degrees = 360.0};
    // The fitted near and far of one view do not hold all around: fitted per frame instead.
    scene.camera.near.reset();
    scene.camera.far.reset();
    return scene;
}

// Every frame of `scene` through one pipeline.
std::vector<core::FrameResult> run_all(const core::Scene& scene, core::MeshFrames& meshes,
                                       std::unique_ptr<core::OcclusionSource> occlusion,
                                       core::PipelineOptions options = {}) {
    core::FramePipeline pipeline(scene, meshes, std::move(occlusion), std::move(options));
    std::vector<core::FrameResult> out;
    for (int frame = scene.first_frame; frame <= scene.last_frame; ++frame) out.push_back(pipeline.run(frame));
    return out;
}

// Same polylines, bit for bit, in the same order.
void expect_same_lines(const core::FrameLines& a, const core::FrameLines& b) {
    ASSERT_EQ(a.polylines.size(), b.polylines.size()) << "frame " << a.frame;
    for (size_t i = 0; i < a.polylines.size(); ++i) {
        const core::Polyline &p = a.polylines[i], &q = b.polylines[i];
        EXPECT_EQ(p.id, q.id);
        EXPECT_EQ(p.kind, q.kind);
        EXPECT_EQ(p.visible, q.visible);
        EXPECT_EQ(p.closed, q.closed);
        EXPECT_EQ(p.edges, q.edges);
        EXPECT_EQ(p.points_px, q.points_px) << "frame " << a.frame << ", polyline " << i;
    }
    EXPECT_EQ(a.occluded.size(), b.occluded.size());
}

// Same strokes: ids, ends and outline geometry.
void expect_same_strokes(const core::FrameStrokes& a, const core::FrameStrokes& b) {
    ASSERT_EQ(a.strokes.size(), b.strokes.size());
    for (size_t i = 0; i < a.strokes.size(); ++i) {
        EXPECT_EQ(a.strokes[i].id, b.strokes[i].id);
        EXPECT_EQ(a.strokes[i].geometry.points_px, b.strokes[i].geometry.points_px) << "stroke " << i;
        EXPECT_EQ(a.strokes[i].geometry.bridged, b.strokes[i].geometry.bridged) << "stroke " << i;
        EXPECT_EQ(a.strokes[i].width, b.strokes[i].width) << "stroke " << i;
    }
}

double visible_length(const core::FrameLines& frame) {
    double sum = 0.0;
    for (const double px : frame.stats.visible_length_px) sum += px;
    return sum;
}

// Passes each prepare() on to a real test and records what the pipeline said had changed.
class RecordingOcclusion final : public core::OcclusionSource {
  public:
    RecordingOcclusion(core::VisibilityMode mode, std::vector<core::MeshChange>& r_changes)
        : inner_(core::make_cpu_occlusion(mode)), changes_(r_changes) {}
    const core::Occlusion& prepare(const core::Mesh& mesh, const core::EdgeTable& table,
                                   const core::Projection& projection, core::MeshChange change) override {
        changes_.push_back(change);
        return inner_->prepare(mesh, table, projection, change);
    }
    core::VisibilityMode mode() const override { return inner_->mode(); }

  private:
    std::unique_ptr<core::OcclusionSource> inner_;
    std::vector<core::MeshChange>& changes_;
};

TEST(Modes, ParseFromTheirNamesAndRefuseOthersNamingTheKey) {
    for (const core::TrackerMode mode : {core::TrackerMode::kIncremental, core::TrackerMode::kBrute}) {
        EXPECT_EQ(core::parse_tracker_mode(core::tracker_mode_name(mode), "--tracker"), mode);
    }
    for (const core::VisibilityMode mode :
         {core::VisibilityMode::kGl, core::VisibilityMode::kRaycast, core::VisibilityMode::kExact}) {
        EXPECT_EQ(core::parse_visibility_mode(core::visibility_mode_name(mode), "--visibility"), mode);
    }
    EXPECT_STREQ(core::tracker_mode_name(core::TrackerMode::kBrute), "brute");
    EXPECT_STREQ(core::visibility_mode_name(core::VisibilityMode::kRaycast), "raycast");
    try {
        core::parse_tracker_mode("Brute", "--tracker");
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "--tracker 'Brute': expected incremental or brute");
    }
    try {
        core::parse_visibility_mode("auto", "visibility");
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "visibility 'auto': expected gl, raycast or exact");
    }
    EXPECT_FALSE(core::visibility_mode_from_name("").has_value());
    EXPECT_THROW(core::make_cpu_occlusion(core::VisibilityMode::kGl), InternalError);
}

TEST(FramePipeline, BruteAndIncrementalDrawTheSameLinesAndStrokes) {
    const core::Mesh mesh = torus_behind_sphere(0.0f);
    const core::Scene scene = turntable(mesh, 8);
    core::MeshFrames brute_meshes(mesh), tracked_meshes(mesh);
    const auto brute = run_all(scene, brute_meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact),
                               {.tracker = core::TrackerMode::kBrute});
    const auto tracked = run_all(scene, tracked_meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact),
                                 {.tracker = core::TrackerMode::kIncremental});
    size_t tested_brute = 0, tested_tracked = 0;
    for (size_t f = 0; f < brute.size(); ++f) {
        SCOPED_TRACE("frame " + std::to_string(f + 1));
        expect_same_lines(brute[f].lines, tracked[f].lines);
        expect_same_strokes(brute[f].strokes, tracked[f].strokes);
        EXPECT_EQ(brute[f].lines.stats.tracker, "brute");
        EXPECT_EQ(tracked[f].lines.stats.tracker, "incremental");
        EXPECT_EQ(brute[f].lines.stats.feature_edges, tracked[f].lines.stats.feature_edges);
        if (f > 0) {
            tested_brute += brute[f].lines.stats.edges_tested;
            tested_tracked += tracked[f].lines.stats.edges_tested;
        }
    }
    EXPECT_LT(tested_tracked, tested_brute / 2) << "after the first frame the tracker tests fewer edges";
}

TEST(FramePipeline, ARunOfOneFrameFindsEdgesByBruteForce) {
    const core::Mesh mesh = test::cube(1.0);
    core::MeshFrames meshes(mesh);
    core::Scene scene = test::scene_for(kView, mesh);  // frames 1..1
    const auto exact = [] { return core::make_cpu_occlusion(core::VisibilityMode::kExact); };
    EXPECT_EQ(core::FramePipeline(scene, meshes, exact()).tracker_mode(), core::TrackerMode::kBrute);
    EXPECT_EQ(core::FramePipeline(scene, meshes, exact(), {.frame_count = 2}).tracker_mode(),
              core::TrackerMode::kIncremental);
    scene.last_frame = 48;
    EXPECT_EQ(core::FramePipeline(scene, meshes, exact()).tracker_mode(), core::TrackerMode::kIncremental);
    EXPECT_EQ(core::FramePipeline(scene, meshes, exact(), {.frame_count = 1}).tracker_mode(), core::TrackerMode::kBrute);
    core::FramePipeline one(scene, meshes, exact(), {.frame_count = 1});
    EXPECT_EQ(one.run(5).lines.stats.tracker, "brute");
}

TEST(FramePipeline, RaycastAndExactAgreeOnASphereInFrontOfATorus) {
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree";
    const core::Mesh mesh = torus_behind_sphere(0.0f);
    const core::Scene scene = turntable(mesh, 6);
    core::MeshFrames exact_meshes(mesh), raycast_meshes(mesh);
    const auto exact = run_all(scene, exact_meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    const auto raycast = run_all(scene, raycast_meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast));
    for (size_t f = 0; f < exact.size(); ++f) {
        SCOPED_TRACE("frame " + std::to_string(f + 1));
        EXPECT_EQ(exact[f].lines.stats.visibility, "exact");
        EXPECT_EQ(raycast[f].lines.stats.visibility, "raycast");
        EXPECT_EQ(raycast[f].lines.stats.visibility_reason, "asked for");
        EXPECT_TRUE(raycast[f].lines.stats.gl_context.empty());
        EXPECT_FALSE(exact[f].lines.occluded.empty()) << "the sphere hides part of the torus";
        // Float rays against exact segment queries: the visible length agrees to within
        // kMinAgreement, as the visibility tests ask of the ray-cast test.
        const double length = visible_length(exact[f].lines);
        EXPECT_GT(length, 1000.0);
        EXPECT_NEAR(visible_length(raycast[f].lines), length, (1.0 - kMinAgreement) * length);
        EXPECT_EQ(raycast[f].lines.polylines.size(), exact[f].lines.polylines.size());
        EXPECT_EQ(raycast[f].strokes.strokes.size(), exact[f].strokes.strokes.size());
    }
}

TEST(FramePipeline, StaticMeshPreparesTheOcclusionTestOnceAndLaterFramesReuseIt) {
    std::vector<core::MeshChange> changes;
    const core::Mesh mesh = torus_behind_sphere(0.0f);
    core::MeshFrames meshes(mesh);
    run_all(turntable(mesh, 3), meshes,
            std::make_unique<RecordingOcclusion>(core::VisibilityMode::kExact, changes));
    EXPECT_EQ(changes, (std::vector<core::MeshChange>{core::MeshChange::kTopology, core::MeshChange::kNone,
                                                       core::MeshChange::kNone}));
}

// A deforming sequence: the sphere slides across the torus from frame to frame, so each frame's
// occlusion differs; drawn frame by frame through one pipeline, every frame must be what a fresh
// pipeline draws from that frame's mesh alone.
class DeformingSequence : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    static constexpr int kFrames = 4;
    static core::Mesh mesh_at(int frame) { return torus_behind_sphere(-0.9f + 0.6f * float(frame - 1)); }

    core::Scene scene() {
        for (int frame = 1; frame <= kFrames; ++frame) {
            test::write_obj(dir / ("f" + std::to_string(frame) + ".obj"), mesh_at(frame));
        }
        core::Scene s = test::scene_for(kView, mesh_at(1));
        s.mesh = {.path = dir / "f%d.obj", .is_sequence = true};
        s.last_frame = kFrames;
        s.camera.near.reset();
        s.camera.far.reset();
        return s;
    }

    void check(core::VisibilityMode mode) {
        const core::Scene sequence = scene();
        std::vector<core::MeshChange> changes;
        core::MeshFrames meshes(sequence.mesh, sequence.first_frame);
        const auto drawn = run_all(sequence, meshes, std::make_unique<RecordingOcclusion>(mode, changes));
        EXPECT_EQ(changes, (std::vector<core::MeshChange>{core::MeshChange::kTopology, core::MeshChange::kPositions,
                                                           core::MeshChange::kPositions, core::MeshChange::kPositions}));
        double first_length = 0.0;
        for (int frame = 1; frame <= kFrames; ++frame) {
            SCOPED_TRACE("frame " + std::to_string(frame));
            // The same frame alone: its own mesh, a fresh occlusion test.
            core::Scene alone = sequence;
            alone.first_frame = alone.last_frame = frame;
            core::MeshFrames alone_meshes(mesh_at(frame));
            core::FramePipeline fresh(alone, alone_meshes, core::make_cpu_occlusion(mode));
            const core::FrameResult reference = fresh.run(frame);
            const core::FrameLines& lines = drawn[size_t(frame - 1)].lines;
            if (mode == core::VisibilityMode::kExact) {
                // The tree is built again for new positions: the very same answer.
                EXPECT_EQ(lines.polylines.size(), reference.lines.polylines.size());
                EXPECT_EQ(lines.stats.visible_length_px, reference.lines.stats.visible_length_px);
            } else {
                // A refitted BVH and a new one answer alike up to float rounding.
                const double length = visible_length(reference.lines);
                EXPECT_NEAR(visible_length(lines), length, (1.0 - kMinAgreement) * length);
            }
            if (frame == 1) first_length = visible_length(lines);
        }
        EXPECT_GT(std::abs(visible_length(drawn.back().lines) - first_length), 20.0)
            << "the sliding sphere must change what is hidden";
    }
};

TEST_F(DeformingSequence, ExactTestIsBuiltAgainForEachFramesPositions) { check(core::VisibilityMode::kExact); }

TEST_F(DeformingSequence, RaycastBvhIsRefittedToEachFramesPositions) {
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree";
    check(core::VisibilityMode::kRaycast);
}

TEST(FramePipeline, OccludedPartsAreSetAsideWithoutLinesHiddenAndOutputWithIt) {
    const core::Mesh mesh = torus_behind_sphere(0.0f);
    core::Scene scene = test::scene_for(kView, mesh);
    core::MeshFrames meshes(mesh);
    const core::FrameResult shown = core::FramePipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact)).run(1);
    scene.lines.hidden = true;
    const core::FrameResult all = core::FramePipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact)).run(1);
    size_t hidden = 0;
    for (const core::Polyline& p : shown.lines.polylines) EXPECT_TRUE(p.visible);
    for (const core::Polyline& p : all.lines.polylines) hidden += !p.visible;
    EXPECT_GT(shown.lines.occluded.size(), 0u) << "kept for gap bridging";
    EXPECT_EQ(hidden, shown.lines.occluded.size());
    EXPECT_TRUE(all.lines.occluded.empty());
    EXPECT_EQ(all.lines.polylines.size(), shown.lines.polylines.size() + shown.lines.occluded.size());
    for (size_t i = 0; i < shown.lines.polylines.size(); ++i) EXPECT_EQ(shown.lines.polylines[i].id, i) << "numbered again";
    EXPECT_EQ(shown.lines.stats.visible_length_px, all.lines.stats.visible_length_px);
}

TEST(FramePipeline, ReportsItsStepsAndStageTimesAndTheFramesMesh) {
    const core::Mesh mesh = test::torus(1.0, 0.35, 48, 24);
    core::MeshFrames meshes(mesh);
    std::vector<std::string> steps;
    core::FramePipeline pipeline(turntable(mesh, 4), meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact),
                                 {.step_done = [&](const char* step) { steps.push_back(step); }});
    const core::FrameResult first = pipeline.run(1);
    EXPECT_EQ(steps, (std::vector<std::string>{"load", "tracker build", "extract", "chain", "occlusion", "visibility",
                                               "strokes"}));
    steps.clear();
    const core::FrameResult second = pipeline.run(2);
    EXPECT_EQ(steps, (std::vector<std::string>{"load", "extract", "chain", "occlusion", "visibility", "strokes"}));
    std::vector<std::string> stages;
    for (const auto& [stage, ms] : second.lines.stats.ms) {
        stages.push_back(stage);
        EXPECT_GE(ms, 0.0);
    }
    EXPECT_EQ(stages, (std::vector<std::string>{"load", "extract", "chain", "visibility", "strokes"}));
    EXPECT_EQ(second.mesh, &meshes.at(2));
    EXPECT_EQ(second.lines.frame, 2);
    EXPECT_EQ(second.lines.stats.faces, mesh.triangles.size());
    EXPECT_EQ(second.lines.stats.edges, meshes.edges().edge_count());
    EXPECT_FALSE(second.strokes.strokes.empty());
    // Stroke coherence carries frame 1's strokes into frame 2.
    EXPECT_FALSE(first.strokes.strokes.empty());
    EXPECT_EQ(first.strokes.stats.inherited, 0u);
    EXPECT_GT(second.strokes.stats.inherited, 0u);
}

TEST(FramePipeline, WarnsOnceWhenTheCameraIsInsideTheMeshBounds) {
    const core::Mesh mesh = test::cube(2.0);
    core::Scene scene = test::scene_for({.eye = {0.5, 0.2, 0.3}, .target = {0.0, 0.0, -3.0}}, mesh);
    scene.last_frame = 3;
    core::MeshFrames meshes(mesh);
    std::vector<std::string> warnings;
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    for (int frame = 1; frame <= 3; ++frame) {
        for (const std::string& w : pipeline.run(frame).warnings) warnings.push_back(w);
    }
    EXPECT_EQ(warnings, (std::vector<std::string>{
                            "frame 1: the camera is inside the mesh's bounds; lines may be hidden"}));
}

// A camera that looks away from the mesh draws nothing: said once, and the frames are written.
TEST(FramePipeline, WarnsOnceWhenTheMeshIsWhollyOutOfView) {
    const core::Mesh mesh = test::cube(1.0);
    for (const glm::dvec3 target : {glm::dvec3(0.0, 0.0, 20.0), glm::dvec3(-40.0, 0.0, 5.0)}) {  // behind, to the side
        core::Scene scene = test::scene_for({.eye = {0.0, 0.0, 5.0}, .target = target}, mesh);
        scene.last_frame = 3;
        core::MeshFrames meshes(mesh);
        std::vector<std::string> warnings;
        core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
        for (int frame = 1; frame <= 3; ++frame) {
            const core::FrameResult r = pipeline.run(frame);
            EXPECT_TRUE(r.strokes.strokes.empty());
            for (const std::string& w : r.warnings) warnings.push_back(w);
        }
        EXPECT_EQ(
            warnings,
            (std::vector<std::string>{"frame 1: the mesh is wholly outside the camera's view; nothing is drawn"}));
    }
    // In view, no warning.
    const core::Scene seen = test::scene_for({.eye = {0.0, 0.0, 5.0}}, mesh);
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(seen, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    EXPECT_TRUE(pipeline.run(1).warnings.empty());
}

TEST(FramePipeline, AFrameThatCannotBeReadThrowsAndTheNextFrameIsDrawn) {
    const fs::path dir = test::fresh_temp_dir("AFrameThatCannotBeReadThrowsAndTheNextFrameIsDrawn");
    test::write_obj(dir / "f1.obj", test::cube(1.0));
    test::write_obj(dir / "f2.obj", test::uv_sphere(16, 8, 1.0));  // another topology
    test::write_obj(dir / "f3.obj", test::cube(1.2));
    core::Scene scene = test::scene_for(kView, test::cube(1.2));
    scene.mesh = {.path = dir / "f%d.obj", .is_sequence = true};
    scene.last_frame = 3;
    core::MeshFrames meshes(scene.mesh, 1);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    EXPECT_FALSE(pipeline.run(1).lines.polylines.empty());
    EXPECT_THROW(pipeline.run(2), InputError);
    const core::FrameResult third = pipeline.run(3);
    EXPECT_EQ(third.lines.frame, 3);
    EXPECT_FALSE(third.lines.polylines.empty());
    fs::remove_all(dir);
}

// On a mesh that holds still, run() finds the next frame's lines on a second thread while the
// caller has this frame; a step_done callback turns that off. Both must draw the same, also when
// the frames are asked for out of order (a frame found ahead and not asked for is dropped).
TEST(FramePipeline, LinesFoundAheadDrawTheSameAsLinesFoundInTurn) {
    const core::Mesh mesh = torus_behind_sphere(0.0f);
    const core::Scene scene = turntable(mesh, 8);
    core::MeshFrames ahead_meshes(mesh), in_turn_meshes(mesh);
    core::FramePipeline ahead(scene, ahead_meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    core::FramePipeline in_turn(scene, in_turn_meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact),
                                {.step_done = [](const char*) {}});
    for (const int frame : {1, 2, 3, 6, 4, 5, 8, 7}) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        const core::FrameResult a = ahead.run(frame), b = in_turn.run(frame);
        EXPECT_EQ(a.lines.frame, frame);
        expect_same_lines(a.lines, b.lines);
        expect_same_strokes(a.strokes, b.strokes);
        EXPECT_EQ(a.lines.stats.feature_edges, b.lines.stats.feature_edges);
        EXPECT_EQ(a.lines.camera.eye, b.lines.camera.eye);
        EXPECT_EQ(a.mesh, &ahead_meshes.at(frame));
    }
}

// A mesh that moves in memory, as a skinned glTF shot does: frame f's mesh is MeshAt(f).
template <core::Mesh (*MeshAt)(int)>
class MovingMesh final : public core::AnimatedMesh {
  public:
    static core::Mesh mesh_at(int frame) { return MeshAt(frame); }
    const core::Mesh& rest() const override { return rest_; }
    bool deforms() const override { return true; }
    void positions_at(int frame, std::vector<glm::vec3>& r_positions) const override {
        r_positions = mesh_at(frame).positions;
    }

  private:
    core::Mesh rest_ = mesh_at(1);
};

// The sphere slides across the torus.
core::Mesh sliding_sphere_at(int frame) { return torus_behind_sphere(-0.9f + 0.3f * float(frame - 1)); }
using SlidingSphere = MovingMesh<sliding_sphere_at>;

// A moving mesh is kept twice over: the mesh of a frame stays as it was while the next frame's is
// made, and is made again only after two other frames.
TEST(MeshFrames, AMovingMeshKeepsTheFrameBeforeWhileTheNextIsMade) {
    core::MeshFrames meshes(std::make_shared<SlidingSphere>(), "sliding");
    const core::Mesh& first = meshes.at(1);
    const core::Mesh& second = meshes.at(2);
    EXPECT_NE(&first, &second);
    EXPECT_EQ(first.positions, SlidingSphere::mesh_at(1).positions);
    EXPECT_EQ(second.positions, SlidingSphere::mesh_at(2).positions);
    EXPECT_EQ(first.triangles, second.triangles);
    EXPECT_EQ(&meshes.at(1), &first) << "the frame before, asked again, is not made again";
    EXPECT_EQ(&meshes.at(3), &second) << "a third frame takes the copy of the frame before the last asked";
    EXPECT_EQ(first.positions, SlidingSphere::mesh_at(1).positions);
    EXPECT_EQ(second.positions, SlidingSphere::mesh_at(3).positions);
}

// On a moving mesh too, the next frame's lines (and their visibility) are found while the caller
// has this frame, into the second copy of the mesh: each frame draws what a pipeline finding
// every frame in turn draws, and the frame's mesh is its own while the next frame's is made.
// With a tone, which queries the frame's occlusion test, the next frame is looked for after it.
TEST(FramePipeline, LinesFoundAheadOnAMovingMeshDrawTheSameAsLinesFoundInTurn) {
    for (const bool tone : {false, true}) {
        SCOPED_TRACE(tone ? "stippled" : "lines only");
        core::Scene scene = turntable(SlidingSphere::mesh_at(1), 7);
        if (tone) scene.tone = {.mode = core::ToneMode::kStipple, .curve = {.max = 0.6}};
        for (const core::VisibilityMode mode : {core::VisibilityMode::kExact, core::VisibilityMode::kRaycast}) {
            if (mode == core::VisibilityMode::kRaycast && !core::raycast_available()) continue;
            SCOPED_TRACE(core::visibility_mode_name(mode));
            core::MeshFrames ahead_meshes(std::make_shared<SlidingSphere>(), "sliding");
            core::MeshFrames in_turn_meshes(std::make_shared<SlidingSphere>(), "sliding");
            core::FramePipeline ahead(scene, ahead_meshes, core::make_cpu_occlusion(mode));
            core::FramePipeline in_turn(scene, in_turn_meshes, core::make_cpu_occlusion(mode),
                                        {.step_done = [](const char*) {}});
            for (const int frame : {1, 2, 3, 6, 4, 5, 7}) {
                SCOPED_TRACE("frame " + std::to_string(frame));
                const core::FrameResult a = ahead.run(frame), b = in_turn.run(frame);
                expect_same_lines(a.lines, b.lines);
                expect_same_strokes(a.strokes, b.strokes);
                ASSERT_EQ(a.tone.dots.size(), b.tone.dots.size());
                for (size_t i = 0; i < a.tone.dots.size(); ++i) {
                    EXPECT_EQ(a.tone.dots[i].sample, b.tone.dots[i].sample);
                    EXPECT_EQ(a.tone.dots[i].point_px, b.tone.dots[i].point_px);
                }
                EXPECT_EQ(a.tone.dots.empty(), !tone);
                ASSERT_NE(a.mesh, nullptr);
                EXPECT_EQ(a.mesh->positions, SlidingSphere::mesh_at(frame).positions)
                    << "the frame's mesh, while the next frame's is being made";
            }
        }
    }
}

// A process forked while the next frame's lines were being found (a Python program handing
// frames to forked workers, say) has no worker thread: it must draw on, the same lines, not wait
// for a thread that is not there.
TEST(FramePipeline, AForkedProcessDrawsOnWithoutTheWorkerThread) {
    const core::Mesh mesh = torus_behind_sphere(0.0f);
    const core::Scene scene = turntable(mesh, 6);
    core::MeshFrames reference_meshes(mesh);
    const auto reference = run_all(scene, reference_meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact),
                                   {.step_done = [](const char*) {}});
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    (void)pipeline.run(1);  // frame 2's lines are now being found ahead
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        alarm(60);  // a child that waits for the missing thread is killed, and the test fails
        int wrong = 0;
        for (int frame = 2; frame <= 4; ++frame) {
            const core::FrameResult drawn = pipeline.run(frame);
            const core::FrameLines& want = reference[size_t(frame - 1)].lines;
            if (drawn.lines.polylines.size() != want.polylines.size()) ++wrong;
            for (size_t i = 0; i < std::min(drawn.lines.polylines.size(), want.polylines.size()); ++i) {
                wrong += drawn.lines.polylines[i].points_px != want.polylines[i].points_px;
            }
        }
        _exit(wrong == 0 ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "the forked process was stopped (signal " << WTERMSIG(status) << ")";
    EXPECT_EQ(WEXITSTATUS(status), 0) << "the forked process drew other lines";
    expect_same_lines(pipeline.run(2).lines, reference[1].lines);  // the parent goes on as before
}

// A bumpy sphere before a torus, moved along x by `shift`: the bumps give the silhouette dips
// behind their neighbouring faces, short occluded gaps for the stroke repairs.
core::Mesh bumps_before_torus(float shift) {
    return test::combine(test::bumpy_sphere(test::icosphere(5), {.count = 60, .height_max = 0.12}),
                         test::torus(1.0, 0.35, 48, 24), {0.3f + shift, -0.2f, -1.4f});
}

// A shot that holds still (the same mesh and camera as the frame before) draws the lines,
// strokes and tone the frame before drew, and from its first frame those of a run of that frame
// alone: the stroke
// repairs that read last frame's strokes would answer otherwise there, and, in a tangle, could
// answer one way and the other in turn (the shot would flicker). Once the camera moves, strokes
// are made again; when it stops, the frames hold from there.
TEST(FramePipeline, AHeldShotDrawsTheStrokesOfTheFrameBefore) {
    const core::Mesh mesh = bumps_before_torus(0.0f);
    core::Scene scene = test::scene_for(kView, mesh);
    scene.last_frame = 8;
    scene.tone = {.mode = core::ToneMode::kStipple, .curve = {.max = 0.6}};
    for (int frame = 1; frame <= 8; ++frame) {
        const double turn = frame <= 4 ? 0.0 : 0.05 * std::min(frame - 4, 3);  // still, moving, still
        scene.camera.per_frame[frame] = {.eye = {kView.eye.x + turn, kView.eye.y, kView.eye.z}, .fov_y_deg = 40.0};
    }
    core::MeshFrames meshes(mesh), alone_meshes(mesh);
    const std::vector<core::FrameResult> frames =
        run_all(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast));
    core::Scene first_alone = scene;
    first_alone.last_frame = 1;
    const std::vector<core::FrameResult> alone =
        run_all(first_alone, alone_meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast));
    ASSERT_GT(frames[0].strokes.stats.bridges, 0u) << "the shot must have gaps for the repairs to bridge";
    expect_same_strokes(frames[0].strokes, alone[0].strokes);
    for (const int frame : {2, 3, 4, 8}) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        // The lines of a held frame are taken as they were found: the same as found afresh.
        core::Scene only = scene;
        only.first_frame = only.last_frame = frame;
        core::MeshFrames only_meshes(mesh);
        const core::FrameResult afresh =
            run_all(only, only_meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast))[0];
        expect_same_lines(frames[size_t(frame - 1)].lines, afresh.lines);
        EXPECT_EQ(frames[size_t(frame - 1)].lines.stats.feature_edges, afresh.lines.stats.feature_edges);
        // And its dots: those of the frame before; while that one's strokes are those of the
        // first frame (a run of one frame's), the same as drawn afresh (the dots keep off the ink).
        const std::vector<core::Dot>& dots = frames[size_t(frame - 1)].tone.dots;
        const std::vector<core::Dot>& dots_before = frames[size_t(frame - 2)].tone.dots;
        ASSERT_FALSE(dots.empty());
        ASSERT_EQ(dots.size(), dots_before.size());
        for (size_t i = 0; i < dots.size(); ++i) EXPECT_EQ(dots[i].point_px, dots_before[i].point_px);
        if (frame <= 4) {
            ASSERT_EQ(dots.size(), afresh.tone.dots.size());
            for (size_t i = 0; i < dots.size(); ++i) EXPECT_EQ(dots[i].sample, afresh.tone.dots[i].sample);
        }
        const core::FrameStrokes& held = frames[size_t(frame - 1)].strokes;
        const core::FrameStrokes& before = frames[size_t(frame - 2)].strokes;
        expect_same_strokes(held, before);
        EXPECT_EQ(held.frame, frame);
        EXPECT_EQ(held.stats.inherited, held.strokes.size());
        EXPECT_EQ(held.stats.inherited_length_px, held.stats.visible_length_px);
    }
    EXPECT_NE(frames[4].lines.camera.eye, frames[3].lines.camera.eye);
    EXPECT_NE(frames[4].strokes.strokes[0].geometry.points_px, frames[3].strokes.strokes[0].geometry.points_px)
        << "the camera moved: strokes made again";
}

// A first frame has no memory for the stroke repairs, which then join less than the frame after
// it would: it is drawn as if it followed itself, so that the frame after it, the camera having
// barely moved, keeps its strokes (drawn once, a noisy terrain kept 93% of them and a wavy torus
// 80%).
TEST(FramePipeline, TheFrameAfterTheFirstKeepsItsStrokes) {
    struct Case {
        const char* name;
        core::Mesh mesh;
        double kept;  // the least share of the first frame's strokes whose ids the second keeps
    };
    const Case cases[] = {{"noisy terrain", test::noise_terrain(96, 0.3), 0.98},
                          {"wavy torus", test::wavy_torus(200, 60, 0.15, 0.05), 0.93}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        core::Scene scene = test::scene_for(kView, c.mesh);
        scene.last_frame = 2;
        for (const int frame : {1, 2}) {
            scene.camera.per_frame[frame] = {.eye = {kView.eye.x + 0.002 * frame, kView.eye.y, kView.eye.z},
                                             .fov_y_deg = 40.0};
        }
        core::MeshFrames meshes(c.mesh);
        const std::vector<core::FrameResult> frames =
            run_all(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast));
        const core::FrameStrokes &first = frames[0].strokes, &second = frames[1].strokes;
        ASSERT_GT(first.stats.bridges, 0u) << "the shot must have gaps for the repairs to bridge";
        EXPECT_EQ(first.stats.inherited, 0u) << "no frame before the first";
        std::set<uint32_t> second_ids;
        for (const core::Stroke& stroke : second.strokes) second_ids.insert(stroke.id);
        size_t kept = 0;
        for (const core::Stroke& stroke : first.strokes) kept += second_ids.count(stroke.id);
        EXPECT_GE(double(kept), c.kept * double(first.strokes.size())) << kept << " of " << first.strokes.size();
    }
}

// A moving mesh (a skinned or morphing shot) under a still camera holds too, while it stands
// still: here at frames 1-3, then it slides, then stops again from frame 6.
core::Mesh still_slide_still_at(int frame) { return bumps_before_torus(0.1f * float(std::clamp(frame, 3, 6) - 3)); }
using StillSlideStill = MovingMesh<still_slide_still_at>;

TEST(FramePipeline, AMovingMeshThatStandsStillHoldsTheStrokesOfTheFrameBefore) {
    core::Scene scene = test::scene_for(kView, StillSlideStill::mesh_at(1));
    scene.last_frame = 8;
    core::MeshFrames meshes(std::make_shared<StillSlideStill>(), "still, slide, still");
    const std::vector<core::FrameResult> frames =
        run_all(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast));
    const auto points = [&](int frame) {
        std::vector<std::vector<glm::dvec2>> lines;
        for (const core::Stroke& stroke : frames[size_t(frame - 1)].strokes.strokes) {
            lines.push_back(stroke.geometry.points_px);
        }
        return lines;
    };
    for (const int frame : {4, 5, 6}) {
        EXPECT_NE(points(frame), points(frame - 1)) << "frame " << frame << ": the mesh moved";
    }
    for (const int frame : {2, 3, 7, 8}) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        expect_same_strokes(frames[size_t(frame - 1)].strokes, frames[size_t(frame - 2)].strokes);
        EXPECT_EQ(frames[size_t(frame - 1)].strokes.stats.inherited, frames[size_t(frame - 1)].strokes.strokes.size());
    }
}

// A frame whose lines cannot be found (here: no camera for it) throws from its own run(), even
// when they were looked for ahead, during the frame before; the frame after it is drawn.
TEST(FramePipeline, AFrameWithoutACameraThrowsFromItsOwnRunAndTheNextIsDrawn) {
    const core::Mesh mesh = test::cube(1.0);
    core::Scene scene = test::scene_for(kView, mesh);
    scene.last_frame = 4;
    for (const int frame : {1, 2, 4}) {
        scene.camera.per_frame[frame] = {.eye = kView.eye + glm::dvec3(0.1 * frame, 0.0, 0.0), .fov_y_deg = 40.0};
    }
    core::MeshFrames meshes(mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact));
    EXPECT_FALSE(pipeline.run(1).lines.polylines.empty());
    EXPECT_FALSE(pipeline.run(2).lines.polylines.empty());
    EXPECT_THROW(pipeline.run(3), InputError);
    const core::FrameResult fourth = pipeline.run(4);
    EXPECT_EQ(fourth.lines.frame, 4);
    EXPECT_FALSE(fourth.lines.polylines.empty());
}

}  // namespace
}  // namespace inkline
