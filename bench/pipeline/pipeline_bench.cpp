// SPDX-License-Identifier: MIT
// Where a scene's render time goes: every stage of `inkline render --visibility raycast --svg`
// for each frame, drawn by the CLI's own core::FramePipeline (incremental tracker, chaining,
// ray-cast visibility with the occluded parts that gap bridging needs, brush strokes) and its
// SVG built and written as the CLI's writers do, in wall-clock and whole-process CPU time, plus
// the one-time costs (mesh file, edge table, cone tree, BVH) and the peak memory.
//
//   inkline_pipeline_bench SCENE.json [--frames A:B] [--svg DIR] [--repeat N]
//
// Prints a markdown table: per stage, the median over frames 2.. (frame 1 pays the one-time
// builds, listed apart; "load" is the mesh file of a sequence's frame). CPU time is summed over
// threads, so on a shared machine it measures this work alone where wall time also measures the
// neighbours. --repeat draws the frames N times over (after the first pass, on the same
// pipeline) for steadier medians.

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

#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/visibility/occlusion_source.h"
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
        double wall_ms = 0.0, cpu_ms = 0.0;
        Lap operator+(const Lap& o) const { return {wall_ms + o.wall_ms, cpu_ms + o.cpu_ms}; }
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

const char* const kStages[] = {"load", "extract", "chain", "visibility", "strokes", "svg"};

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

    output::DrawStyle style;
    style.color = output::hex_color(scene.brush.color);
    style.opacity = scene.brush.opacity;
    std::map<std::string, std::vector<double>> wall, cpu;
    std::map<std::string, Laps::Lap> first_frame;
    Laps::Lap tree, bvh;
    size_t strokes = 0, frames_done = 0;

    // Each step of a frame, lapped as the pipeline ends it.
    std::map<std::string, Laps::Lap> stage;
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast),
                                 {.frame_count = last - first + 1,
                                  .step_done = [&](const char* step) { stage[step] = laps.lap(); }});
    for (int pass = 0; pass <= repeat; ++pass) {
        for (int frame = first; frame <= last; ++frame) {
            stage.clear();
            laps.lap();
            const core::FrameResult drawn = pipeline.run(frame);
            const output::Drawing drawing = output::brush_drawing(drawn.lines, drawn.strokes, style, false);
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04d.svg", frame);
            output::write_file_atomically(svg_dir / name, output::svg_document(drawing, {}));
            stage["svg"] = laps.lap();
            strokes += drawn.strokes.strokes.size();
            ++frames_done;

            // The first frame builds the cone tree and the BVH (listed apart); later frames'
            // occlusion step (a refit for a sequence) is part of their visibility.
            if (pass == 0 && frame == first) {
                tree = stage["tracker build"];
                bvh = stage["occlusion"];
            } else {
                stage["visibility"] = stage["occlusion"] + stage["visibility"];
            }
            stage.erase("tracker build");
            stage.erase("occlusion");
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
