// SPDX-License-Identifier: MIT
// `inkline render --write-on`: one frame becomes a sequence that draws it stroke by stroke and
// ends in the frame itself; a sequence is drawn while it plays; the animated SVG plays in
// Chromium as the frame sequence shows it.
#include "tests/support/raster.h"
#include "tests/support/run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace inkline {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

class WriteOnCli : public ::testing::Test {
  protected:
    fs::path dir = fs::temp_directory_path() /
                   ("inkline_write_on_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    void SetUp() override {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    // Frame 1 of the torus sample at 480x360 written on over `seconds` at `fps`, with `more` options.
    test::RunResult write_on(const std::string& seconds, const std::string& fps, const std::string& more = "") {
        const std::string out = dir.string();
        return test::run_inkline("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json -q --size 480x360 --frames 1 --write-on " +
                                 seconds + " --fps " + fps + " --json " + out + "/%04d.json --png " + out + "/%04d.png --svg " +
                                 out + "/%04d.svg " + more);
    }
};

TEST_F(WriteOnCli, OneFrameBecomesASequenceThatEndsInTheFrame) {
    const auto r = write_on("0.5", "10");
    ASSERT_EQ(r.code, 0) << r.output;
    // 0.5 s at 10 fps: frames 1 (t = 0) to 6 (t = 0.5, done).
    for (int f = 1; f <= 6; ++f) EXPECT_TRUE(fs::exists(dir / (std::string(f < 10 ? "000" : "00") + std::to_string(f) + ".png")));
    EXPECT_FALSE(fs::exists(dir / "0007.png"));
    const auto plain = test::run_inkline("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json -q --size 480x360 --frames 1 --png " +
                                         (dir / "plain.png").string() + " --svg " + (dir / "plain.svg").string());
    ASSERT_EQ(plain.code, 0) << plain.output;
    EXPECT_EQ(read_file(dir / "0006.png"), read_file(dir / "plain.png"));

    // Each stroke's drawn length follows the schedule the JSON states, and only grows.
    std::map<int, double> drawn_before;  // stroke id -> drawn_px
    double total = 0.0;
    for (int f = 1; f <= 6; ++f) {
        const auto j = nlohmann::json::parse(read_file(dir / ("000" + std::to_string(f) + ".json")));
        const double t = j["write_on"]["time"];
        const double speed = j["write_on"]["speed_px_per_s"];
        EXPECT_NEAR(t, (f - 1) / 10.0, 1e-9);
        EXPECT_EQ(j["write_on"]["seconds"], 0.5);
        if (f == 1) {
            EXPECT_TRUE(j["strokes"].empty());
        }
        total = 0.0;
        for (const auto& s : j["strokes"]) {
            const auto& w = s["write_on"];
            if (w["start"].is_null()) continue;
            const double start = w["start"], end = w["end"], length = w["length_px"], drawn = w["drawn_px"];
            EXPECT_LE(start, t);
            EXPECT_NEAR(drawn, std::clamp((t - start) * speed, 0.0, length), 1e-2);
            EXPECT_NEAR(end - start, length / speed, 1e-5);
            const int id = s["id"];
            EXPECT_GE(drawn, drawn_before[id]);
            drawn_before[id] = drawn;
            total += length;
        }
    }
    // Done: every stroke whole, the lengths adding up to speed times seconds.
    const auto last = nlohmann::json::parse(read_file(dir / "0006.json"));
    EXPECT_NEAR(total, double(last["write_on"]["speed_px_per_s"]) * 0.5, 0.01);
}

TEST_F(WriteOnCli, ASequenceIsDrawnWhileItPlaysAndItsLastFrameHeldUntilDone) {
    const std::string out = dir.string();
    const auto r = test::run_inkline("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json -q --size 320x240 --frames 1:3 --write-on 0.5 --fps 10 --json " +
                                     out + "/%04d.json");
    ASSERT_EQ(r.code, 0) << r.output;
    for (int f = 1; f <= 6; ++f) {
        const auto j = nlohmann::json::parse(read_file(dir / ("000" + std::to_string(f) + ".json")));
        EXPECT_EQ(j["frame"], f);
        EXPECT_NEAR(double(j["write_on"]["time"]), (f - 1) / 10.0, 1e-9);
    }
    EXPECT_FALSE(fs::exists(dir / "0007.json"));
    // Frames 4 to 6 hold frame 3's drawing: its camera, its strokes.
    const auto three = nlohmann::json::parse(read_file(dir / "0003.json"));
    const auto six = nlohmann::json::parse(read_file(dir / "0006.json"));
    EXPECT_EQ(three["camera"], six["camera"]);
    EXPECT_GE(six["strokes"].size(), three["strokes"].size());
}

TEST_F(WriteOnCli, BadWriteOnsAreRefusedBeforeAnythingIsWritten) {
    const std::string sample = std::string(INKLINE_SAMPLES) + "/torus/scene.json";
    const std::string out = " --svg " + (dir / "%04d.svg").string();
    const auto without = test::run_inkline("render " + sample + " -q --frames 1 --animated-svg " + (dir / "a.svg").string() + out);
    EXPECT_EQ(without.code, 2);
    EXPECT_NE(without.output.find("--animated-svg: needs a write-on"), std::string::npos) << without.output;
    const auto chunk = test::run_inkline("render " + sample + " -q --frames 1:4 --write-on 1 --chunk 1/2" + out);
    EXPECT_EQ(chunk.code, 2);
    EXPECT_NE(chunk.output.find("--chunk: a write-on cannot be split"), std::string::npos) << chunk.output;
    const auto farm = test::run_inkline("farm " + sample + " --chunks 2 -o " + (dir / "farm").string() + " -- --frames 1:4 --write-on 1");
    EXPECT_EQ(farm.code, 2);
    EXPECT_NE(farm.output.find("--write-on: a write-on cannot be split"), std::string::npos) << farm.output;
    EXPECT_FALSE(fs::exists(dir / "farm"));
    for (const std::string bad : {"0", "-1", "nan", "1e9"}) {
        const auto r = test::run_inkline("render " + sample + " -q --frames 1 --write-on " + bad + out);
        EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    }
    const auto fps = test::run_inkline("render " + sample + " -q --frames 1 --fps 12" + out);
    EXPECT_EQ(fps.code, 2);
    EXPECT_NE(fps.output.find("--fps: applies only to glTF input"), std::string::npos) << fps.output;
    // Frames past the last frame number.
    const auto far = test::run_inkline("render " + sample + " -q --frames 999999990 --write-on 10" + out);
    EXPECT_EQ(far.code, 2);
    EXPECT_NE(far.output.find("--write-on"), std::string::npos) << far.output;
    // One file for several frames.
    const auto one = test::run_inkline("render " + sample + " -q --frames 1 --write-on 1 --svg " + (dir / "one.svg").string());
    EXPECT_EQ(one.code, 2);
    EXPECT_NE(one.output.find("has no frame field"), std::string::npos) << one.output;
    // The scene key, checked like the option.
    std::ofstream(dir / "scene.json") << R"({"mesh": ")" << std::string(INKLINE_SAMPLES) << R"(/torus/torus.obj", "write_on": -2})";
    const auto key = test::run_inkline("render " + (dir / "scene.json").string() + " -q" + out);
    EXPECT_EQ(key.code, 2);
    EXPECT_NE(key.output.find("write_on"), std::string::npos) << key.output;
    EXPECT_FALSE(fs::exists(dir / "0001.svg"));
}

TEST_F(WriteOnCli, TheSceneKeyWritesOnAndTheOptionOverridesIt) {
    std::ofstream(dir / "scene.json") << R"({"mesh": ")" << std::string(INKLINE_SAMPLES) << R"(/torus/torus.obj", "frames": [1, 1],
        "image": {"width": 200, "height": 150}, "fps": 4, "write_on": 0.5,
        "camera": {"eye": [0, 1, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40}})";
    const auto r = test::run_inkline("render " + (dir / "scene.json").string() + " -q --json " + (dir / "%04d.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "0003.json"));  // 0.5 s at 4 fps: frames 1 to 3
    EXPECT_FALSE(fs::exists(dir / "0004.json"));
    const auto o = test::run_inkline("render " + (dir / "scene.json").string() + " -q --write-on 1 --json " + (dir / "o%04d.json").string());
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_TRUE(fs::exists(dir / "o0005.json"));
    EXPECT_FALSE(fs::exists(dir / "o0006.json"));
}

// A page that shows an SVG document at a time of its animation, paused.
void write_page(const fs::path& page, std::string svg, double t) {
    svg.erase(0, svg.find("<svg"));
    std::ofstream(page) << "<!DOCTYPE html><html><head><style>html,body{margin:0;padding:0;overflow:hidden}svg{display:block}"
                           "</style></head><body>"
                        << svg << "<script>const s = document.querySelector('svg'); s.pauseAnimations(); s.setCurrentTime("
                        << t << ");</script></body></html>";
}

// The animated SVG, screenshot by headless Chromium at three times, against the frames of those
// times (their SVG in Chromium, and their PNG by Cairo): ink IoU at least 0.95.
TEST_F(WriteOnCli, TheAnimatedSvgPlaysInChromiumAsTheFrameSequence) {
    const auto found = test::run_shell("command -v chromium");
    if (found.code != 0) GTEST_SKIP() << "chromium is not installed (.ci/setup installs it)";
    std::string chromium = found.output;
    chromium.erase(chromium.find_last_not_of("\n") + 1);
    const std::string out = dir.string();
    const auto r = test::run_inkline("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json -q --size 960x720 --frames 1 "
                                     "--write-on 1 --fps 10 --background '#ffffff' --png " + out + "/%04d.png --svg " + out +
                                     "/%04d.svg --animated-svg " + out + "/animated.svg");
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string animated = read_file(dir / "animated.svg");
    ASSERT_NE(animated.find("<animate"), std::string::npos);
    const auto screenshot = [&](const std::string& svg, double t, const std::string& name) {
        const fs::path page = dir / (name + ".html"), shot = dir / (name + ".png");
        write_page(page, svg, t);
        const auto c = test::run_shell(chromium + " --headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage --hide-scrollbars "
                                       "--force-device-scale-factor=1 --window-size=960,720 --user-data-dir=" + (dir / "profile").string() +
                                       " --screenshot=" + shot.string() + " file://" + page.string());
        EXPECT_TRUE(fs::exists(shot)) << c.output;
        return test::png_file_coverage(shot, test::Ink::kAlphaOrDark);
    };
    for (const int frame : {3, 6, 9}) {
        const double t = (frame - 1) / 10.0;
        const std::string name = "000" + std::to_string(frame);
        const auto played = screenshot(animated, t, "played_" + name);
        const auto framed_svg = screenshot(read_file(dir / (name + ".svg")), 0.0, "frame_" + name);
        const auto framed_png = test::png_file_coverage(dir / (name + ".png"), test::Ink::kAlphaOrDark);
        size_t ink = 0;
        for (const uint8_t v : framed_png) ink += v;
        EXPECT_GT(ink, 1000u) << "frame " << frame;
        const double to_svg = test::iou(played, framed_svg), to_png = test::iou(played, framed_png);
        std::printf("write-on at %.1f s: ink IoU %.4f with the frame's SVG in Chromium, %.4f with its PNG (%zu px of ink)\n", t,
                    to_svg, to_png, ink);
        EXPECT_GE(to_svg, 0.95) << "frame " << frame;
        EXPECT_GE(to_png, 0.95) << "frame " << frame;
    }
}

}  // namespace
}  // namespace inkline
