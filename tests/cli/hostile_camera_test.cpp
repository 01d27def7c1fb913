// SPDX-License-Identifier: MIT
// Hostile input, camera: each case asserts the exit code, the one-line message and the state of
// every file involved afterwards (tests/support/hostile.h).
#include "tests/support/hostile.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace inkline {
namespace {

namespace fs = std::filesystem;
using test::HostileTest;

class HostileCamera : public HostileTest {
  protected:
    // A closed octahedron of the given radius about `center`, written as OBJ with full precision.
    fs::path octahedron(const std::string& name, double radius, double center = 0.0) {
        std::ostringstream obj;
        obj.precision(17);
        const double v[6][3] = {{radius, 0, 0}, {-radius, 0, 0}, {0, radius, 0},
                                {0, -radius, 0}, {0, 0, radius}, {0, 0, -radius}};
        for (const auto& p : v) obj << "v " << center + p[0] << " " << center + p[1] << " " << center + p[2] << "\n";
        obj << "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
        test::write_text(dir / name, obj.str());
        return dir / name;
    }
    fs::path scene(const std::string& camera, const std::string& extra = "") {
        octahedron("oct.obj", 1.0);
        test::write_text(dir / "scene.json", R"({"mesh": "oct.obj", "camera": )" + camera + extra + "}");
        return dir / "scene.json";
    }
    // Renders frame 1 to out/f.json and out/f.svg; returns the run.
    test::RunResult render(const fs::path& input, const std::string& visibility) {
        return test::run_inkline("render " + input.string() + " --frames 1 --visibility " + visibility +
                                 " -q --json " + (dir / "out" / "f.json").string() + " --svg " +
                                 (dir / "out" / "f.svg").string());
    }
    // A refused input: exit 2, one line naming the key, nothing written.
    void expect_refused(const fs::path& input, const std::string& needle) {
        for (const char* mode : {"raycast", "exact", "gl"}) {
            SCOPED_TRACE(mode);
            const auto before = test::folder_state(dir);
            const test::RunResult r = render(input, mode);
            test::expect_one_line_error(r, 2, needle);
            EXPECT_TRUE(test::changed_entries(before, test::folder_state(dir)).empty());
        }
    }
    // A drawn input: exit 0 in every mode, whole JSON and SVG files; returns the stroke counts.
    void expect_drawn(const fs::path& input) {
        for (const char* mode : {"raycast", "exact", "gl"}) {
            SCOPED_TRACE(mode);
            fs::remove_all(dir / "out");
            const test::RunResult r = render(input, mode);
            ASSERT_EQ(r.code, 0) << r.output;
            std::ifstream json(dir / "out" / "f.json"), svg(dir / "out" / "f.svg");
            std::stringstream j, s;
            j << json.rdbuf();
            s << svg.rdbuf();
            EXPECT_NE(j.str().find("\"strokes\""), std::string::npos);
            EXPECT_EQ(j.str().find_last_not_of(" \n"), j.str().rfind('}'));
            EXPECT_NE(s.str().find("</svg>"), std::string::npos);
            std::vector<std::string> names;
            for (const auto& e : fs::directory_iterator(dir / "out")) names.push_back(e.path().filename().string());
            EXPECT_EQ(names.size(), 2u) << "only the two outputs, no temporaries";
        }
    }
};

// Issue 19 class 1: SIGABRT in Embree's ray.valid() from the default turntable of a mesh inside
// the coordinate limit.
TEST_F(HostileCamera, HugeMeshInsideTheCoordinateLimitIsDrawnInEveryMode) {
    for (const double radius : {5e17, 1e18 / 1.0000001}) expect_drawn(octahedron("big.obj", radius));
}

TEST_F(HostileCamera, TinyMeshIsDrawnInEveryMode) {
    for (const double radius : {1e-30, 1e-20}) expect_drawn(octahedron("tiny.obj", radius));
}

TEST_F(HostileCamera, SmallMeshFarFromTheOriginIsDrawnInEveryMode) {
    expect_drawn(octahedron("far.obj", 1.0, 1e6));
    expect_drawn(octahedron("far.obj", 1e3, 1e17));
}

TEST_F(HostileCamera, EyeAtTheLimitIsDrawnInEveryMode) {
    expect_drawn(scene(R"({"eye": [0, 0, 1e19], "target": [0, 0, 0]})"));
    expect_drawn(scene(R"({"eye": [-1e19, 1e19, 1e19], "target": [1e19, -1e19, -1e19]})"));
    expect_drawn(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "near": 1e-300, "far": 1e300})"));
    expect_drawn(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "fov_y_deg": 0.001})"));
    expect_drawn(scene(R"({"eye": [0, 0, 1e-20], "target": [0, 0, 0], "up": [1e-300, 1e-300, 0]})"));
}

TEST_F(HostileCamera, OrthographicViewsAtTheLimitsAreDrawnInEveryMode) {
    expect_drawn(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": 3})"));
    expect_drawn(scene(R"({"eye": [0, 0, 1e19], "target": [0, 0, 0], "ortho_height": 1e19})"));
    expect_drawn(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": 1e-18})"));
    // The eye inside the mesh, and behind it: an orthographic view sees all of it.
    expect_drawn(scene(R"({"eye": [0, 0, 0.2], "target": [0, 0, 0], "ortho_height": 3})"));
    expect_drawn(scene(R"({"eye": [0, 0, -5], "target": [0, 0, -6], "ortho_height": 3})"));
    for (const double radius : {1e-30, 1e-20}) {
        octahedron("tiny.obj", radius);
        test::write_text(dir / "tiny.json", R"({"mesh": "tiny.obj", "camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "ortho_height": 1e-15}})");
        expect_drawn(dir / "tiny.json");
    }
    octahedron("far.obj", 1e3, 1e17);
    test::write_text(dir / "far.json", R"({"mesh": "far.obj", "camera": {"eye": [1e17, 1e17, 2e17], "target": [1e17, 1e17, 1e17], "ortho_height": 4000}})");
    expect_drawn(dir / "far.json");
}

TEST_F(HostileCamera, BadOrthographicViewsAreRefusedWithTheirKey) {
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": 0})"),
                   "key 'camera.ortho_height': must be between 1e-18 and 1e+19");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": -2})"), "key 'camera.ortho_height'");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": 1e20})"), "key 'camera.ortho_height'");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": "tall"})"),
                   "key 'camera.ortho_height': expected a number");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": 2, "fov_y_deg": 30})"),
                   "key 'camera.ortho_height': an orthographic camera has no fov_y_deg");
    expect_refused(scene(R"({"frames": [{"frame": 1, "eye": [0, 0, 4], "target": [0, 0, 0], "ortho_height": 1e-19}]})"),
                   "key 'camera.frames[0].ortho_height'");
}

TEST_F(HostileCamera, EyeBeyondTheLimitIsRefusedWithItsKey) {
    expect_refused(scene(R"({"eye": [0, 0, 1e20], "target": [0, 0, 0]})"), "scene.json: key 'camera.eye': coordinate 1e+20 exceeds the limit of 1e+19");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [1e38, 0, 0]})"), "key 'camera.target': coordinate 1e+38");
    expect_refused(scene(R"({"frames": [{"frame": 1, "eye": [0, -3e300, 4], "target": [0, 0, 0]}]})"),
                   "key 'camera.frames[0].eye': coordinate -3e+300");
    expect_refused(scene(R"({"eye": [0, 0, 1e400], "target": [0, 0, 0]})"), "scene.json: not valid JSON: number overflow");
}

TEST_F(HostileCamera, DegenerateCameraIsRefusedWithItsKey) {
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "fov_y_deg": 1e-300})"), "key 'camera.fov_y_deg'");
    expect_refused(scene(R"({"eye": [5, 5, 5], "target": [5, 5, 5]})"), "key 'camera.eye': equals the target");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 0, 1e300]})"), "key 'camera.up': is parallel");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "near": 2, "far": 1})"), "key 'camera.far'");
}

// Issue 19 class 8: an axis whose squared length overflows made a NaN that blamed camera.far.
TEST_F(HostileCamera, OverflowingRotationAxisIsDrawnNotBlamedOnTheCamera) {
    expect_drawn(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})",
                       R"(, "object": {"rotate": {"axis": [1e300, 1e300, 0], "degrees": 90}})"));
    expect_drawn(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "orbit": {"axis": [0, 1e308, 1e308], "degrees": 360}})"));
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})", R"(, "object": {"rotate": {"axis": [0, 0, 0], "degrees": 90}})"),
                   "key 'object.rotate.axis': must not be the zero vector");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})",
                         R"(, "object": {"rotate": {"axis": [0, 1, 0], "degrees": 90, "center": [1e300, 0, 0]}})"),
                   "key 'object.rotate.center': coordinate 1e+300");
}

// Issue 19 class 4c: [1, 4294967298] was read as [1, 2].
TEST_F(HostileCamera, FrameNumbersBeyondTheRangeAreRefusedWithTheirKey) {
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})", R"(, "frames": [1, 4294967298])"),
                   "key 'frames': frame numbers must be between -999999999 and 999999999");
    expect_refused(scene(R"({"frames": [{"frame": 4294967297, "eye": [0, 0, 4], "target": [0, 0, 0]}]})"),
                   "key 'camera.frames[0].frame': frame numbers must be between");
}

// Issue 19 class 8: an error echoed a 200 MB value in full.
TEST_F(HostileCamera, LongKeysAndFileNamesStayOneShortLine) {
    const std::string key(2'000'000, 'k');
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})", ", \"" + key + "\": 1"), "unknown key");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})", ", \"brush\": {\"tip\": \"" + std::string(2'000'000, 'm') + "\n\"}"),
                   "not valid JSON");
    expect_refused(scene(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})",
                         ", \"brush\": {\"tip\": \"" + std::string(200, 't') + "/" + std::string(200, 'u') + "\"}"),
                   "key 'brush.tip': no such file");
}

}  // namespace
}  // namespace inkline
