// SPDX-License-Identifier: MIT
// Hostile input, the command line: outputs that would replace an input or one another, options
// a bare mesh must honour, frame numbers past the documented range, Slurm scripts built from
// hostile names. Each case asserts the exit code, the one-line message and the state of every
// file involved afterwards (tests/support/hostile.h).
#include "tests/support/hostile.h"
#include "tests/support/shapes.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <sys/stat.h>

namespace inkline {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A path as one shell word.
std::string q(const fs::path& p) {
    std::string out = "'";
    for (char c : p.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

class HostileCli : public test::HostileTest {
  protected:
    // A cube mesh and a scene that draws it, in `dir`.
    void SetUp() override {
        test::write_obj(dir / "cube.obj", test::cube(1.0));
        test::write_text(dir / "scene.json", R"({"mesh": "cube.obj", "frames": [1, 2], "image": {"width": 64, "height": 64},
            "camera": {"eye": [3, 2.5, 4], "target": [0, 0, 0]}})");
    }

    // Runs a render that must be refused, and checks that no file in `dir` changed.
    void expect_refused(const std::string& args, int code, const std::string& needle) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_inkline("render " + args + " -q");
        test::expect_one_line_error(r, code, needle);
        EXPECT_EQ(test::changed_entries(before, test::folder_state(dir)), std::vector<std::string>{}) << args;
    }
};

// Class 3c: an output that is an input, under any spelling or link, is refused before anything
// is written.
TEST_F(HostileCli, OutputNamingTheMeshIsRefused) {
    expect_refused(q(dir / "cube.obj") + " --frames 1 --json " + q(dir / "cube.obj") + " --svg " + q(dir / "f.svg"), 2,
                   "--json would replace the mesh it reads");
    expect_refused(q(dir / "cube.obj") + " --frames 1 --svg " + q(dir / "sub" / ".." / "cube.obj"), 2,
                   "--svg would replace the mesh");
}

TEST_F(HostileCli, OutputLinkedToTheSceneIsRefused) {
    fs::create_directories(dir / "out" / "svg");
    fs::create_symlink(dir / "scene.json", dir / "out" / "svg" / "frame_0002.svg");
    expect_refused(q(dir / "scene.json") + " -o " + q(dir / "out"), 2, "--svg would replace the scene it reads");
    fs::create_hard_link(dir / "cube.obj", dir / "out" / "frame_0001.png");
    expect_refused(q(dir / "scene.json") + " --png " + q(dir / "out" / "frame_%04d.png"), 2,
                   "--png would replace the mesh it reads");
}

TEST_F(HostileCli, OutputNamingAFrameOfTheMeshSequenceIsRefused) {
    for (int f = 1; f <= 3; ++f) test::write_obj(dir / "anim" / ("f" + std::to_string(f) + ".obj"), test::cube(1.0 + 0.1 * f));
    test::write_text(dir / "seq.json", R"({"mesh": {"sequence": "anim/f%d.obj"}, "frames": [1, 3], "image": {"width": 64, "height": 64},
        "camera": {"eye": [3, 2.5, 4], "target": [0, 0, 0]}})");
    // Frame N's JSON would be the mesh of frame N.
    expect_refused(q(dir / "seq.json") + " --json " + q(dir / "anim" / "f%d.obj"), 2, "--json would replace the mesh it reads");
    // A chunk too.
    expect_refused(q(dir / "seq.json") + " --chunk 3/3 --svg " + q(dir / "anim" / "f%d.obj"), 2,
                   "--svg would replace the mesh it reads");
}

// A scene's brush tip is an input whether or not the preview draws with it.
TEST_F(HostileCli, OutputNamingTheBrushTipIsRefused) {
    test::write_text(dir / "tip.png", "not read: the check comes first");
    test::write_text(dir / "tip.json", R"({"mesh": "cube.obj", "frames": [1, 1], "image": {"width": 64, "height": 64},
        "camera": {"eye": [3, 2.5, 4], "target": [0, 0, 0]}, "brush": {"tip": "tip.png"}})");
    for (const char* option : {"--preview", "--png"}) {
        expect_refused(q(dir / "tip.json") + " " + option + " " + q(dir / "tip.png"), 2,
                       std::string(option) + " would replace the brush tip");
    }
}

// Class 3c: two outputs that expand to the same file, in the same frame or in different ones.
TEST_F(HostileCli, TwoOutputsNamingOneFileAreRefused) {
    expect_refused(q(dir / "cube.obj") + " --frames 1 --json " + q(dir / "a.out") + " --svg " + q(dir / "." / "a.out"), 2,
                   "--json and --svg would write the same file");
    // Frame 11's SVG and frame 1's JSON are both f11.x; frames 1-10 would be written first.
    expect_refused(q(dir / "cube.obj") + " --frames 1:12 --json " + q(dir / "f1%d.x") + " --svg " + q(dir / "f%d.x"), 2,
                   "would write the same file");
    // %d and %04d agree from frame 1000 on.
    expect_refused(q(dir / "cube.obj") + " --frames 998:1001 --png " + q(dir / "p%d.png") + " --svg " +
                       q(dir / "p%04d.png"),
                   2, "would write the same file");
    // The same folder reached through a link.
    fs::create_directory_symlink(dir, dir / "alias");
    expect_refused(q(dir / "cube.obj") + " --frames 1 --json " + q(dir / "b.out") + " --pdf " + q(dir / "alias" / "b.out"),
                   2, "would write the same file");
}

TEST_F(HostileCli, DistinctOutputsWithSimilarPatternsAreWritten) {
    const test::RunResult r = test::run_inkline("render " + q(dir / "cube.obj") + " -q --frames 1:12 --json " +
                                                q(dir / "f%d.json") + " --svg " + q(dir / "f%02d.svg"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "f12.json"));
    EXPECT_TRUE(fs::exists(dir / "f01.svg"));
}

// Class 3c: an existing read-only output is refused, not replaced, also for root.
TEST_F(HostileCli, ReadOnlyOutputIsRefusedBeforeAnythingIsWritten) {
    test::write_text(dir / "out" / "svg" / "frame_0002.svg", "kept\n");
    fs::permissions(dir / "out" / "svg" / "frame_0002.svg", fs::perms::owner_read | fs::perms::group_read);
    expect_refused(q(dir / "scene.json") + " -o " + q(dir / "out"), 3, "frame_0002.svg: is read-only; not replaced");
    EXPECT_EQ(test::read_text(dir / "out" / "svg" / "frame_0002.svg"), "kept\n");
    EXPECT_FALSE(fs::exists(dir / "out" / "json"));
}

// Class 6: a bare mesh is drawn with the options given, not the default turntable's.
TEST_F(HostileCli, BareMeshHonoursSizeAndHidden) {
    const test::RunResult r = test::run_inkline("render " + q(dir / "cube.obj") + " -q --frames 1 --size 256x128 --hidden " +
                                                "--json " + q(dir / "f.json") + " --svg " + q(dir / "f.svg"));
    ASSERT_EQ(r.code, 0) << r.output;
    const json frame = json::parse(test::read_text(dir / "f.json"));
    EXPECT_EQ(frame["image"]["width"], 256);
    EXPECT_EQ(frame["image"]["height"], 128);
    size_t hidden = 0;
    for (const json& s : frame["strokes"]) hidden += s["visible"] == false;
    EXPECT_GT(hidden, 0u) << "a cube seen from above has hidden back edges";
    const std::string svg = test::read_text(dir / "f.svg");
    EXPECT_NE(svg.find("width=\"256\""), std::string::npos);
    EXPECT_NE(svg.find("height=\"128\""), std::string::npos);
}

// Class 4c: frame numbers beyond the documented range are refused, not wrapped or looped over.
TEST_F(HostileCli, FrameNumbersOutsideTheRangeAreRefused) {
    for (const std::string frames : {"1:2147483647", "1:4294967298", "-5000000000:1", "1000000000", "1:99999999999999999999"}) {
        const std::string needle = frames.size() > 20 ? "expected A:B" : "frame numbers must be between -999999999 and 999999999";
        expect_refused(q(dir / "cube.obj") + " --frames " + frames + " -o " + q(dir / "out"), 2, needle);
    }
    const test::RunResult r = test::run_inkline("render " + q(dir / "cube.obj") + " -q --frames 999999998:999999999 --json " +
                                                q(dir / "f%d.json"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "f999999999.json"));
}

// Class 9: Slurm's task variables must be numbers.
TEST_F(HostileCli, NonNumericSlurmTaskIsRefused) {
    for (const std::string id : {"abc", "1x", "", " "}) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_shell("SLURM_ARRAY_TASK_ID='" + id + "' SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=2 " +
                                                  test::inkline_command() + " render " + q(dir / "scene.json") +
                                                  " -q --chunk slurm -o " + q(dir / "out"));
        test::expect_one_line_error(r, 2, "SLURM_ARRAY_TASK_ID");
        EXPECT_TRUE(test::changed_entries(before, test::folder_state(dir)).empty());
    }
}

// Class 7: nothing the user names reaches a Slurm script unquoted.
TEST_F(HostileCli, FarmScriptsQuoteHostileNames) {
    const fs::path scene = dir / "a\ntouch PWNED\n'$(touch PWNED2)'.json";
    fs::copy_file(dir / "scene.json", scene);
    const fs::path out = dir / "out #x 'y'";
    const test::RunResult r = test::run_inkline("farm " + q(scene) + " --chunks 2 -o " + q(out) +
                                                " --partition 'a b' -- --frames 1:2");
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* script : {"render.sbatch", "summary.sbatch", "submit.sh"}) {
        // Every line is a comment, a #SBATCH directive or a command whose words are quoted.
        const test::RunResult syntax = test::run_shell("bash -n " + q(out / "slurm" / script));
        EXPECT_EQ(syntax.code, 0) << syntax.output;
    }
    EXPECT_NE(test::read_text(out / "slurm" / "render.sbatch").find("#SBATCH \"--partition=a b\"\n"), std::string::npos);
    // Run as a job would, outside Slurm: the render refuses (no task id), nothing else runs.
    const test::RunResult job = test::run_shell("cd " + q(dir) + " && bash " + q(out / "slurm" / "render.sbatch"));
    EXPECT_EQ(job.code, 2) << job.output;
    EXPECT_NE(job.output.find("SLURM_ARRAY_TASK_ID is not set"), std::string::npos) << job.output;
    EXPECT_FALSE(fs::exists(dir / "PWNED"));
    EXPECT_FALSE(fs::exists(dir / "PWNED2"));
}

TEST_F(HostileCli, FarmRefusesWhatASlurmDirectiveCannotHold) {
    for (const std::string option : {"--partition $'debug\\nrm -rf /tmp/x'", "--mem '4G\"'", "--time $'1:00\\r'",
                                     "--sbatch=$'--account=lab\\n#SBATCH --uid=0'", "--sbatch='--comment=a\\b'"}) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_shell(test::inkline_command() + " farm " + q(dir / "scene.json") +
                                                  " --chunks 2 -o " + q(dir / "out") + " " + option);
        test::expect_one_line_error(r, 2, "cannot be written into a Slurm #SBATCH line");
        EXPECT_TRUE(test::changed_entries(before, test::folder_state(dir)).empty()) << option;
    }
}

// What can be known before the first frame is checked before the first frame: no run writes
// some frames and then stops on a name, a camera or a size it was given from the start.
TEST_F(HostileCli, OverlongOutputNameIsRefusedBeforeAnythingIsWritten) {
    const std::string long_name(250, 'c');
    // Frame 99999 fits in 255 bytes, frame 100000 does not.
    expect_refused(q(dir / "cube.obj") + " --frames 99998:100001 --svg " + q(dir / "s%d.svg") + " --json " +
                       q(dir / (long_name + "%d")),
                   3, "a file or folder name longer than 255 bytes");
}

TEST_F(HostileCli, MissingPerFrameCameraIsRefusedBeforeAnythingIsWritten) {
    test::write_text(dir / "cams.json", R"({"mesh": "cube.obj", "frames": [1, 3], "image": {"width": 64, "height": 64},
        "camera": {"frames": [{"frame": 1, "eye": [3, 2.5, 4], "target": [0, 0, 0]},
                              {"frame": 3, "eye": [3, 2.5, 4], "target": [0, 0, 0]}]}})");
    expect_refused(q(dir / "cams.json") + " -o " + q(dir / "out"), 2, "key 'camera.frames': no camera for frame 2");
    const test::RunResult ok = test::run_inkline("render " + q(dir / "cams.json") + " -q --frames 3 -o " + q(dir / "out"));
    EXPECT_EQ(ok.code, 0) << ok.output;
}

TEST_F(HostileCli, PreviewLargerThanGlCanDrawIsRefusedBeforeAnythingIsWritten) {
    expect_refused(q(dir / "cube.obj") + " --frames 1 --size 40000x8 --max-image-side 40000 --json " + q(dir / "f.json") +
                       " --preview " + q(dir / "p.png"),
                   2, "framebuffer limit");
}

TEST_F(HostileCli, PreviewUnderATightAddressSpaceLimitIsOutOfMemoryNotACrash) {
    if (test::kAddressSanitizer) GTEST_SKIP() << "ulimit -v stops AddressSanitizer from starting";
    for (const int limit_mb : {500, 800, 1200}) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_shell("ulimit -v " + std::to_string(limit_mb * 1024) + "; " +
                                                  test::inkline_command() + " render " + q(dir / "cube.obj") +
                                                  " -q --frames 1 --json " + q(dir / "f.json") + " --preview " +
                                                  q(dir / "p.png"));
        test::expect_one_line_error(r, 5, "OpenGL needs at least 1536 MiB of address space");
        EXPECT_EQ(test::changed_entries(before, test::folder_state(dir)), std::vector<std::string>{}) << limit_mb;
    }
}

// Never lose a frame already written: a failing re-run keeps the complete PDF of an earlier run.
TEST_F(HostileCli, FailingRerunKeepsTheEarlierMultiPagePdf) {
    for (int f = 1; f <= 3; ++f) test::write_obj(dir / "anim" / ("f" + std::to_string(f) + ".obj"), test::cube(1.0 + 0.1 * f));
    test::write_text(dir / "seq.json", R"({"mesh": {"sequence": "anim/f%d.obj"}, "frames": [1, 3], "image": {"width": 64, "height": 64},
        "camera": {"eye": [3, 2.5, 4], "target": [0, 0, 0]}})");
    const std::string run = "render " + q(dir / "seq.json") + " --pdf " + q(dir / "all.pdf");
    ASSERT_EQ(test::run_inkline(run + " -q").code, 0);
    const std::string complete = test::read_text(dir / "all.pdf");
    test::write_text(dir / "anim" / "f3.obj", "garbage\n");
    const test::RunResult failed = test::run_inkline(run);
    EXPECT_EQ(failed.code, 2) << failed.output;
    EXPECT_NE(failed.output.find("all.pdf: kept as it was; the 2 page(s) of this failed run are not written over it"),
              std::string::npos)
        << failed.output;
    EXPECT_TRUE(test::read_text(dir / "all.pdf") == complete);
    // Without an earlier file, the pages drawn before the failure are written.
    fs::remove(dir / "all.pdf");
    EXPECT_EQ(test::run_inkline(run + " -q").code, 2);
    EXPECT_TRUE(fs::exists(dir / "all.pdf"));
}

TEST_F(HostileCli, FarmRefusesOptionsItSetsItself) {
    for (const std::string option : {"--sbatch=--array=1-100", "--sbatch=--output=/tmp/x.log", "--sbatch=-J name",
                                     "--sbatch=--dependency=afterok:1", "--sbatch=notanoption", "-- --chunk 1/2",
                                     "-- -o elsewhere"}) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_shell(test::inkline_command() + " farm " + q(dir / "scene.json") +
                                                  " --chunks 2 -o " + q(dir / "out") + " " + option);
        EXPECT_EQ(r.code, 2) << option << ": " << r.output;
        EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
        EXPECT_TRUE(test::changed_entries(before, test::folder_state(dir)).empty()) << option;
    }
    const test::RunResult ok = test::run_inkline("farm " + q(dir / "scene.json") + " --chunks 2 -o " + q(dir / "out") +
                                                 " --sbatch=--account=lab --time 01:00:00");
    ASSERT_EQ(ok.code, 0) << ok.output;
    for (const char* script : {"render.sbatch", "summary.sbatch"}) {
        const std::string text = test::read_text(dir / "out" / "slurm" / script);
        EXPECT_NE(text.find("#SBATCH --account=lab\n"), std::string::npos) << script;
        EXPECT_NE(text.find("#SBATCH --time=01:00:00\n"), std::string::npos) << script;
    }
}

TEST_F(HostileCli, CountsOutOfRangeAreRefused) {
    expect_refused(q(dir / "scene.json") + " --chunk 1/0 -o " + q(dir / "out"), 2, "N must be at least 1");
    for (const std::string faces : {"-1", "0", "99999999999999999999"}) {
        const test::RunResult r = test::run_inkline("render " + q(dir / "cube.obj") + " -q --max-faces " + faces);
        test::expect_one_line_error(r, 2, "--max-faces");
    }
}

}  // namespace
}  // namespace inkline
