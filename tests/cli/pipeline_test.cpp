// SPDX-License-Identifier: MIT
// The library pipeline draws what `inkline render` writes: core::FramePipeline's frames, written
// with output::polylines_json, equal the CLI's polylines JSON (timings aside).
#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/frame_pattern.h"
#include "core/scene/scene.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "export/json.h"
#include "tests/support/obj.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include <string>

namespace inkline {
namespace {

namespace fs = std::filesystem;

nlohmann::json without_timings(const std::string& text) {
    nlohmann::json doc = nlohmann::json::parse(text);
    doc["stats"].erase("ms");
    return doc;
}

class LibraryPipeline : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // Renders `scene_file` with the CLI (`options` added) to JSON, draws frames first..last of
    // the same scene through the library, and compares each frame.
    void expect_same_as_cli(const fs::path& scene_file, const std::string& options, core::VisibilityMode mode,
                            int first, int last, core::PipelineOptions pipeline_options = {}, bool hidden = false) {
        const std::string pattern = (dir / "cli" / "f_%04d.json").string();
        const test::RunResult r = test::run_inkline("render " + scene_file.string() + " --visibility " +
                                                    core::visibility_mode_name(mode) + " " + options +
                                                    (hidden ? " --hidden" : "") + " -q --json " + pattern);
        ASSERT_EQ(r.code, 0) << r.output;

        // What an outside program writes.
        core::Scene scene = core::load_scene(scene_file);
        scene.lines.hidden = scene.lines.hidden || hidden;
        core::MeshFrames meshes(scene.mesh, first);
        core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(mode), std::move(pipeline_options));
        for (int frame = first; frame <= last; ++frame) {
            SCOPED_TRACE("frame " + std::to_string(frame));
            const core::FrameResult f = pipeline.run(frame);
            const nlohmann::json cli = without_timings(test::read_text(core::format_frame(pattern, frame)));
            const nlohmann::json library = without_timings(output::polylines_json(f.lines, &f.strokes));
            EXPECT_EQ(library, cli);
            EXPECT_EQ(library["stats"]["visibility"]["reason"], "asked for");
            EXPECT_FALSE(library["strokes"].empty());
        }
    }

    // A torus whose tube swells from frame to frame (a deforming sequence), frames 1..3.
    fs::path swelling_torus() {
        for (int frame = 1; frame <= 3; ++frame) {
            test::write_obj(dir / "anim" / ("t" + std::to_string(frame) + ".obj"),
                            test::torus(1.0, 0.3 + 0.05 * frame, 48, 24));
        }
        test::write_text(dir / "scene.json", R"({"mesh": {"sequence": "anim/t%d.obj"}, "frames": [1, 3],
            "image": {"width": 512, "height": 512},
            "camera": {"eye": [0.5, 1.4, 3.5], "target": [0, 0, 0], "orbit": {"axis": [0, 1, 0], "degrees": 90}}})");
        return dir / "scene.json";
    }
};

const fs::path kSample = fs::path(INKLINE_SAMPLES) / "torus" / "scene.json";

TEST_F(LibraryPipeline, SampleFramesEqualTheClisWithRayCasting) {
    if (!core::raycast_available()) GTEST_SKIP() << "this build has no Embree";
    expect_same_as_cli(kSample, "--frames 1:4", core::VisibilityMode::kRaycast, 1, 4);
}

TEST_F(LibraryPipeline, SampleFramesWithHiddenLinesEqualTheClisWithExactVisibility) {
    expect_same_as_cli(kSample, "--frames 1:3", core::VisibilityMode::kExact, 1, 3, {}, true);
}

TEST_F(LibraryPipeline, OneFrameEqualsTheClisOneFrameRun) {
    // `--frames 7` is a run of one frame: brute force, as PipelineOptions::frame_count = 1 asks.
    expect_same_as_cli(kSample, "--frames 7", core::VisibilityMode::kExact, 7, 7, {.frame_count = 1});
}

TEST_F(LibraryPipeline, DeformingSequenceEqualsTheCli) {
    // The whole scene, as an outside program draws it with the default options.
    expect_same_as_cli(swelling_torus(), "", core::VisibilityMode::kExact, 1, 3);
    expect_same_as_cli(swelling_torus(), "", core::VisibilityMode::kExact, 1, 3, {}, true);
}

}  // namespace
}  // namespace inkline
