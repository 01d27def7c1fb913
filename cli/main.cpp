// SPDX-License-Identifier: MIT
// The inkline program: parses arguments, runs a command, maps errors to exit codes:
// 0 success, 1 internal error, 2 usage or input error, 3 output error (docs/cli.md).
#include "cli/farm.h"
#include "cli/render.h"
#include "core/error.h"
#include "core/scene/scene.h"
#include "core/version.h"
#include "export/atomic_file.h"
#include "gl/context.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <system_error>

namespace {

enum ExitCode { kOk = 0, kInternal = 1, kInputError = 2, kOutputError = 3, kOutOfMemory = 5 };

// The render options, shared by `render` and the render arguments that `farm` passes on.
void add_render_options(CLI::App* cmd, inkline::cli::RenderArgs& r) {
    cmd->add_option("--frames", r.frames, "frame range A:B (inclusive), overrides the scene");
    cmd->add_option("--size", r.size, "image size WxH in pixels, overrides the scene");
    cmd->add_option("--json", r.json_pattern, "polylines JSON per frame, e.g. out/json/frame_%04d.json");
    cmd->add_option("--svg", r.svg_pattern, "SVG per frame, e.g. out/svg/frame_%04d.svg");
    cmd->add_option("--png", r.png_pattern, "PNG per frame (Cairo), e.g. out/png/frame_%04d.png");
    cmd->add_option("--preview", r.preview_pattern,
                    "GL preview PNG per frame, strokes textured with the brush tip, e.g. out/preview/frame_%04d.png");
    cmd->add_option("--preview-underlay", r.preview_underlay, "mesh under the preview's strokes: none, flat or toon")
        ->capture_default_str();
    cmd->add_option("--pdf", r.pdf_path,
                           "PDF: a file gets one page per frame; a pattern with %04d one file per frame");
    cmd->add_option("--write-on", r.write_on,
                    "draw each frame stroke by stroke in drawing order over SECONDS: the outputs become a frame "
                    "sequence at --fps (default: the scene's write_on)")
        ->check(CLI::Range(1e-6, inkline::core::kMaxWriteOnSeconds));
    cmd->add_option("--animated-svg", r.animated_svg,
                    "with a write-on: an animated SVG (SMIL) of each frame's write-on, e.g. out/write_on_%04d.svg");
    cmd->add_option("--page", r.page, "PDF page size: A4, A3, Letter or WxHmm (default: the image at --dpi)");
    cmd->add_option("--margin", r.margin_mm, "PDF margin in mm with --page")->capture_default_str();
    cmd->add_option("--dpi", r.dpi, "PDF pixels per inch without --page")->capture_default_str();
    cmd->add_option("--background", r.background, "colour behind the lines, #rrggbb (default: transparent)");
    cmd->add_option("-o,--out", r.out_dir, "folder for every output not given explicitly (default: out)");
    cmd->add_option("--tracker", r.tracker, "silhouette extraction: incremental or brute")
        ->capture_default_str();
    cmd->add_option("--contour", r.contour,
                    "silhouettes along mesh edges (mesh) or the smooth contour across faces (smooth); "
                    "default: the scene's lines.contour, else mesh");
    cmd->add_option("--visibility", r.visibility,
                           "occlusion test: auto (gl on hardware GL, else raycast), gl, raycast or exact")
        ->capture_default_str();
    cmd->add_option("--gl", r.gl_backend, "GL context: auto (EGL, then OSMesa), egl or osmesa")
        ->capture_default_str();
    cmd->add_option("--gltf-scene", r.gltf_scene, "glTF input: draw this scene of the file (default: its default scene)")
        ->check(CLI::Range(0, 1 << 30));
    cmd->add_option("--animation", r.animation, "glTF input: play only this animation, by name or index (default: all together)");
    cmd->add_option("--camera", r.camera,
                    "glTF input: look through this camera, by its or its node's name, or its index in the file's "
                    "cameras (default: the first)");
    cmd->add_option("--fps", r.fps,
                    "glTF input: frame F is animation time F / fps; a write-on's frames per second (default: 24, or "
                    "the scene's fps)")
        ->check(CLI::Range(1e-6, 1e6));
    cmd->add_option("--layers", r.layers, "SVG layers: kind, object or style (a layer per object or per style with its kind layers inside)")
        ->capture_default_str();
    cmd->add_flag("--centerline", r.centerline,
                         "constant-width centerlines instead of brush outlines (pen plotters, cutters)");
    cmd->add_option("--path-format", r.path_format,
                    "brush outlines in SVG, PDF and PNG as polygons (polygon) or cubic Bezier curves fitted within "
                    "brush.max_deviation_px (bezier)")
        ->capture_default_str();
    cmd->add_flag("--hidden", r.hidden, "also output occluded lines (visible: false)");
    cmd->add_option("--tone", r.tone,
                    "tone on the surface: stipple (dots), hatch or crosshatch (with the scene's tone block or its "
                    "defaults), or none; default: the scene's tone.mode, else none");
    cmd->add_option("--chunk", r.chunk,
                           "render chunk K of N contiguous chunks of the frames (K/N), or 'slurm' for the job array task");
    cmd->add_flag("--keep-going", r.keep_going, "report a frame that fails and render the rest");
    cmd->add_option("--max-faces", r.max_faces, "refuse meshes with more faces")
        ->capture_default_str()
        ->check(CLI::Range(size_t(1), size_t(1) << 32));
    cmd->add_option("--max-image-side", r.max_image_side, "refuse larger images, px")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_flag("-v,--verbose", r.verbose, "per-frame details on stderr");
    cmd->add_flag("-q,--quiet", r.quiet, "no summary or warnings on stderr");

}

// Parses the render options given to `farm` after "--".
inkline::cli::RenderArgs parse_render_args(const std::vector<std::string>& words) {
    CLI::App app{"render options"};
    inkline::cli::RenderArgs r;
    add_render_options(&app, r);
    std::vector<std::string> reversed(words.rbegin(), words.rend());  // CLI11 takes them last first
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        throw inkline::InputError(std::string("render options after --: ") + e.what());
    }
    return r;
}

// The longest error line, in characters: a message quoting a huge value stays readable.
constexpr size_t kMaxMessageChars = 300;

// Prints one error line: control characters (a newline in a file name) shown as '?', a long
// message cut in the middle.
void report(const char* prefix, const std::string& message) {
    std::cerr << prefix << inkline::quote_value(message, kMaxMessageChars) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"inkline: brush-stroked line art from 3D meshes and their animation"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "inkline " + std::string(inkline::kVersion));

    inkline::cli::RenderArgs render;
    CLI::App* render_cmd = app.add_subcommand("render", "Render a scene (.json), a glTF shot, or a mesh as a turntable");
    render_cmd->add_option("input", render.input, "scene file (.json), glTF shot (.glb .gltf) or mesh (.obj .off .ply .stl)")
        ->required();
    add_render_options(render_cmd, render);

    inkline::cli::FarmArgs farm;
    CLI::App* farm_cmd = app.add_subcommand("farm", "Write (and with --submit, submit) a Slurm job array for a sequence");
    farm_cmd->add_option("scene", farm.scene, "scene file (.json) or mesh")->required();
    farm_cmd->add_option("--chunks", farm.chunks, "number of chunks (array tasks)")->required();
    farm_cmd->add_option("-o,--out", farm.out_dir, "output folder; the scripts go to DIR/slurm/")->required();
    farm_cmd->add_option("--partition", farm.partition, "sbatch --partition");
    farm_cmd->add_option("--time", farm.time, "sbatch --time per chunk, e.g. 01:00:00");
    farm_cmd->add_option("--mem", farm.mem, "sbatch --mem per chunk, e.g. 4G");
    farm_cmd->add_option("--sbatch", farm.sbatch_args, "any other sbatch option, e.g. --sbatch=--account=lab (repeatable)");
    farm_cmd->add_option("--assemble-pdf", farm.assemble_pdf,
                         "multi-page PDF assembled from the per-frame PDFs (default DIR/sequence.pdf)");
    farm_cmd->add_flag("--submit", farm.submit, "submit with sbatch after writing the scripts");
    farm_cmd->add_flag("--summarize", farm.summarize, "check every frame's files and assemble the PDF (the summary job)");
    farm_cmd->footer("Render options for every chunk follow a --, e.g. inkline farm scene.json --chunks 8 -o out -- --png "
                     "'out/png/f_%04d.png'");

    std::string info_path;
    CLI::App* info_cmd = app.add_subcommand("info", "Print a mesh's topology report");
    info_cmd->add_option("mesh", info_path, "mesh file")->required();

    // Words after the first "--" are render options that `farm` passes on to every chunk.
    int own_words = argc;
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--") {
            own_words = i;
            farm.render_args.assign(argv + i + 1, argv + argc);
            break;
        }
    }
    try {
        app.parse(own_words, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        report("inkline: error: ", std::string(e.what()) + " (see inkline --help)");
        return kInputError;
    }
    inkline::output::install_interrupt_cleanup();
    try {
        if (*render_cmd) return inkline::cli::run_render(render);
        if (*info_cmd) return inkline::cli::run_info(info_path);
        if (*farm_cmd) return inkline::cli::run_farm(farm, parse_render_args(farm.render_args));
    } catch (const inkline::InputError& e) {
        report("inkline: error: ", e.what());
        return kInputError;
    } catch (const inkline::OutputError& e) {
        report("inkline: error: ", e.what());
        return kOutputError;
    } catch (const inkline::gl::ContextError& e) {
        report("inkline: error: no usable OpenGL context: ",
               std::string(e.what()) + " (try --gl osmesa, or --visibility raycast or exact)");
        return kInputError;
    } catch (const inkline::OutOfMemory& e) {
        report("inkline: error: out of memory: ", e.what());
        return kOutOfMemory;
    } catch (const std::bad_alloc&) {
        report("inkline: error: ", "out of memory");
        return kOutOfMemory;
    } catch (const std::system_error& e) {
        // A thread that cannot start (EAGAIN) or memory that cannot be mapped is a resource limit.
        if (e.code() == std::errc::resource_unavailable_try_again || e.code() == std::errc::not_enough_memory) {
            report("inkline: error: out of memory or threads: ", e.what());
            return kOutOfMemory;
        }
        report("inkline: internal error: ", e.what());
        return kInternal;
    } catch (const std::exception& e) {
        report("inkline: internal error: ", e.what());
        return kInternal;
    }
    return kInternal;
}
