// SPDX-License-Identifier: MIT
// The program under hostile conditions: failing frames, full disks, interruptions, limits.
#include "tests/support/obj.h"
#include "tests/support/run.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

namespace inkline {
namespace {

namespace fs = std::filesystem;

class BadInput : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // A 4-frame cube sequence whose third frame is garbage.
    fs::path corrupt_sequence() {
        for (int f = 1; f <= 4; ++f) {
            core::Mesh cube = test::cube(1.0 + 0.1 * f);
            test::write_obj(dir / "anim" / ("f" + std::to_string(f) + ".obj"), cube);
        }
        test::write_text(dir / "anim" / "f3.obj", "v 0 0 0\nthis is not a mesh\nf 1 2 3\n");
        test::write_text(dir / "scene.json", R"({"mesh": {"sequence": "anim/f%d.obj"}, "frames": [1, 4],
            "camera": {"eye": [3, 2.5, 4], "target": [0, 0, 0]}})");
        return dir / "scene.json";
    }

    // Files in a folder tree that are not complete outputs: temporaries or truncated files.
    static std::vector<std::string> partial_files(const fs::path& root) {
        std::vector<std::string> bad;
        if (!fs::exists(root)) return bad;
        for (const auto& e : fs::recursive_directory_iterator(root)) {
            if (!e.is_regular_file()) continue;
            const std::string name = e.path().filename().string();
            const std::string text = test::read_text(e.path());
            const bool whole = (name.ends_with(".svg") && text.ends_with("</svg>\n")) ||
                               (name.ends_with(".json") && text.ends_with("}\n")) ||
                               (name.ends_with(".png") && text.ends_with(std::string("IEND\xae\x42\x60\x82", 8))) ||
                               (name.ends_with(".pdf") && text.ends_with("%%EOF\n"));
            if (!whole) bad.push_back(e.path().string());
        }
        return bad;
    }
};

TEST_F(BadInput, FailingFrameStopsTheRunAndKeepsEarlierFrames) {
    const test::RunResult r = test::run_inkline("render " + corrupt_sequence().string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("f3.obj"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "out" / "svg" / "frame_0001.svg"));
    EXPECT_TRUE(fs::exists(dir / "out" / "svg" / "frame_0002.svg"));
    EXPECT_FALSE(fs::exists(dir / "out" / "svg" / "frame_0003.svg"));
    EXPECT_FALSE(fs::exists(dir / "out" / "svg" / "frame_0004.svg"));
    EXPECT_TRUE(partial_files(dir / "out").empty());
}

TEST_F(BadInput, KeepGoingRendersTheRest) {
    const test::RunResult r =
        test::run_inkline("render " + corrupt_sequence().string() + " --keep-going -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("frame 3"), std::string::npos) << r.output;
    for (int f : {1, 2, 4}) EXPECT_TRUE(fs::exists(dir / "out" / "json" / ("frame_000" + std::to_string(f) + ".json")));
    EXPECT_FALSE(fs::exists(dir / "out" / "json" / "frame_0003.json"));
}

TEST_F(BadInput, DifferentTopologyNamesTheFrame) {
    corrupt_sequence();
    test::write_obj(dir / "anim" / "f3.obj", test::uv_sphere(8, 4, 1.0));
    const test::RunResult r = test::run_inkline("render " + (dir / "scene.json").string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("f3.obj: frame 3 has a different topology"), std::string::npos) << r.output;
}

TEST_F(BadInput, MissingSequenceFrameNamesTheFile) {
    corrupt_sequence();
    fs::remove(dir / "anim" / "f3.obj");
    const test::RunResult r = test::run_inkline("render " + (dir / "scene.json").string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("f3.obj: file not found"), std::string::npos) << r.output;
}

TEST_F(BadInput, FullDiskIsAnOutputErrorWithoutPartialFiles) {
    test::write_obj(dir / "torus.obj", test::torus(1.0, 0.4, 48, 24));
    // ulimit -f counts 1024-byte blocks: every SVG of this torus is larger than 2 KiB.
    const test::RunResult r = test::run_shell("ulimit -f 2; " + test::inkline_command() + " render " +
                                              (dir / "torus.obj").string() + " --frames 1:3 -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 3) << r.output;
    EXPECT_NE(r.output.find("File too large"), std::string::npos) << r.output;
    EXPECT_TRUE(partial_files(dir / "out").empty());
}

TEST_F(BadInput, InterruptedRunLeavesOnlyWholeFiles) {
    test::write_obj(dir / "torus.obj", test::torus(1.0, 0.4, 160, 80));
    for (int signal_number : {SIGTERM, SIGINT}) {
        fs::remove_all(dir / "out");
        const pid_t child = ::fork();
        if (child == 0) {
            // PNG output at 2048 px keeps every frame busy long enough to be interrupted.
            const std::string input = (dir / "torus.obj").string(), out = (dir / "out").string();
            const std::string png = (dir / "out" / "png" / "f%04d.png").string();
            ::execl(INKLINE_EXE, INKLINE_EXE, "render", input.c_str(), "--size", "2048x2048", "--hidden", "-q", "-o",
                    out.c_str(), "--png", png.c_str(), static_cast<char*>(nullptr));
            ::_exit(127);
        }
        // Interrupt as soon as the first frame is written: mid-sequence, whatever the speed.
        for (int i = 0; i < 500 && !fs::exists(dir / "out" / "json" / "frame_0001.json"); ++i) ::usleep(10 * 1000);
        ::kill(child, signal_number);
        int status = 0;
        ::waitpid(child, &status, 0);
        EXPECT_TRUE(WIFSIGNALED(status)) << "the 48-frame run should still be going when interrupted";
        EXPECT_TRUE(partial_files(dir / "out").empty());
    }
}

TEST_F(BadInput, AnInterruptAtAnyMomentLeavesOnlyWholeFiles) {
    // A frame's files are written on a thread of their own while the next frame is drawn:
    // interrupted anywhere along the run, no temporary is left.
    test::write_obj(dir / "torus.obj", test::torus(1.0, 0.4, 96, 48));
    const std::string input = (dir / "torus.obj").string(), out = (dir / "out").string();
    const std::string pdf = (dir / "out" / "pdf" / "f%04d.pdf").string();
    const auto run = [&] {
        ::execl(INKLINE_EXE, INKLINE_EXE, "render", input.c_str(), "--size", "512x512", "-q", "-o", out.c_str(),
                "--pdf", pdf.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    };
    // The whole run, uninterrupted, sets the moments (a sanitizer build runs slower).
    const auto start = std::chrono::steady_clock::now();
    const pid_t whole = ::fork();
    if (whole == 0) run();
    int status = 0;
    ::waitpid(whole, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    const double run_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    for (int k = 1; k <= 8; ++k) {
        fs::remove_all(dir / "out");
        const pid_t child = ::fork();
        if (child == 0) run();
        ::usleep(useconds_t(run_us * k / 16.0));
        ::kill(child, k % 2 ? SIGINT : SIGTERM);
        ::waitpid(child, &status, 0);
        EXPECT_TRUE(WIFSIGNALED(status)) << k << "/16 of the run: it should still be going";
        EXPECT_TRUE(partial_files(dir / "out").empty()) << k << "/16 of the run";
    }
}

TEST_F(BadInput, FaceLimitIsEnforced) {
    test::write_obj(dir / "cube.obj", test::cube(1.0));
    const test::RunResult r = test::run_inkline("render " + (dir / "cube.obj").string() + " --max-faces 10 -o " +
                                                (dir / "out").string());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("cube.obj: more than 10 faces, the limit (raise it with --max-faces)"), std::string::npos) << r.output;
}

TEST_F(BadInput, ImageSizeLimitIsConfigurable) {
    test::write_obj(dir / "cube.obj", test::cube(1.0));
    test::write_text(dir / "scene.json", R"({"mesh": "cube.obj", "image": {"width": 3000, "height": 200},
        "camera": {"eye": [3, 2, 4], "target": [0, 0, 0]}})");
    const test::RunResult refused =
        test::run_inkline("render " + (dir / "scene.json").string() + " --max-image-side 2048 -o " + (dir / "out").string());
    EXPECT_EQ(refused.code, 2);
    EXPECT_NE(refused.output.find("key 'image.width': exceeds the limit of 2048 px"), std::string::npos) << refused.output;
    EXPECT_EQ(test::run_inkline("render " + (dir / "scene.json").string() + " -q --svg " + (dir / "f.svg").string()).code, 0);
    const test::RunResult size = test::run_inkline("render " + (dir / "scene.json").string() + " --size 100000x100000 -o " +
                                                   (dir / "out").string());
    EXPECT_EQ(size.code, 2);
    EXPECT_NE(size.output.find("each side must be 1..16384 px"), std::string::npos) << size.output;
}

TEST_F(BadInput, OddMeshesWarnAndStillDraw) {
    core::Mesh odd = test::cube(1.0);
    std::swap(odd.triangles[0].y, odd.triangles[0].z);  // a flipped face
    odd.triangles.push_back(odd.triangles[4]);          // a duplicate face
    odd.positions.insert(odd.positions.end(), {{3, 0, 0}, {3, 1, 0}, {4, 0.5f, 0}, {2, 0.5f, 0}, {3, 0.5f, 1}, {0, -1, -1}});
    odd.triangles.push_back({0, 1, 13});  // zero area: vertex 13 lies between vertices 0 and 1
    odd.triangles.push_back({8, 9, 10});  // three faces on one edge: non-manifold
    odd.triangles.push_back({9, 8, 11});
    odd.triangles.push_back({8, 9, 12});
    test::write_obj(dir / "odd.obj", odd);
    const test::RunResult r = test::run_inkline("render " + (dir / "odd.obj").string() + " --frames 1:1 -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 0) << r.output;
    for (const char* warning : {"1 degenerate face(s) ignored", "1 duplicate face(s) ignored", "1 non-manifold edge(s)",
                                "2 non-manifold vertex(es)", "inconsistent orientation"}) {
        EXPECT_NE(r.output.find(warning), std::string::npos) << warning << "\n" << r.output;
    }
    EXPECT_NE(test::read_text(dir / "out" / "svg" / "frame_0001.svg").find("<path id=\"stroke-"), std::string::npos);
}

TEST_F(BadInput, CameraInsideTheMeshWarnsAndDraws) {
    test::write_obj(dir / "sphere.obj", test::uv_sphere(32, 16, 2.0));
    test::write_text(dir / "scene.json", R"({"mesh": "sphere.obj", "camera": {"eye": [0, 0, 0.5], "target": [0, 0, -1]}})");
    const test::RunResult r = test::run_inkline("render " + (dir / "scene.json").string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("inside the mesh"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "out" / "svg" / "frame_0001.svg"));
}

}  // namespace
}  // namespace inkline
