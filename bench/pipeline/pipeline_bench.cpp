// SPDX-License-Identifier: MIT
// Where a scene's render time goes: every stage of `inkline render --svg` for each frame, as
// cli/render.cpp's Sequence and Writers run them (incremental tracker, chaining, ray-cast
// visibility, brush strokes, SVG built and written), in wall-clock and whole-process CPU time,
// plus the one-time costs (mesh file, edge table, cone tree, BVH) and the peak memory.
//
//   inkline_pipeline_bench SCENE.json [--frames A:B] [--svg DIR] [--repeat N]
//
// Prints a markdown table: per stage, the median over frames 2.. (frame 1 pays the one-time
// builds, listed apart). CPU time is summed over threads, so on a shared machine it measures
// this work alone where wall time also measures the neighbours. --repeat renders the frames
// N times over (after the first pass) for steadier medians.

#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/lines/chaining.h"
#include "core/lines/features.h"
#include "core/lines/silhouette_tracker.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_lines.h"
#include "core/scene/scene.h"
#include "core/strokes/strokes.h"
#include "core/visibility/raycast_visibility.h"
#include "core/visibility/visibility.h"
#include "export/atomic_file.h"
#include "export/drawing.h"
#include "export/svg.h"

namespace {

namespace core = inkline::core;
namespace output = inkline::output;

// Wall-clock and whole-process CPU time since the last lap, ms.
class Laps {
  public:
    struct Lap {
        double wall_ms, cpu_ms;
    };
    Lap lap() {
        const auto wall = std::chrono::steady_clock::now();
        const double cpu = process_cpu_ms();
        const Lap out{std::chrono::duration<double, std::milli>(wall - wall_).count(), cpu - cpu_};
        wall_ = wall;
        cpu_ = cpu;
        return out;
    }

  private:
    static double process_cpu_ms() {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
    }
    std::chrono::steady_clock::time_point wall_ = std::chrono::steady_clock::now();
    double cpu_ = process_cpu_ms();
};

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

[[noreturn]] void usage_error(const std::string& what) {
    std::fprintf(stderr,
                 "inkline_pipeline_bench: %s\nusage: inkline_pipeline_bench SCENE.json [--frames A:B] "
                 "[--svg DIR] [--repeat N]\n",
                 what.c_str());
    std::exit(2);
}

const char* const kStages[] = {"extract", "chain", "visibility", "strokes", "svg"};

int run(int argc, char** argv) {
    if (argc < 2) usage_error("no scene");
    const std::filesystem::path scene_path = argv[1];
    std::optional<std::pair<int, int>> frames;
    std::filesystem::path svg_dir = std::filesystem::temp_directory_path() / "inkline_pipeline_bench";
    int repeat = 0;
    for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        if (i + 1 >= argc) usage_error("missing value for " + arg);
        const std::string value = argv[++i];
        if (arg == "--frames") {
            const size_t colon = value.find(':');
            frames = {std::atoi(value.c_str()),
                      std::atoi(value.c_str() + (colon == std::string::npos ? 0 : colon + 1))};
        } else if (arg == "--svg") {
            svg_dir = value;
        } else if (arg == "--repeat") {
            repeat = std::atoi(value.c_str());
        } else {
            usage_error("unknown option " + arg);
        }
    }

    Laps laps;
    const core::Scene scene = core::load_scene(scene_path);
    const int first = frames ? frames->first : scene.first_frame, last = frames ? frames->second : scene.last_frame;
    core::MeshFrames meshes(scene.mesh, first);  // reads the file, builds the edge table
    const Laps::Lap load = laps.lap();
    const core::EdgeTable& table = meshes.edges();
    const size_t faces = meshes.at(first).triangles.size();

    std::optional<core::SilhouetteTracker> tracker;
    std::optional<core::RaycastOcclusion> occlusion;
    core::StrokeCoherence coherence;
    output::DrawStyle style;
    style.color = output::hex_color(scene.brush.color);
    style.opacity = scene.brush.opacity;
    std::map<std::string, std::vector<double>> wall, cpu;
    std::map<std::string, Laps::Lap> first_frame;
    Laps::Lap tree{0, 0}, bvh{0, 0};
    size_t strokes = 0, frames_done = 0;

    for (int pass = 0; pass <= repeat; ++pass) {
        for (int frame = first; frame <= last; ++frame) {
            laps.lap();
            const core::Mesh& mesh = meshes.at(frame);
            core::FrameLines lines;
            lines.frame = frame;
            lines.image = scene.image;
            lines.light = scene.light;
            const glm::dmat4 world_from_object = core::world_from_object_at(scene, frame);
            lines.camera =
                core::camera_at(scene, frame, core::transformed(core::bounds_of(mesh.positions), world_from_object));
            const core::Projection projection(lines.camera, scene.image, world_from_object);
            std::map<std::string, Laps::Lap> stage;

            if (!tracker) {
                laps.lap();
                tracker.emplace(table, mesh, core::TrackerOptions{.deforming = meshes.is_sequence()});
                tree = laps.lap();
            } else if (pass == 0 && frame != first) {
                laps.lap();
            }
            const core::FeatureEdges features = tracker->update(mesh, projection.eye_object(), scene.lines);
            stage["extract"] = laps.lap();
            const std::vector<core::Chain> chains = core::chain_feature_edges(features, table);
            stage["chain"] = laps.lap();
            if (!occlusion) {
                occlusion.emplace(mesh, table);
                bvh = laps.lap();
            } else if (meshes.is_sequence() && frame != first) {
                occlusion->update_positions(mesh);
            }
            lines.strokes =
                core::split_by_visibility(chains, mesh, projection, *occlusion, {.keep_hidden = scene.lines.hidden});
            stage["visibility"] = laps.lap();
            core::tally_visible_length(lines);
            const core::FrameStrokes drawn =
                core::build_strokes(lines, mesh, table, projection, scene.brush, coherence);
            stage["strokes"] = laps.lap();
            const output::Drawing drawing = output::brush_drawing(lines, drawn, style, false);
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04d.svg", frame);
            output::write_file_atomically(svg_dir / name, output::svg_document(drawing, {}));
            stage["svg"] = laps.lap();
            strokes += drawn.strokes.size();
            ++frames_done;

            if (pass == 0 && frame == first) {
                first_frame = stage;
                continue;
            }
            for (const auto& [key, lap] : stage) {
                wall[key].push_back(lap.wall_ms);
                cpu[key].push_back(lap.cpu_ms);
            }
        }
    }

    double total_wall = 0.0, total_cpu = 0.0;
    std::printf("%s: %zu faces, %zu edges; frames %d..%d, %zu rendered, %zu strokes; peak RSS %.0f MB\n\n",
                scene_path.string().c_str(), faces, table.edge_count(), first, last, frames_done, strokes,
                peak_rss_mb());
    std::printf("| stage | ms/frame wall (median) | ms/frame CPU (median) | frame %d wall | frame %d CPU |\n", first,
                first);
    std::printf("|---|---:|---:|---:|---:|\n");
    for (const char* key : kStages) {
        const double w = median(wall[key]), c = median(cpu[key]);
        total_wall += w;
        total_cpu += c;
        std::printf("| %s | %.2f | %.2f | %.1f | %.1f |\n", key, w, c, first_frame[key].wall_ms,
                    first_frame[key].cpu_ms);
    }
    std::printf("| **per frame** | **%.2f** | **%.2f** | | |\n\n", total_wall, total_cpu);
    std::printf("| one-time | wall ms | CPU ms |\n|---|---:|---:|\n");
    std::printf("| mesh file + edge table | %.0f | %.0f |\n", load.wall_ms, load.cpu_ms);
    std::printf("| cone tree (tracker) | %.0f | %.0f |\n", tree.wall_ms, tree.cpu_ms);
    std::printf("| BVH (Embree) | %.0f | %.0f |\n", bvh.wall_ms, bvh.cpu_ms);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_pipeline_bench: %s\n", e.what());
        return 1;
    }
}
