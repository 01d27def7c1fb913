// SPDX-License-Identifier: MIT
// The files a render writes: its output patterns, resolved from the options, and the checks that
// refuse, before anything is written, outputs that would replace an input or one another.
#pragma once

#include "cli/render.h"

#include <filesystem>
#include <string>
#include <vector>

namespace inkline::cli {

// Output patterns of a run; an empty one is not written. `pdf` is a pattern when
// pdf_per_frame, else one file with a page per frame.
struct Outputs {
    std::string json;
    std::string svg;
    std::string png;
    std::string preview;
    std::string pdf;
    bool pdf_per_frame = false;
    std::string animated_svg;  // one per frame drawn, not per frame written
};

// Explicit patterns as given; -o DIR fills in JSON and SVG; no output at all means -o out.
// frame_count frames are drawn and written_count written (more with a write-on). Throws
// InputError when several frames are written and a pattern has no frame field.
Outputs resolve_outputs(const RenderArgs& args, int frame_count, int written_count);

// A file the run reads, named by its role in messages ("mesh", "scene", "brush tip").
struct InputFile {
    std::string role;
    std::filesystem::path path;
};

// Refuses the run before it writes anything when, for a frame in [first, last] (per-frame outputs
// up to written_last, animated SVGs up to last), an output is one of `inputs` (the same file,
// through any link), two outputs name the same file, or an output exists and has no write
// permission. Throws InputError (OutputError for a read-only output).
void check_outputs(const Outputs& outputs, int first, int last, int written_last, const std::vector<InputFile>& inputs);

}  // namespace inkline::cli
