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
    std::string png_pattern;
    std::string preview_pattern;          // GL preview PNG per frame (textured brush strokes)
    std::string preview_underlay = "none";  // none | flat | toon: the mesh under the preview's strokes
    double write_on = 0.0;        // s: each frame drawn stroke by stroke; 0: the scene's write_on (none by default)
    std::string animated_svg;     // with a write-on: an animated SVG per frame
    std::string pdf_path;     // a pattern with a frame field: one file per frame; else one page per frame
    std::string page;         // A4, A3, Letter, WxHmm; empty: the image size at dpi
    double margin_mm = 10.0;
    double dpi = 96.0;
    std::string background;   // colour behind the lines; empty: transparent (SVG, PNG) / white paper (PDF)
    std::string out_dir;
    std::string tracker = "incremental";  // incremental | brute
    std::string contour;                  // mesh | smooth; empty: the scene's (mesh)
    std::string visibility = "auto";      // auto | gl | raycast | exact
    std::string gl_backend = "auto";      // auto | egl | osmesa
    bool centerline = false;              // constant-width centerlines instead of brush outlines
    std::string path_format = "polygon";  // polygon | bezier: how SVG, PDF and PNG write outlines
    std::string layers = "kind";          // SVG layers: kind, or object (each with kind layers inside)
    bool hidden = false;
    std::string tone;         // stipple | none: overrides the scene's tone mode; empty: the scene's
    int gltf_scene = -1;      // glTF input: the file's scene; -1: the scene JSON's or the file's default
    std::string animation;    // glTF input: one animation by name or index; empty: all
    std::string camera;       // glTF input: a camera by name; empty: the first
    double fps = 0.0;         // glTF input: frames per second of animation time; 0: the scene's (24)
    std::string chunk;        // "K/N" or "slurm": render the K-th of N contiguous chunks of the frames
    bool keep_going = false;
    size_t max_faces = 50'000'000;
    int max_image_side = 16384;  // px
    bool verbose = false;
    bool quiet = false;
};

// Renders every frame; returns the process exit code. Throws InputError / OutputError for
// failures that stop the run.
int run_render(const RenderArgs& args);

// The frames of chunk `k` (1-based) of `n` contiguous chunks of [first, last]: sizes differ by at
// most one, earlier chunks take the extra frames. Empty (first > last) when n exceeds the count.
struct ChunkRange {
    int first = 0;
    int last = -1;
};
ChunkRange chunk_range(int first, int last, int k, int n);

// What a render would write: its frame range and output patterns (reads the scene's frames).
struct RenderPlan {
    int first = 1;
    int last = 1;  // the last frame written (a write-on may write frames past the shot's)
    std::string json, svg, png, preview, pdf;  // patterns; pdf may be a single file
    bool pdf_per_frame = false;
    bool write_on = false;  // each frame written on (cannot be split into chunks)
};
RenderPlan plan_render(const RenderArgs& args);

// Prints a mesh's topology report; returns the exit code.
int run_info(const std::string& mesh_path);

}  // namespace inkline::cli
