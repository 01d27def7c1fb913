// SPDX-License-Identifier: MIT
// Hostile input, outputs: each case asserts the exit code, the one-line message and the state of
// every file involved afterwards (tests/support/hostile.h).
#include "tests/support/hostile.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

namespace inkline {
namespace {

namespace fs = std::filesystem;
using test::HostileTest;

class HostileOutputs : public HostileTest {
  protected:
    void SetUp() override {
        test::write_obj(dir / "torus.obj", test::torus(1.0, 0.4, 48, 24));
        test::write_text(dir / "scene.json", R"({"mesh": "torus.obj", "frames": [1, 2],
            "image": {"width": 64, "height": 64},
            "camera": {"eye": [0.0, 2.6, 4.6], "target": [0.0, 0.0, 0.0], "fov_y_deg": 40}})");
    }

    // The start of a one-frame render of the torus scene (exact visibility: no GL, no Embree).
    std::string render() const {
        return "render " + (dir / "scene.json").string() + " --frames 1 --visibility exact -q";
    }
    std::string at(const std::string& name) const { return (dir / name).string(); }

    // The names a run changed, in order.
    std::vector<std::string> changed_by(const std::map<std::string, test::FileState>& before) const {
        return test::changed_entries(before, test::folder_state(dir));
    }
};

using Names = std::vector<std::string>;

// --- Class 3a: devices, FIFOs and links ----------------------------------------------------------

TEST_F(HostileOutputs, CharacterDeviceOutputIsWrittenInPlaceNotReplaced) {
    if (::geteuid() != 0) GTEST_SKIP() << "mknod needs root";
    ASSERT_EQ(::mknod((dir / "null").c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
    const auto before = test::folder_state(dir);
    for (const char* option : {"--json", "--svg", "--png", "--pdf"}) {
        const test::RunResult r = test::run_inkline(render() + " " + option + " " + at("null"));
        EXPECT_EQ(r.code, 0) << option << ": " << r.output;
        EXPECT_EQ(changed_by(before), Names{}) << option;
    }
}

TEST_F(HostileOutputs, DevNullItselfStaysTheDevice) {
    struct stat before {};
    ASSERT_EQ(::stat("/dev/null", &before), 0);
    const auto folder = test::folder_state(dir);
    const test::RunResult r = test::run_inkline(render() + " --json /dev/null --svg /dev/null");
    EXPECT_EQ(r.code, 0) << r.output;
    struct stat after {};
    ASSERT_EQ(::stat("/dev/null", &after), 0);
    EXPECT_TRUE(S_ISCHR(after.st_mode));
    EXPECT_EQ(after.st_ino, before.st_ino);
    EXPECT_EQ(after.st_rdev, before.st_rdev);
    EXPECT_EQ(changed_by(folder), Names{});
    EXPECT_EQ(test::run_shell("ls -a /dev | grep -c '^\\.null\\.tmp'").output, "0\n");
}

TEST_F(HostileOutputs, FifoOutputIsWrittenForItsReaderAndStaysAFifo) {
    for (const std::string option : {"--json", "--svg", "--png"}) {
        ASSERT_EQ(::mkfifo(at("pipe").c_str(), 0644), 0);
        const auto before = test::folder_state(dir);
        // The reader starts first in the background; the run opens the FIFO as it is.
        const test::RunResult r = test::run_shell("timeout 60 cat " + at("pipe") + " > " + at("got") + " & " +
                                                  test::inkline_command() + " " + render() + " " + option + " " +
                                                  at("pipe") + "; code=$?; wait; exit $code");
        EXPECT_EQ(r.code, 0) << option << ": " << r.output;
        EXPECT_EQ(changed_by(before), Names{"got"}) << option;
        const std::string got = test::read_text(dir / "got");
        const bool whole = option == "--json"  ? got.ends_with("}\n")
                           : option == "--svg" ? got.ends_with("</svg>\n")
                                               : got.ends_with(std::string("IEND\xae\x42\x60\x82", 8));
        EXPECT_TRUE(whole) << option << ": " << got.size() << " bytes";
        fs::remove(dir / "pipe");
        fs::remove(dir / "got");
    }
}

TEST_F(HostileOutputs, FifoWhoseReaderLeavesIsAnOutputError) {
    ASSERT_EQ(::mkfifo(at("pipe").c_str(), 0644), 0);
    const auto before = test::folder_state(dir);
    // The reader takes one byte and goes: the rest of the PNG (far more than a pipe holds) meets a
    // broken pipe.
    const test::RunResult r = test::run_shell("timeout 60 head -c 1 " + at("pipe") + " > /dev/null & " +
                                              test::inkline_command() + " " + render() +
                                              " --size 4096x4096 --png " + at("pipe") + "; code=$?; wait; exit $code");
    test::expect_one_line_error(r, 3, "pipe: cannot write: Broken pipe");
    EXPECT_EQ(changed_by(before), Names{});
}

TEST_F(HostileOutputs, DevStdoutAppendsToWhatTheShellOpened) {
    test::write_text(dir / "log.txt", "earlier\n");
    const auto before = test::folder_state(dir);
    const test::RunResult r = test::run_shell(test::inkline_command() + " " + render() + " --json /dev/stdout >> " +
                                              at("log.txt"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output, "");
    const auto after = test::folder_state(dir);
    EXPECT_EQ(test::changed_entries(before, after), Names{"log.txt"});
    EXPECT_EQ(after.at("log.txt").inode, before.at("log.txt").inode);
    const std::string log = test::read_text(dir / "log.txt");
    EXPECT_TRUE(log.starts_with("earlier\n{")) << log.substr(0, 40);
    EXPECT_TRUE(log.ends_with("}\n"));
}

TEST_F(HostileOutputs, SymlinkedOutputReplacesTheFileItLeadsToAndKeepsTheLink) {
    test::write_text(dir / "real" / "frame.svg", "old");
    test::write_text(dir / "real" / "frame.json", "old");
    fs::create_directories(dir / "links");
    fs::create_symlink("../real/frame.svg", dir / "links" / "frame.svg");
    fs::create_symlink(dir / "real" / "frame.json", dir / "links" / "frame.json");
    const auto before = test::folder_state(dir);
    const test::RunResult r =
        test::run_inkline(render() + " --svg " + at("links/frame.svg") + " --json " + at("links/frame.json"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(changed_by(before), (Names{"real/frame.json", "real/frame.svg"}));
    EXPECT_TRUE(test::read_text(dir / "real" / "frame.svg").ends_with("</svg>\n"));
}

TEST_F(HostileOutputs, DanglingLinkOutputIsRefused) {
    fs::create_symlink(dir / "elsewhere" / "target.svg", dir / "frame.svg");
    const auto before = test::folder_state(dir);
    const test::RunResult r = test::run_inkline(render() + " --svg " + at("frame.svg"));
    test::expect_one_line_error(r, 3, "frame.svg: is a symbolic link to a missing file; not followed");
    EXPECT_EQ(changed_by(before), Names{});
}

TEST_F(HostileOutputs, FolderOutputIsRefused) {
    fs::create_directories(dir / "frame.png");
    const auto before = test::folder_state(dir);
    const test::RunResult r = test::run_inkline(render() + " --png " + at("frame.png"));
    test::expect_one_line_error(r, 3, "frame.png: is a folder; not replaced");
    EXPECT_EQ(changed_by(before), Names{});
}

// A PNG is made on a second thread while the next frame is drawn: frame 2's failure still stops
// the run with its one line before anything of frame 3 is written, and frame 1 stays whole.
TEST_F(HostileOutputs, FolderInTheWayOfASecondFramesPngStopsTheRunBeforeTheThird) {
    test::write_text(dir / "three.json", R"({"mesh": "torus.obj", "frames": [1, 3],
        "image": {"width": 64, "height": 64},
        "camera": {"eye": [0.0, 2.6, 4.6], "target": [0.0, 0.0, 0.0], "fov_y_deg": 40}})");
    fs::create_directories(dir / "f0002.png");
    const test::RunResult r = test::run_inkline("render " + at("three.json") + " --visibility exact -q --png " + at("f%04d.png") +
                                                " --svg " + at("f%04d.svg"));
    test::expect_one_line_error(r, 3, "f0002.png: is a folder; not replaced");
    EXPECT_TRUE(fs::is_regular_file(dir / "f0001.png"));
    EXPECT_GT(fs::file_size(dir / "f0001.png"), 100u);
    EXPECT_TRUE(fs::is_regular_file(dir / "f0001.svg"));
    EXPECT_TRUE(fs::is_directory(dir / "f0002.png"));
    EXPECT_FALSE(fs::exists(dir / "f0003.png"));
    EXPECT_FALSE(fs::exists(dir / "f0003.svg"));
}

// --- Class 3b: temporaries -----------------------------------------------------------------------

TEST_F(HostileOutputs, LinkPlantedAtTheOldPredictableTemporaryNameIsNotFollowed) {
    test::write_text(dir / "victim.txt", "precious");
    const auto before = test::folder_state(dir);
    // `exec` keeps the shell's pid, so $$ is the run's pid: the old name was .NAME.tmpPID.
    const test::RunResult r = test::run_shell("cd " + dir.string() + " && ln -s victim.txt .frame.svg.tmp$$ && exec " +
                                              test::inkline_command() + " " + render() + " --svg frame.svg");
    EXPECT_EQ(r.code, 0) << r.output;
    const Names changed = changed_by(before);
    ASSERT_EQ(changed.size(), 2u) << ::testing::PrintToString(changed);
    EXPECT_TRUE(changed[0].starts_with(".frame.svg.tmp")) << changed[0];  // the planted link, as it was
    EXPECT_TRUE(fs::is_symlink(dir / changed[0]));
    EXPECT_EQ(changed[1], "frame.svg");
    EXPECT_EQ(test::read_text(dir / "victim.txt"), "precious");
}

TEST_F(HostileOutputs, LeftoverTemporaryOfADeadRunIsRemovedAndNothingElse) {
    const std::string dead = test::run_shell("sh -c 'echo $$'").output.substr(0, 9);
    const std::string dead_pid = dead.substr(0, dead.find('\n'));
    test::write_text(dir / "victim.txt", "precious");
    test::write_text(dir / (".frame.svg.tmp-" + dead_pid + "-Abcd1234"), "<svg half");
    fs::create_symlink("victim.txt", dir / (".frame.svg.tmp-" + dead_pid + "-Link5678"));
    test::write_text(dir / (".frame.svg.tmp-1-Live1234"), "a running process's");
    test::write_text(dir / (".other.svg.tmp-" + dead_pid + "-Abcd1234"), "another output's");
    const auto before = test::folder_state(dir);
    const test::RunResult r = test::run_inkline(render() + " --svg " + at("frame.svg"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(changed_by(before), (Names{"frame.svg", ".frame.svg.tmp-" + dead_pid + "-Abcd1234 (removed)",
                                         ".frame.svg.tmp-" + dead_pid + "-Link5678 (removed)"}));
    EXPECT_EQ(test::read_text(dir / "victim.txt"), "precious");
}

TEST_F(HostileOutputs, OutputNameOf250BytesIsWritten) {
    const std::string name = std::string(246, 'n') + ".svg";
    const std::string png = std::string(246, 'p') + ".png";
    const auto before = test::folder_state(dir);
    const test::RunResult r = test::run_inkline(render() + " --svg " + at(name) + " --png " + at(png));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(changed_by(before), (Names{name, png}));
}

// --- Class 3c: read-only outputs -----------------------------------------------------------------

TEST_F(HostileOutputs, ReadOnlyOutputIsRefusedAndLeftAsItIs) {
    for (const std::string ext : {"json", "svg", "png", "pdf"}) {
        const fs::path out = dir / ("frame." + ext);
        test::write_text(out, "old");
        fs::permissions(out, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_inkline(render() + " --" + ext + " " + out.string());
        test::expect_one_line_error(r, 3, "frame." + ext + ": is read-only; not replaced");
        EXPECT_EQ(changed_by(before), Names{}) << ext;
        EXPECT_EQ(test::read_text(out), "old");
    }
}

// --- Classes 8 and 9: sizes Cairo or PDF cannot take ----------------------------------------------

TEST_F(HostileOutputs, PngOverCairosSideLimitIsRefusedBeforeAnythingIsWritten) {
    for (const std::string size : {"32768x16", "16x32768", "40000x40000"}) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_inkline(render() + " --size " + size + " --max-image-side 40000 --svg " +
                                                    at("a.svg") + " --json " + at("a.json") + " --png " + at("a.png"));
        test::expect_one_line_error(r, 2, "PNG of " + size + " px: Cairo draws images of at most 32767 px a side");
        EXPECT_EQ(changed_by(before), Names{}) << size;
    }
}

TEST_F(HostileOutputs, MeshNameThatIsNotUtf8MakesAPdf) {
    const std::string mesh = at("torus\xff\xfe.obj");
    fs::copy_file(dir / "torus.obj", mesh);
    const auto before = test::folder_state(dir);
    // The title (the mesh's name) is in the document's metadata and, with --page, under the image.
    for (const std::string& pdf : {"--pdf " + at("a.pdf"), "--pdf " + at("p%d.pdf") + " --page A4"}) {
        const test::RunResult r = test::run_inkline("render '" + mesh + "' --frames 1 --visibility exact -q " + pdf);
        EXPECT_EQ(r.code, 0) << r.output;
    }
    EXPECT_EQ(changed_by(before), (Names{"a.pdf", "p1.pdf"}));
    for (const std::string name : {"a.pdf", "p1.pdf"}) {
        const std::string text = test::read_text(dir / name);
        EXPECT_EQ(text.rfind("%PDF-", 0), 0u) << name;
        EXPECT_NE(text.find("%%EOF"), std::string::npos) << name;
    }
}

TEST_F(HostileOutputs, PdfPageOutsidePdfsLimitsIsRefusedNamingDpi) {
    for (const std::string dpi : {"1e-300", "0.001", "3"}) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_inkline(render() + " --size 1024x64 --svg " + at("a.svg") + " --pdf " +
                                                    at("a.pdf") + " --dpi " + dpi);
        test::expect_one_line_error(r, 2, "--dpi " + dpi + ": a 1024x64 px image makes a PDF page of ");
        EXPECT_EQ(changed_by(before), Names{}) << dpi;
    }
    const auto before = test::folder_state(dir);
    const test::RunResult r =
        test::run_inkline(render() + " --size 1024x64 --pdf " + at("a%d.pdf") + " --dpi 6");  // 12288 x 768 pt
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(changed_by(before), Names{"a1.pdf"});
}

TEST_F(HostileOutputs, MarginThatLeavesNoRoomOnThePageIsRefusedNamingMargin) {
    const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
        {"A4", "150", "210x297"}, {"A4", "105", "210x297"}, {"100x40mm", "20", "100x40"}, {"Letter", "999", "215.9x279.4"}};
    for (const auto& [page, margin, shown] : cases) {
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_inkline(render() + " --svg " + at("a.svg") + " --pdf " + at("a.pdf") +
                                                    " --page " + page + " --margin " + margin);
        test::expect_one_line_error(r, 2,
                                    std::string("--margin ") + margin + " mm leaves no room for the image on a " +
                                        shown + " mm page");
        EXPECT_EQ(changed_by(before), Names{}) << page << " " << margin;
    }
    const auto before = test::folder_state(dir);
    const test::RunResult r = test::run_inkline(render() + " --pdf " + at("a.pdf") + " --page 100x40mm --margin 19");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(changed_by(before), Names{"a.pdf"});
}

// --- Class 2: out of memory ----------------------------------------------------------------------

// Renders an 8192x8192 frame under address-space limits of `limits_mb`. Each run either
// succeeds with exactly the file an unlimited run writes, or ends with exit 5, the one line
// "out of memory" and no file (or cannot even load its libraries). Returns how many runs failed
// while a 64x64 frame under the same limit succeeds: those ran out of memory drawing.
int runs_out_of_memory_whole_or_nothing(const fs::path& dir, const std::string& render, const std::string& option,
                                        const std::string& name, const std::vector<int>& limits_mb) {
    const std::string big = render + " --size 8192x8192 --max-image-side 8192 " + option + " ";
    EXPECT_EQ(test::run_inkline(big + (dir / ("reference_" + name)).string()).code, 0);
    const std::string reference = test::read_text(dir / ("reference_" + name));
    int failed_drawing = 0;
    for (const int limit_mb : limits_mb) {
        const auto before = test::folder_state(dir);
        const std::string limit = "ulimit -v " + std::to_string(limit_mb * 1000) + "; ";
        const test::RunResult r = test::run_shell(limit + test::inkline_command() + " " + big + (dir / name).string());
        const std::string where = limit + r.output;
        if (r.code == 127 && r.output.find("error while loading shared libraries") != std::string::npos) {
            EXPECT_EQ(test::changed_entries(before, test::folder_state(dir)), Names{}) << where;
            continue;
        }
        if (r.code == 0) {
            EXPECT_EQ(test::changed_entries(before, test::folder_state(dir)), Names{name}) << where;
            EXPECT_TRUE(test::read_text(dir / name) == reference) << where << "differs from the unlimited run's";
            fs::remove(dir / name);
            continue;
        }
        EXPECT_EQ(r.code, 5) << where;
        EXPECT_EQ(r.output, "inkline: error: out of memory\n") << where;
        EXPECT_EQ(test::changed_entries(before, test::folder_state(dir)), Names{}) << where;
        const test::RunResult small = test::run_shell(limit + test::inkline_command() + " " + render + " " + option +
                                                      " " + (dir / ("small_" + name)).string());
        if (small.code == 0) ++failed_drawing;
        fs::remove(dir / ("small_" + name));
    }
    return failed_drawing;
}

TEST_F(HostileOutputs, PngUnderMemoryPressureIsWholeOrExitsFiveWithNothingWritten) {
    if (test::kAddressSanitizer) GTEST_SKIP() << "ulimit -v stops AddressSanitizer from starting";
    // The image alone is 256 MiB; drawing it takes as much again for each layer's group.
    const int failed_drawing =
        runs_out_of_memory_whole_or_nothing(dir, render(), "--png", "frame.png", {300, 500, 700, 900, 1100, 1300, 1500});
    EXPECT_GT(failed_drawing, 0) << "no limit made the drawing itself run out of memory";
}

TEST_F(HostileOutputs, PdfUnderMemoryPressureIsWholeOrExitsFiveWithNothingWritten) {
    if (test::kAddressSanitizer) GTEST_SKIP() << "ulimit -v stops AddressSanitizer from starting";
    // A PDF needs little memory: these limits fail anywhere from loading to writing.
    runs_out_of_memory_whole_or_nothing(dir, render(), "--pdf", "frame.pdf", {260, 265, 270, 280, 300, 400});
}

}  // namespace
}  // namespace inkline
