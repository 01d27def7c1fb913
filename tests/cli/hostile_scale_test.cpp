// SPDX-License-Identifier: MIT
// Hostile input, scale: each case asserts the exit code, the one-line message and the state of
// every file involved afterwards (tests/support/hostile.h).
//
// Shapes that made a stage quadratic: a vertex in every face (fans, cones, disc caps from CAD
// exports), a polygon of very many corners, and tens of thousands of strokes from frame 2 on. Each
// runs in a few seconds; `timeout 120` turns a return of the quadratic cost into a failure rather
// than a hung suite.
#include "tests/support/hostile.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

namespace inkline {
namespace {

namespace fs = std::filesystem;
using test::HostileTest;

class HostileScale : public HostileTest {};

// Runs inkline under a guard against a hang: a run that takes this long has gone quadratic (each
// case runs in seconds).
test::RunResult run_guarded(const std::string& args) {
    return test::run_shell("timeout 120 " + test::inkline_command() + " " + args);
}

// A frame's JSON written whole: the document's first and last bytes, and its frame number.
void expect_whole_json(const fs::path& path, int frame) {
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    const std::string text = test::read_text(path);
    ASSERT_GT(text.size(), 2u) << path;
    EXPECT_EQ(text.front(), '{') << path;
    EXPECT_EQ(text.substr(text.size() - 2), "}\n") << path;
    EXPECT_NE(text.find("\"frame\":" + std::to_string(frame) + ","), std::string::npos) << path;
}

// Only the expected outputs appeared, and the input is as it was.
void expect_only_outputs(const std::map<std::string, test::FileState>& before,
                         const std::map<std::string, test::FileState>& after, const std::vector<std::string>& outputs) {
    std::vector<std::string> changed = test::changed_entries(before, after);
    std::erase_if(changed, [](const std::string& name) { return name == "out" || name.rfind("out/", 0) == 0; });
    EXPECT_TRUE(changed.empty()) << "changed besides the outputs: " << changed.front();
    size_t files = 0;
    for (const auto& [name, state] : after) {
        if (name.rfind("out/", 0) == 0 && S_ISREG(state.mode)) ++files;
    }
    EXPECT_EQ(files, outputs.size()) << "no temporary or partial file left";
    for (const std::string& name : outputs) EXPECT_TRUE(after.contains(name)) << name;
}

TEST_F(HostileScale, ConeOf300kFacesIsDescribedWithoutDelay) {
    // The apex and the base centre each have 150000 faces: counting the fans around them was
    // quadratic (past 100 s).
    test::write_obj(dir / "cone.obj", test::closed_cone(150000));
    const auto before = test::folder_state(dir);
    const test::RunResult r = run_guarded("info " + (dir / "cone.obj").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("faces: 300000\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("non-manifold vertices: 0\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("boundary edges: 0\n"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    EXPECT_TRUE(test::changed_entries(before, test::folder_state(dir)).empty());
}

TEST_F(HostileScale, DiscOfAMillionFacesAroundOneVertexIsDescribed) {
    // A million faces at one vertex: quadratic, the fan count took minutes, well past the guard
    // on any machine; linear, about a second with the file read.
    test::write_obj(dir / "disc.obj", test::disc_cap(1000000));
    const auto before = test::folder_state(dir);
    const test::RunResult r = run_guarded("info " + (dir / "disc.obj").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("faces: 1000000\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("non-manifold vertices: 0\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("boundary edges: 1000000\n"), std::string::npos) << r.output;
    EXPECT_TRUE(test::changed_entries(before, test::folder_state(dir)).empty());
}

TEST_F(HostileScale, TwoConesTouchingAtTheirApexOfOneHundredThousandFacesEach) {
    // 50000 faces at the shared apex from each cone: one non-manifold vertex, found as fast.
    const core::Mesh two = test::twin_cones(50000);
    test::write_obj(dir / "cones.obj", two);
    const test::RunResult r = run_guarded("info " + (dir / "cones.obj").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("faces: 200000\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("non-manifold vertices: 1\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1 non-manifold vertex"), std::string::npos) << "and its warning:\n" << r.output;
}

TEST_F(HostileScale, DiscCapOf150kFacesRendersTwoFramesWhole) {
    // One vertex in all 150000 faces, and a rim of 150000 edges drawn as one boundary loop.
    test::write_obj(dir / "cap.obj", test::disc_cap(150000));
    const auto before = test::folder_state(dir);
    const test::RunResult r = run_guarded("render " + (dir / "cap.obj").string() +
                                                " --frames 1:2 --size 512x512 -q -o " + (dir / "out").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output, "");
    expect_whole_json(dir / "out/json/frame_0001.json", 1);
    expect_whole_json(dir / "out/json/frame_0002.json", 2);
    EXPECT_NE(test::read_text(dir / "out/json/frame_0002.json").find("\"faces\":150000,"), std::string::npos);
    expect_only_outputs(before, test::folder_state(dir),
                        {"out/json/frame_0001.json", "out/json/frame_0002.json", "out/svg/frame_0001.svg",
                         "out/svg/frame_0002.svg"});
}

TEST_F(HostileScale, PolygonOfAQuarterMillionCornersRendersWhole) {
    // One OBJ face of 250000 corners, fan-triangulated on reading: every triangle has its first
    // corner.
    constexpr int kCorners = 250000;
    {
        std::ofstream obj(dir / "polygon.obj");
        obj.precision(9);
        for (int i = 0; i < kCorners; ++i) {
            const double a = 2.0 * std::numbers::pi * double(i) / kCorners;
            obj << "v " << std::cos(a) << " 0 " << std::sin(a) << "\n";
        }
        obj << "f";
        for (int i = 1; i <= kCorners; ++i) obj << ' ' << i;
        obj << "\n";
    }
    const auto before = test::folder_state(dir);
    const test::RunResult r = run_guarded("render " + (dir / "polygon.obj").string() +
                                                " --frames 1 --size 512x512 -q -o " + (dir / "out").string());
    ASSERT_EQ(r.code, 0) << r.output;
    expect_whole_json(dir / "out/json/frame_0001.json", 1);
    EXPECT_NE(test::read_text(dir / "out/json/frame_0001.json").find("\"faces\":" + std::to_string(kCorners - 2) + ","),
              std::string::npos);
    expect_only_outputs(before, test::folder_state(dir), {"out/json/frame_0001.json", "out/svg/frame_0001.svg"});
}

TEST_F(HostileScale, StarPolygonOfThirtyThousandCornersRendersWhole) {
    // A star-shaped face, fan-triangulated on reading: its fan edges are silhouettes that meet at
    // the first corner, one junction of about 30000 stroke ends, whose joins were searched pair by
    // pair (about 20 s; now about 5).
    constexpr int kCorners = 30000;
    {
        std::ofstream obj(dir / "star.obj");
        obj.precision(9);
        for (int i = 0; i < kCorners; ++i) {
            const double a = 2.0 * std::numbers::pi * double(i) / kCorners, r = 1.0 + 0.5 * (i % 2);
            obj << "v " << r * std::cos(a) << " " << r * std::sin(a) << " 0\n";
        }
        obj << "f";
        for (int i = 1; i <= kCorners; ++i) obj << ' ' << i;
        obj << "\n";
    }
    const auto before = test::folder_state(dir);
    const test::RunResult r = run_guarded("render " + (dir / "star.obj").string() +
                                          " --frames 1 --size 256x256 --visibility raycast -q -o " +
                                          (dir / "out").string());
    ASSERT_EQ(r.code, 0) << r.output;
    expect_whole_json(dir / "out/json/frame_0001.json", 1);
    EXPECT_NE(test::read_text(dir / "out/json/frame_0001.json").find("\"faces\":" + std::to_string(kCorners - 2) + ","),
              std::string::npos);
    expect_only_outputs(before, test::folder_state(dir), {"out/json/frame_0001.json", "out/svg/frame_0001.svg"});
}

TEST_F(HostileScale, TensOfThousandsOfStrokesFromFrameTwoRenderWhole) {
    // Random terrain: frame 2 joins last frame's split strokes again, which compared every stroke
    // end with every other (13 s at 16k strokes, 48 s at 30k).
    test::write_obj(dir / "terrain.obj", test::noise_terrain(210, 0.15));
    const auto before = test::folder_state(dir);
    const test::RunResult r = run_guarded("render " + (dir / "terrain.obj").string() +
                                                " --frames 1:2 -q --json " + (dir / "out/f_%04d.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    expect_whole_json(dir / "out/f_0001.json", 1);
    expect_whole_json(dir / "out/f_0002.json", 2);
    // Tens of thousands of strokes, nearly all carried over from frame 1.
    const std::string frame2 = test::read_text(dir / "out/f_0002.json");
    size_t strokes = 0;
    for (size_t at = frame2.find("\"ends\":["); at != std::string::npos; at = frame2.find("\"ends\":[", at + 1)) ++strokes;
    EXPECT_GT(strokes, 10000u);
    const size_t inherited = frame2.find("\"inherited_ids\":");
    ASSERT_NE(inherited, std::string::npos);
    EXPECT_GT(std::stoul(frame2.substr(inherited + 16)), strokes * 9 / 10);
    expect_only_outputs(before, test::folder_state(dir), {"out/f_0001.json", "out/f_0002.json"});
}

}  // namespace
}  // namespace inkline
