// SPDX-License-Identifier: MIT
// The inkline program: parses arguments, runs a command, maps errors to exit codes:
// 0 success, 1 internal error, 2 usage or input error, 3 output error (docs/cli.md).
#include "cli/render.h"
#include "core/error.h"
#include "export/atomic_file.h"

#include <CLI/CLI.hpp>

#include <iostream>

namespace {

enum ExitCode { kOk = 0, kInternal = 1, kInputError = 2, kOutputError = 3 };

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"inkline: brush-stroked line art from 3D meshes and their animation"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "inkline 0.1.0");

    inkline::cli::RenderArgs render;
    CLI::App* render_cmd = app.add_subcommand("render", "Render a scene (.json) or a mesh as a turntable");
    render_cmd->add_option("input", render.input, "scene file (.json) or mesh (.obj .off .ply .stl)")->required();
    render_cmd->add_option("--frames", render.frames, "frame range A:B (inclusive), overrides the scene");
    render_cmd->add_option("--size", render.size, "image size WxH in pixels, overrides the scene");
    render_cmd->add_option("--json", render.json_pattern, "polylines JSON per frame, e.g. out/json/frame_%04d.json");
    render_cmd->add_option("--svg", render.svg_pattern, "SVG per frame, e.g. out/svg/frame_%04d.svg");
    render_cmd->add_option("--png", render.png_pattern, "PNG per frame (Cairo), e.g. out/png/frame_%04d.png");
    render_cmd->add_option("--pdf", render.pdf_path,
                           "PDF: a file gets one page per frame; a pattern with %04d one file per frame");
    render_cmd->add_option("--page", render.page, "PDF page size: A4, A3, Letter or WxHmm (default: the image at --dpi)");
    render_cmd->add_option("--margin", render.margin_mm, "PDF margin in mm with --page")->capture_default_str();
    render_cmd->add_option("--dpi", render.dpi, "PDF pixels per inch without --page")->capture_default_str();
    render_cmd->add_option("--background", render.background, "colour behind the lines, #rrggbb (default: transparent)");
    render_cmd->add_option("-o,--out", render.out_dir, "folder for every output not given explicitly (default: out)");
    render_cmd->add_option("--tracker", render.tracker, "silhouette extraction: incremental or brute")
        ->capture_default_str();
    render_cmd->add_option("--visibility", render.visibility,
                           "occlusion test: auto (gl on hardware GL, else raycast), gl, raycast or exact")
        ->capture_default_str();
    render_cmd->add_option("--gl", render.gl_backend, "GL context: auto (EGL, then OSMesa), egl or osmesa")
        ->capture_default_str();
    render_cmd->add_flag("--centerline", render.centerline,
                         "constant-width centerlines instead of brush outlines (pen plotters, cutters)");
    render_cmd->add_flag("--hidden", render.hidden, "also output occluded lines (visible: false)");
    render_cmd->add_option("--chunk", render.chunk,
                           "render chunk K of N contiguous chunks of the frames (K/N), or 'slurm' for the job array task");
    render_cmd->add_flag("--keep-going", render.keep_going, "report a frame that fails and render the rest");
    render_cmd->add_option("--max-faces", render.max_faces, "refuse meshes with more faces")->capture_default_str();
    render_cmd->add_flag("-v,--verbose", render.verbose, "per-frame details on stderr");
    render_cmd->add_flag("-q,--quiet", render.quiet, "no summary or warnings on stderr");

    std::string info_path;
    CLI::App* info_cmd = app.add_subcommand("info", "Print a mesh's topology report");
    info_cmd->add_option("mesh", info_path, "mesh file")->required();

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? kOk : kInputError;
    }
    inkline::output::install_interrupt_cleanup();
    try {
        if (*render_cmd) return inkline::cli::run_render(render);
        if (*info_cmd) return inkline::cli::run_info(info_path);
    } catch (const inkline::InputError& e) {
        std::cerr << "inkline: error: " << e.what() << "\n";
        return kInputError;
    } catch (const inkline::OutputError& e) {
        std::cerr << "inkline: error: " << e.what() << "\n";
        return kOutputError;
    } catch (const std::exception& e) {
        std::cerr << "inkline: internal error: " << e.what() << "\n";
        return kInternal;
    }
    return kInternal;
}
