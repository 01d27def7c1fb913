// SPDX-License-Identifier: MIT
// --chunk K/N: every chunk of a sequence writes exactly the files a sequential run writes.
#include "tests/support/obj.h"
#include "tests/support/run.h"

#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

namespace inkline {
namespace {

namespace fs = std::filesystem;

class Chunk : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    test::RunResult render(const fs::path& out, const std::string& extra) {
        return test::run_inkline("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 13:24 --size 512x512 -q -o " +
                                 out.string() + " --png " + (out / "png" / "f%04d.png").string() + " --pdf " +
                                 (out / "pdf" / "f%04d.pdf").string() + " " + extra);
    }

    static std::set<std::string> files_under(const fs::path& root) {
        std::set<std::string> out;
        for (const auto& e : fs::recursive_directory_iterator(root))
            if (e.is_regular_file()) out.insert(fs::relative(e.path(), root).string());
        return out;
    }
};

// The polylines JSON may differ only in its timings.
nlohmann::json without_timings(const fs::path& path) {
    nlohmann::json doc = nlohmann::json::parse(test::read_text(path));
    doc["stats"].erase("ms");
    return doc;
}

TEST_F(Chunk, EveryChunkReproducesTheSequentialRun) {
    ASSERT_EQ(render(dir / "seq", "").code, 0);
    for (int k = 1; k <= 4; ++k) ASSERT_EQ(render(dir / "chunks", "--chunk " + std::to_string(k) + "/4").code, 0) << k;

    const std::set<std::string> sequential = files_under(dir / "seq");
    ASSERT_EQ(sequential.size(), 12u * 4u);
    EXPECT_EQ(files_under(dir / "chunks"), sequential);
    std::set<int> first_ids, all_ids, last_ids;
    for (const std::string& name : sequential) {
        const fs::path a = dir / "seq" / name, b = dir / "chunks" / name;
        if (name.ends_with(".json")) {
            EXPECT_EQ(without_timings(a), without_timings(b)) << name;
            const nlohmann::json doc = nlohmann::json::parse(test::read_text(a));
            for (const auto& s : doc["strokes"]) {
                const int id = s["id"].get<int>();
                all_ids.insert(id);
                if (name == "json/frame_0013.json") first_ids.insert(id);
                if (name == "json/frame_0024.json") last_ids.insert(id);
            }
        } else {
            EXPECT_EQ(test::read_text(a), test::read_text(b)) << name << " differs byte for byte";
        }
    }
    // Frames 13-24 of the sample have lines that appear and disappear, so ids carry real history.
    EXPECT_GT(all_ids.size(), first_ids.size());
    EXPECT_NE(first_ids, last_ids);
}

TEST_F(Chunk, ChunksPartitionTheFrames) {
    // 12 frames in 5 chunks: 3, 3, 2, 2, 2 frames.
    const int expected[] = {3, 3, 2, 2, 2};
    for (int k = 1; k <= 5; ++k) {
        const fs::path out = dir / ("c" + std::to_string(k));
        ASSERT_EQ(test::run_inkline("render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:12 --size 64x64 -q --svg " +
                                    (out / "f%02d.svg").string() + " --chunk " + std::to_string(k) + "/5")
                      .code,
                  0);
        EXPECT_EQ(files_under(out).size(), size_t(expected[k - 1])) << k;
    }
    EXPECT_TRUE(fs::exists(dir / "c1" / "f01.svg"));
    EXPECT_TRUE(fs::exists(dir / "c5" / "f12.svg"));
}

TEST_F(Chunk, SlurmArrayTaskSelectsTheChunk) {
    const std::string cmd = "SLURM_ARRAY_TASK_ID=12 SLURM_ARRAY_TASK_MIN=10 SLURM_ARRAY_TASK_MAX=13 " + test::inkline_command() +
                            " render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1:8 --size 64x64 -q --svg " +
                            (dir / "f%02d.svg").string() + " --chunk slurm";
    ASSERT_EQ(test::run_shell(cmd).code, 0);
    EXPECT_EQ(files_under(dir), (std::set<std::string>{"f05.svg", "f06.svg"})) << "task 3 of 4";
}

TEST_F(Chunk, BadChunksAreUsageErrors) {
    const std::string base = "render " + std::string(INKLINE_SAMPLES) + "/torus/scene.json -o " + dir.string() + " --chunk ";
    for (const char* bad : {"0/4", "5/4", "x", "1/0"}) {
        const test::RunResult r = test::run_inkline(base + bad);
        EXPECT_EQ(r.code, 2) << bad;
        EXPECT_NE(r.output.find("--chunk"), std::string::npos) << r.output;
    }
    const test::RunResult slurm = test::run_shell("env -u SLURM_ARRAY_TASK_ID " + test::inkline_command() + " " + base + "slurm");
    EXPECT_EQ(slurm.code, 2);
    EXPECT_NE(slurm.output.find("SLURM_ARRAY_TASK_ID is not set"), std::string::npos) << slurm.output;
    const test::RunResult pdf = test::run_inkline(base + "1/2 --pdf " + (dir / "all.pdf").string());
    EXPECT_EQ(pdf.code, 2);
    EXPECT_NE(pdf.output.find("per-frame pattern"), std::string::npos) << pdf.output;
}

}  // namespace
}  // namespace inkline
