// SPDX-License-Identifier: MIT
// Worst-case shapes at four sizes, doubling: how each stage's time grows with the size. A
// near-linear stage doubles (ratio about 2, a little more for n log n); a quadratic one
// quadruples.
//
//   inkline_worst_case_bench [--case fan|polygon|terrain|shared-edge|frames] [--scale K]
//
// Cases (the default runs all five):
//   fan      a closed cone: apex and base centre each in half of the faces (CAD caps and fans)
//   polygon  one polygon of N corners, fan-triangulated as the OBJ reader does (every triangle
//            has the first corner)
//   terrain  an n x n heightfield of random heights: tens of thousands of short strokes, joined
//            again from frame 2 on (noisy scans, terrain)
//   shared-edge  N triangles on one edge, each to a point of a circle around it (a broken CAD
//            export): thousands of strokes cross the image of the edge's two ends, where frame 2
//            finds last frame's strokes crowded within a few pixels
//   frames   a small torus over 20000 frames: per-frame time and memory must stay flat
// The first four render two frames of the default turntable (1024 x 1024, ray-cast visibility)
// through the CLI's own core::FramePipeline and report the one-time builds and frame 2's stages;
// --scale K divides every size by K (a quick run). CPU time of the whole process (all threads),
// ms.

#include <sys/resource.h>
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/mesh_frames.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/visibility/occlusion_source.h"
#include "tests/support/shapes.h"

namespace {

namespace core = inkline::core;
namespace test = inkline::test;

double cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

double peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

// Current resident memory (MB), from /proc.
double rss_mb() {
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0.0;
    long pages = 0, resident = 0;
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
    return double(resident) * 4096.0 / (1024.0 * 1024.0);
}

// N triangles that all share the edge from (0, 0, -1) to (0, 0, 1), each to one of N points
// of the unit circle in z = 0: an edge of N faces.
core::Mesh shared_edge(uint32_t faces) {
    core::Mesh m;
    m.positions = {{0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}};
    for (uint32_t i = 0; i < faces; ++i) {
        const double a = 2.0 * std::numbers::pi * double(i) / faces;
        m.positions.push_back({float(std::cos(a)), float(std::sin(a)), 0.0f});
        m.triangles.push_back({0, 1, 2 + i});
    }
    return m;
}

const char* const kStages[] = {"edge table", "describe", "cone tree", "BVH", "extract", "chain", "visibility", "strokes"};

struct Row {
    std::string size;
    size_t faces = 0, strokes = 0;
    std::map<std::string, double> ms;
    double total = 0.0;
};

// Renders frames 1 and 2 of the default turntable of `mesh` as the CLI does; one-time builds and
// frame 2's stages in CPU ms.
Row render_two_frames(core::Mesh mesh, const std::string& size) {
    Row row;
    row.size = size;
    row.faces = mesh.triangles.size();
    double t = cpu_ms();
    auto lap = [&](const char* stage) {
        const double now = cpu_ms();
        row.ms[stage] += now - t;
        t = now;
    };
    // The edge table and the mesh checks on their own (MeshFrames repeats both, untimed).
    {
        const core::EdgeTable table = core::build_edge_table(mesh);
        lap("edge table");
        const core::MeshReport report = core::describe_mesh(mesh, table);
        lap("describe");
        if (report.faces == 0) std::abort();
    }
    const core::Scene scene = core::default_turntable_scene("bench.obj", core::bounds_of(mesh.positions));
    core::MeshFrames meshes(std::move(mesh));
    int frame = 1;
    // The pipeline's steps as the table's stages: its first occlusion step builds the BVH.
    const auto step_done = [&](const char* step) {
        const std::string name = step;
        if (name == "load") {
            t = cpu_ms();
        } else if (name == "tracker build") {
            lap("cone tree");
        } else if (name == "occlusion") {
            lap(frame == 1 ? "BVH" : "visibility");
        } else {
            lap(step);
        }
    };
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast),
                                 {.step_done = step_done});
    for (; frame <= 2; ++frame) {
        if (frame == 2) row.ms.erase("extract"), row.ms.erase("chain"), row.ms.erase("visibility"), row.ms.erase("strokes");
        row.strokes = pipeline.run(frame).strokes.strokes.size();
    }
    for (const auto& [stage, ms] : row.ms) row.total += ms;
    return row;
}

void print_table(const std::string& title, const std::vector<Row>& rows) {
    std::printf("\n### %s\n\n| size | faces | strokes |", title.c_str());
    for (const char* s : kStages) std::printf(" %s |", s);
    std::printf(" total |\n|---|---:|---:|");
    for (size_t i = 0; i <= std::size(kStages); ++i) std::printf("---:|");
    std::printf("\n");
    for (size_t r = 0; r < rows.size(); ++r) {
        std::printf("| %s | %zu | %zu |", rows[r].size.c_str(), rows[r].faces, rows[r].strokes);
        for (const char* s : kStages) {
            const auto it = rows[r].ms.find(s);
            std::printf(" %.0f |", it == rows[r].ms.end() ? 0.0 : it->second);
        }
        std::printf(" %.0f |\n", rows[r].total);
    }
    // Growth per doubling of the size: each stage's time over the previous size's.
    for (size_t r = 1; r < rows.size(); ++r) {
        std::printf("| x%zu/x%zu | | |", size_t(1) << r, size_t(1) << (r - 1));
        for (const char* s : kStages) {
            const auto a = rows[r - 1].ms.find(s), b = rows[r].ms.find(s);
            if (a == rows[r - 1].ms.end() || b == rows[r].ms.end() || a->second < 5.0) {
                std::printf(" - |");
            } else {
                std::printf(" %.2f |", b->second / a->second);
            }
        }
        std::printf(" %.2f |\n", rows[r].total / rows[r - 1].total);
    }
    std::fflush(stdout);
}

// A small torus over 20000 frames (one turn): mean CPU ms per frame in each quarter of the run,
// and the resident memory at the end of each (stroke coherence must not grow with the frames).
void long_run(int scale) {
    const int frames = 20000 / scale;
    core::MeshFrames meshes(test::torus(1.0, 0.35, 48, 16));
    core::Scene scene = core::default_turntable_scene("bench.obj", core::bounds_of(meshes.at(1).positions));
    scene.last_frame = frames;
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast));
    std::printf("\n### frames: a %zu-face torus, %d frames (one turn)\n\n", meshes.at(1).triangles.size(), frames);
    std::printf("| frames | ms/frame | RSS at end (MB) |\n|---|---:|---:|\n");
    double sum = 0.0;
    for (int frame = 1; frame <= frames; ++frame) {
        const double t = cpu_ms();
        if (pipeline.run(frame).strokes.strokes.empty()) std::abort();
        sum += cpu_ms() - t;
        if (frame % (frames / 4) == 0) {
            std::printf("| %d..%d | %.2f | %.1f |\n", frame - frames / 4 + 1, frame, sum / (frames / 4), rss_mb());
            std::fflush(stdout);
            sum = 0.0;
        }
    }
}

int run(int argc, char** argv) {
    std::string only;
    int scale = 1;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string arg = argv[i];
        if (arg == "--case") {
            only = argv[i + 1];
        } else if (arg == "--scale") {
            scale = std::max(1, std::atoi(argv[i + 1]));
        } else {
            std::fprintf(stderr,
                         "usage: inkline_worst_case_bench [--case fan|polygon|terrain|shared-edge|frames] [--scale K]\n");
            return 2;
        }
    }
    std::printf("CPU ms (all threads); frame 2's stages, one-time builds apart\n");
    auto sizes = [&](uint32_t first) {
        std::vector<uint32_t> out;
        for (int k = 0; k < 4; ++k) out.push_back((first << k) / uint32_t(scale));
        return out;
    };
    if (only.empty() || only == "fan") {
        std::vector<Row> rows;
        for (uint32_t sides : sizes(18750)) rows.push_back(render_two_frames(test::closed_cone(sides), std::to_string(sides) + " sides"));
        print_table("fan: closed cone, apex and base centre each in half of the faces", rows);
    }
    if (only.empty() || only == "polygon") {
        std::vector<Row> rows;
        for (uint32_t corners : sizes(125000)) rows.push_back(render_two_frames(test::fan_polygon(corners), std::to_string(corners) + " corners"));
        print_table("polygon: one face of N corners, fan-triangulated", rows);
    }
    if (only.empty() || only == "terrain") {
        std::vector<Row> rows;
        // Side n grows by sqrt 2 a step: faces (and strokes) double.
        for (int k = 0; k < 4; ++k) {
            const auto n = uint32_t(std::lround(141.0 * std::pow(std::sqrt(2.0), k) / std::sqrt(double(scale))));
            rows.push_back(render_two_frames(test::noise_terrain(n, 0.15), std::to_string(n) + "^2 grid"));
        }
        print_table("terrain: random heightfield", rows);
    }
    if (only.empty() || only == "shared-edge") {
        std::vector<Row> rows;
        for (uint32_t faces : sizes(500)) rows.push_back(render_two_frames(shared_edge(faces), std::to_string(faces) + " faces"));
        print_table("shared-edge: N faces on one edge", rows);
    }
    if (only.empty() || only == "frames") long_run(scale);
    std::printf("\npeak RSS %.0f MB\n", peak_rss_mb());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_worst_case_bench: %s\n", e.what());
        return 1;
    }
}
