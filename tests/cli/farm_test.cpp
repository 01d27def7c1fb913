// SPDX-License-Identifier: MIT
// `inkline farm`: the job scripts, and the summary that finds a failed chunk and completes once
// that chunk alone is re-run. (tests/slurm/slurm_test.sh runs the same on a real Slurm cluster.)
#include "tests/support/obj.h"
#include "tests/support/run.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace inkline {
namespace {

namespace fs = std::filesystem;

TEST(Farm, SummaryNamesTheFailedChunkAndCompletesAfterItsRerun) {
    const fs::path dir = test::fresh_temp_dir("farm_summary");
    const std::string scene = std::string(INKLINE_SAMPLES) + "/torus/scene.json";
    const std::string render_args = " -- --frames 1:12 --size 128x128 --pdf " + (dir / "pdf" / "f_%04d.pdf").string();
    const std::string farm = "farm " + scene + " --chunks 4 -o " + dir.string();
    const test::RunResult wrote = test::run_inkline(farm + " --partition debug --mem 2G" + render_args);
    ASSERT_EQ(wrote.code, 0) << wrote.output;
    const std::string job = test::read_text(dir / "slurm" / "render.sbatch");
    EXPECT_NE(job.find("#SBATCH --array=1-4"), std::string::npos) << job;
    EXPECT_NE(job.find("#SBATCH --partition=debug"), std::string::npos);
    EXPECT_NE(job.find("#SBATCH --mem=2G"), std::string::npos);
    EXPECT_NE(job.find("--chunk slurm"), std::string::npos);
    EXPECT_NE(test::read_text(dir / "slurm" / "submit.sh").find("--dependency=afterany:$array"), std::string::npos);

    // Chunks 1, 2 and 4 run as Slurm would start them; chunk 3 "fails".
    const std::string chunk = "render " + scene + " -q -o " + dir.string() + " --chunk ";
    const std::string rest = " --frames 1:12 --size 128x128 --pdf " + (dir / "pdf" / "f_%04d.pdf").string();
    for (int k : {1, 2, 4}) ASSERT_EQ(test::run_inkline(chunk + std::to_string(k) + "/4" + rest).code, 0);
    const test::RunResult partial = test::run_inkline(farm + " --summarize" + render_args);
    EXPECT_EQ(partial.code, 4) << partial.output;
    EXPECT_NE(partial.output.find("chunk 3 (frames 7-9): missing frame(s) 7 8 9; re-run: sbatch --array=3"),
              std::string::npos)
        << partial.output;
    EXPECT_FALSE(fs::exists(dir / "sequence.pdf"));

    ASSERT_EQ(test::run_inkline(chunk + "3/4" + rest).code, 0);
    const test::RunResult full = test::run_inkline(farm + " --summarize" + render_args);
    EXPECT_EQ(full.code, 0) << full.output;
    EXPECT_NE(test::read_text(dir / "slurm" / "summary.txt").find("complete"), std::string::npos);
    const test::RunResult pages = test::run_shell("pdfinfo " + (dir / "sequence.pdf").string());
    EXPECT_NE(pages.output.find("Pages:           12"), std::string::npos) << pages.output;
    fs::remove_all(dir);
}

TEST(Farm, SingleFilePdfIsRefused) {
    const fs::path dir = test::fresh_temp_dir("farm_pdf");
    const test::RunResult r = test::run_inkline("farm " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --chunks 2 -o " +
                                                dir.string() + " -- --pdf " + (dir / "all.pdf").string());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("per-frame PDFs"), std::string::npos) << r.output;
    fs::remove_all(dir);
}

TEST(Farm, BadModeOptionsAreRefusedBeforeAnyScriptIsWritten) {
    const fs::path dir = test::fresh_temp_dir("farm_modes");
    const std::string farm = "farm " + std::string(INKLINE_SAMPLES) + "/torus/scene.json --chunks 2 -o " + dir.string();
    for (const auto& [option, message] : std::vector<std::pair<std::string, std::string>>{
             {"--tracker nope", "--tracker 'nope': expected incremental or brute"},
             {"--visibility nope", "--visibility 'nope': expected auto, gl, raycast or exact"},
             {"--contour nope", "--contour 'nope': expected mesh or smooth"},
             {"--path-format nope", "--path-format 'nope': expected polygon or bezier"},
             {"--gl nope", "--gl 'nope': expected auto, egl or osmesa"}}) {
        const test::RunResult r = test::run_inkline(farm + " -- " + option);
        EXPECT_EQ(r.code, 2) << option << ": " << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir / "slurm")) << option;
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace inkline
