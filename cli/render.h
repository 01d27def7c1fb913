// SPDX-License-Identifier: MIT
// `inkline render` and `inkline info`: the wiring from a scene to files, frame by frame.
#pragma once

#include <cstddef>
#include <string>

namespace inkline::cli {

struct RenderArgs {
    std::string input;  // scene .json or a mesh file
    std::string frames;
    std::string size;
    std::string json_pattern;
    std::string svg_pattern;
    std::string out_dir;
    std::string tracker = "brute";
    std::string visibility = "exact";
    bool hidden = false;
    bool keep_going = false;
    size_t max_faces = 50'000'000;
    bool verbose = false;
    bool quiet = false;
};

// Renders every frame; returns the process exit code. Throws InputError / OutputError for
// failures that stop the run.
int run_render(const RenderArgs& args);

// Prints a mesh's topology report; returns the exit code.
int run_info(const std::string& mesh_path);

}  // namespace inkline::cli
