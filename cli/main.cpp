// SPDX-License-Identifier: MIT
// The inkline program: parses arguments and wires the pipeline
//   load scene -> extract_feature_edges -> chain_feature_edges -> split_by_visibility
//   -> polylines JSON / SVG
// Exit codes: 0 success, 1 internal error, 2 usage or input error, 3 output error.

#include "core/chaining.h"
#include "core/error.h"
#include "core/exact_visibility.h"
#include "core/features.h"
#include "core/frame_lines.h"
#include "core/frame_pattern.h"
#include "core/mesh_frames.h"
#include "core/mesh_io.h"
#include "core/scene.h"
#include "core/topology.h"
#include "core/visibility.h"
#include "export/atomic_file.h"
#include "export/json.h"
#include "export/svg.h"

#include <CLI/CLI.hpp>
#include <glm/mat4x4.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>
#include <string>

namespace {

namespace core = inkline::core;
namespace output = inkline::output;
namespace fs = std::filesystem;

enum ExitCode { kOk = 0, kInternal = 1, kInputError = 2, kOutputError = 3 };

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
    bool verbose = false;
    bool quiet = false;
};

class Clock {
  public:
    double lap_ms() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
        last_ = now;
        return ms;
    }

  private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// "A:B" or "A" -> inclusive frame range.
std::pair<int, int> parse_frames(const std::string& text) {
    static const std::regex range(R"(^\s*(-?\d+)\s*(?::\s*(-?\d+))?\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, range)) throw inkline::InputError("--frames '" + text + "': expected A:B");
    const int a = std::stoi(m[1]);
    const int b = m[2].matched ? std::stoi(m[2]) : a;
    if (a > b) throw inkline::InputError("--frames '" + text + "': first frame is after the last");
    return {a, b};
}

core::ImageSize parse_size(const std::string& text) {
    static const std::regex size(R"(^\s*(\d{1,9})\s*[xX]\s*(\d{1,9})\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, size)) throw inkline::InputError("--size '" + text + "': expected WxH");
    const core::ImageSize image{std::stoi(m[1]), std::stoi(m[2])};
    if (image.width <= 0 || image.height <= 0 || image.width > core::kMaxImageSide ||
        image.height > core::kMaxImageSide) {
        throw inkline::InputError("--size '" + text + "': each side must be 1.." +
                                  std::to_string(core::kMaxImageSide) + " px");
    }
    return image;
}

bool is_scene_file(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    return ext == ".json" || ext == ".JSON";
}

// World-space bounds of object-space bounds under a transform (its eight corners).
core::Bounds transform_bounds(const core::Bounds& b, const glm::dmat4& world_from_object) {
    core::Bounds out;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                (i & 4) ? b.max.z : b.min.z);
        out.add(glm::dvec3(world_from_object * glm::dvec4(corner, 1.0)));
    }
    return out;
}

int run_render(const RenderArgs& args) {
    // Scene: a file, or a default turntable around a bare mesh.
    core::Scene scene;
    std::optional<core::MeshFrames> meshes;
    if (is_scene_file(args.input)) {
        scene = core::load_scene(args.input);
    } else {
        scene.mesh.path = args.input;
    }
    int first = scene.first_frame, last = scene.last_frame;
    if (!is_scene_file(args.input)) first = 1, last = 48;
    if (!args.frames.empty()) std::tie(first, last) = parse_frames(args.frames);
    meshes.emplace(scene.mesh, first);
    if (!is_scene_file(args.input)) {
        scene = core::default_turntable_scene(args.input, core::bounds_of(meshes->at(first).positions));
        if (args.frames.empty()) first = scene.first_frame, last = scene.last_frame;
    }
    if (!args.size.empty()) scene.image = parse_size(args.size);
    if (args.hidden) scene.lines.hidden = true;

    // Outputs: explicit patterns as given; -o DIR fills in the rest; neither means -o out.
    std::string json_pattern = args.json_pattern, svg_pattern = args.svg_pattern;
    const bool any_explicit = !json_pattern.empty() || !svg_pattern.empty();
    if (!args.out_dir.empty() || !any_explicit) {
        const fs::path dir = args.out_dir.empty() ? fs::path("out") : fs::path(args.out_dir);
        if (json_pattern.empty()) json_pattern = (dir / "json" / "frame_%04d.json").string();
        if (svg_pattern.empty()) svg_pattern = (dir / "svg" / "frame_%04d.svg").string();
    }
    for (const std::string* pattern : {&json_pattern, &svg_pattern}) {
        if (!pattern->empty() && last > first && !core::has_frame_field(*pattern)) {
            throw inkline::InputError("output pattern '" + *pattern +
                                      "' has no frame field such as %04d but " +
                                      std::to_string(last - first + 1) + " frames are rendered");
        }
    }
    if (args.tracker != "brute") throw inkline::InputError("--tracker '" + args.tracker + "': only 'brute' is available");
    if (args.visibility != "exact") throw inkline::InputError("--visibility '" + args.visibility + "': only 'exact' is available");

    if (!args.quiet) {
        for (const std::string& w : meshes->warnings()) std::cerr << "inkline: warning: " << w << "\n";
    }

    const core::EdgeTable& table = meshes->edges();
    const core::VisibilityOptions visibility{.keep_hidden = scene.lines.hidden};
    std::unique_ptr<core::ExactOcclusion> occlusion;  // static meshes build the tree once
    const auto total_start = std::chrono::steady_clock::now();
    size_t total_strokes = 0, files = 0;
    for (int frame = first; frame <= last; ++frame) {
        Clock clock;
        core::FrameLines result;
        result.frame = frame;
        result.image = scene.image;
        result.light = scene.light;
        const core::Mesh& mesh = meshes->at(frame);
        const double load_ms = clock.lap_ms();

        const glm::dmat4 world_from_object = core::world_from_object_at(scene, frame);
        result.camera = core::camera_at(scene, frame, transform_bounds(core::bounds_of(mesh.positions), world_from_object));
        const core::Projection projection(result.camera, scene.image, world_from_object);

        const core::FeatureEdges features = core::extract_feature_edges(mesh, table, projection.eye_object(), scene.lines);
        const double extract_ms = clock.lap_ms();
        const std::vector<core::Chain> chains = core::chain_feature_edges(features, table);
        const double chain_ms = clock.lap_ms();
        if (!occlusion || meshes->is_sequence()) occlusion = std::make_unique<core::ExactOcclusion>(mesh, table);
        result.strokes = core::split_by_visibility(chains, mesh, projection, *occlusion, visibility);
        const double visibility_ms = clock.lap_ms();

        result.stats.faces = mesh.triangles.size();
        result.stats.edges = table.edge_count();
        result.stats.edges_tested = features.edges_tested;
        result.stats.faces_tested = features.faces_tested;
        result.stats.feature_edges = features.count_by_kind();
        core::tally_visible_length(result);
        result.stats.ms = {{"load", load_ms}, {"extract", extract_ms}, {"chain", chain_ms}, {"visibility", visibility_ms}};

        if (!svg_pattern.empty()) {
            output::write_file_atomically(core::format_frame(svg_pattern, frame), output::centerline_svg(result, {}));
            ++files;
        }
        const double svg_ms = clock.lap_ms();
        result.stats.ms.emplace_back("svg", svg_ms);
        if (!json_pattern.empty()) {
            output::write_file_atomically(core::format_frame(json_pattern, frame), output::polylines_json(result));
            ++files;
        }
        total_strokes += result.strokes.size();
        if (args.verbose) {
            std::fprintf(stderr, "frame %d: %zu strokes, %zu feature edges, extract %.1f ms, chain %.1f ms, visibility %.1f ms\n",
                         frame, result.strokes.size(), features.edges.size(), extract_ms, chain_ms, visibility_ms);
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - total_start).count();
    if (!args.quiet) {
        const int count = last - first + 1;
        std::fprintf(stderr, "inkline: %d frame(s), %zu strokes, %zu files in %.2f s (%.1f ms/frame)\n", count,
                     total_strokes, files, seconds, 1000.0 * seconds / count);
    }
    return kOk;
}

int run_info(const std::string& path) {
    const core::LoadedMesh loaded = core::load_mesh(path);
    const core::EdgeTable table = core::build_edge_table(loaded.mesh);
    const core::MeshReport r = core::describe_mesh(loaded.mesh, table);
    const core::Bounds b = core::bounds_of(loaded.mesh.positions);
    std::printf("file: %s\n", path.c_str());
    std::printf("vertices: %zu\nfaces: %zu\nedges: %zu\nboundary edges: %zu\nnon-manifold edges: %zu\n", r.vertices,
                r.faces, r.edges, r.boundary_edges, r.non_manifold_edges);
    std::printf("degenerate faces: %zu\ninconsistently oriented edges: %zu\nconnected components: %zu\n",
                r.degenerate_faces, r.inconsistent_edges, r.connected_components);
    std::printf("bounds: [%g, %g, %g] .. [%g, %g, %g]\n", b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z);
    for (const std::string& w : loaded.warnings) std::printf("warning: %s\n", w.c_str());
    for (const std::string& w : core::mesh_warnings(r)) std::printf("warning: %s\n", w.c_str());
    return kOk;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"inkline: brush-stroked line art from 3D meshes and their animation"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "inkline 0.1.0");

    RenderArgs render;
    CLI::App* render_cmd = app.add_subcommand("render", "Render a scene (.json) or a mesh as a turntable");
    render_cmd->add_option("input", render.input, "scene file (.json) or mesh (.obj .off .ply .stl)")->required();
    render_cmd->add_option("--frames", render.frames, "frame range A:B (inclusive), overrides the scene");
    render_cmd->add_option("--size", render.size, "image size WxH in pixels, overrides the scene");
    render_cmd->add_option("--json", render.json_pattern, "polylines JSON per frame, e.g. out/json/frame_%04d.json");
    render_cmd->add_option("--svg", render.svg_pattern, "SVG per frame, e.g. out/svg/frame_%04d.svg");
    render_cmd->add_option("-o,--out", render.out_dir, "folder for every output not given explicitly (default: out)");
    render_cmd->add_option("--tracker", render.tracker, "silhouette extraction: brute")->capture_default_str();
    render_cmd->add_option("--visibility", render.visibility, "visibility test: exact")->capture_default_str();
    render_cmd->add_flag("--hidden", render.hidden, "also output occluded lines (visible: false)");
    render_cmd->add_flag("-v,--verbose", render.verbose, "per-frame details on stderr");
    render_cmd->add_flag("-q,--quiet", render.quiet, "no summary or warnings on stderr");

    std::string info_path;
    CLI::App* info_cmd = app.add_subcommand("info", "Print a mesh's topology report");
    info_cmd->add_option("mesh", info_path, "mesh file")->required();

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? kOk : kInputError;
    }
    try {
        if (*render_cmd) return run_render(render);
        if (*info_cmd) return run_info(info_path);
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
