// SPDX-License-Identifier: MIT
// `inkline farm`: a Slurm job array that renders a sequence in chunks, and a dependent job that
// checks every frame, names the chunks to re-run and assembles the multi-page PDF.
#pragma once

#include "cli/render.h"

#include <string>
#include <vector>

namespace inkline::cli {

// Exit code of a farm summary that found frames missing.
inline constexpr int kFramesMissing = 4;

struct FarmArgs {
    std::string scene;
    int chunks = 1;
    std::string out_dir;
    std::string partition, time, mem;
    std::vector<std::string> sbatch_args;  // passed through as #SBATCH lines
    std::string assemble_pdf;              // multi-page PDF to assemble from per-frame PDFs
    bool submit = false;
    bool summarize = false;                // the summary job's mode: check frames, assemble PDF
    std::vector<std::string> render_args;  // after "--": passed to every `inkline render`
};

// `render_args` parsed into `base` (its input and -o are the farm's). Writes DIR/slurm/ or, with
// summarize, checks the outputs. Returns the exit code.
int run_farm(const FarmArgs& args, const RenderArgs& render);

}  // namespace inkline::cli
