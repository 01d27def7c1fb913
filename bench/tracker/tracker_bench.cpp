// SPDX-License-Identifier: MIT
// Brute-force feature edges vs SilhouetteTracker on generated meshes of 5k to 1.3M faces, side by
// side in one run: a 120-frame turntable at 3 degrees a frame. Prints a markdown table; with
// --csv FILE also every frame's fraction of edges tested and extraction times. Times the
// extraction stage alone on purpose: it calls extract_feature_edges and SilhouetteTracker
// directly, not core::FramePipeline (inkline_pipeline_bench times the whole pipeline).
//
//   inkline_tracker_bench [--max-faces N] [--frames N] [--csv FILE] [--only TEXT] [--mesh FILE]...
//
// --only runs the cases whose name contains TEXT; --mesh adds a mesh file (OBJ, OFF, PLY, STL),
// for example the models of Debian's libcgal-demo data.

#include "core/lines/features.h"
#include "core/lines/silhouette_tracker.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"
#include "core/scene/scene.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <time.h>

namespace {

namespace core = inkline::core;
namespace test = inkline::test;
// CPU time of this thread, ms: the machines these run on are shared, and wall-clock time there
// measures the neighbours as much as the code.
double cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

// A unit sphere pushed out by `count` Gaussian bumps of random height and width.
core::Mesh bumpy(core::Mesh m, int count, uint32_t seed) {
    return test::bumpy_sphere(std::move(m), {.count = count, .seed = seed});
}

// Random radial jitter of about a fifth of an edge: a rough surface, silhouettes everywhere.
core::Mesh rough(core::Mesh m, double amplitude, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-amplitude, amplitude);
    for (glm::vec3& p : m.positions) p *= float(1.0 + jitter(rng));
    return m;
}

// Torus around y with a tube radius modulated by waves.
core::Mesh noisy_torus(int major_segments, int minor_segments) {
    return test::wavy_torus(major_segments, minor_segments, 0.12, 0.05);
}

struct Case {
    std::string name;
    std::function<core::Mesh()> make;
    size_t faces;  // known before generating, for --max-faces
    core::LineOptions lines;
    bool deforming = false;
    core::TrackerSearch search = core::TrackerSearch::kHierarchy;
};

struct Row {
    std::string name;
    size_t faces = 0, edges = 0;
    double build_ms = 0.0;  // edge table + cone hierarchy, once per topology
    double brute_ms = 0.0, tracker_ms = 0.0, first_ms = 0.0;
    double tested = 0.0, tested_max = 0.0, faces_tested = 0.0;
    double silhouette_edges = 0.0;
    size_t proven = 0;
    int identical = 0, frames = 0;
};

bool same_edges(const core::FeatureEdges& a, const core::FeatureEdges& b) {
    return std::equal(a.edges.begin(), a.edges.end(), b.edges.begin(), b.edges.end(),
                      [](const core::FeatureEdge& x, const core::FeatureEdge& y) {
                          return x.edge == y.edge && x.kind == y.kind;
                      });
}

// The turntable's eye in object space, from the centre of the object's box: the object turns 3
// degrees a frame about y under a camera above and in front of it, like samples/torus.
glm::dvec3 turntable_eye(int frame, double radius) {
    const double a = -3.0 * frame * std::numbers::pi / 180.0;
    const glm::dvec3 eye_world(0.0, 1.2 * radius, 3.2 * radius);
    return {std::cos(a) * eye_world.x + std::sin(a) * eye_world.z, eye_world.y,
            -std::sin(a) * eye_world.x + std::cos(a) * eye_world.z};
}

// Breathing for the deforming case: radial waves travelling along y.
void breathe(const core::Mesh& rest, int frame, core::Mesh& r_mesh) {
    for (size_t v = 0; v < rest.positions.size(); ++v) {
        const glm::vec3 p = rest.positions[v];
        r_mesh.positions[v] = p * float(1.0 + 0.04 * std::sin(6.0 * p.y + 0.3 * frame));
    }
}

Row run(const Case& c, int frames, std::FILE* csv) {
    Row row;
    row.name = c.name;
    const core::Mesh rest = c.make();
    core::Mesh mesh = rest;
    const core::Bounds bounds = core::bounds_of(rest.positions);
    const double radius = bounds.radius();
    double start = cpu_ms();
    const core::EdgeTable table = core::build_edge_table(rest);
    core::SilhouetteTracker tracker(table, rest, {.deforming = c.deforming, .search = c.search});
    row.build_ms = cpu_ms() - start;
    row.faces = rest.triangles.size();
    row.edges = table.edge_count();
    for (int frame = 0; frame < frames; ++frame) {
        if (c.deforming) breathe(rest, frame, mesh);
        const glm::dvec3 eye = bounds.center() + turntable_eye(frame, radius);
        start = cpu_ms();
        const core::FeatureEdges brute = core::extract_feature_edges(mesh, table, eye, c.lines);
        const double brute_ms = cpu_ms() - start;
        start = cpu_ms();
        const core::FeatureEdges tracked = tracker.update(mesh, eye, c.lines);
        const double tracker_ms = cpu_ms() - start;
        const bool identical = same_edges(brute, tracked);
        row.identical += identical ? 1 : 0;
        const double tested = double(tracked.edges_tested) / double(row.edges);
        if (csv) {
            std::fprintf(csv, "\"%s\",%d,%.6f,%.6f,%.4f,%.4f,%zu,%d\n", c.name.c_str(), frame, tested,
                         double(tracked.faces_tested) / double(row.faces), brute_ms, tracker_ms,
                         tracker.stats().silhouette_edges, identical ? 1 : 0);
        }
        if (frame == 0) {
            row.first_ms = tracker_ms;  // the full pass
            continue;
        }
        ++row.frames;
        row.brute_ms += brute_ms;
        row.tracker_ms += tracker_ms;
        row.tested += tested;
        row.tested_max = std::max(row.tested_max, tested);
        row.faces_tested += double(tracked.faces_tested) / double(row.faces);
        row.silhouette_edges += double(tracker.stats().silhouette_edges);
        row.proven += tracker.stats().proven;
    }
    const double n = std::max(1, row.frames);
    row.brute_ms /= n;
    row.tracker_ms /= n;
    row.tested /= n;
    row.faces_tested /= n;
    row.silhouette_edges /= n;
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    size_t max_faces = 2'000'000;
    int frames = 120;
    std::FILE* csv = nullptr;
    std::string only;
    std::vector<std::filesystem::path> mesh_files;
    const char* usage = "usage: %s [--max-faces N] [--frames N] [--csv FILE] [--only TEXT] [--mesh FILE]...\n";
    if (argc % 2 == 0) {
        std::fprintf(stderr, usage, argv[0]);
        return 2;
    }
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i];
        if (key == "--max-faces") {
            max_faces = std::strtoull(argv[i + 1], nullptr, 10);
        } else if (key == "--frames") {
            frames = std::max(2, std::atoi(argv[i + 1]));
        } else if (key == "--csv") {
            csv = std::fopen(argv[i + 1], "w");
            if (!csv) {
                std::fprintf(stderr, "cannot write %s\n", argv[i + 1]);
                return 2;
            }
            std::fprintf(csv, "mesh,frame,edges_tested_fraction,faces_tested_fraction,brute_ms,tracker_ms,"
                              "silhouette_edges,identical\n");
        } else if (key == "--only") {
            only = argv[i + 1];
        } else if (key == "--mesh") {
            mesh_files.emplace_back(argv[i + 1]);
        } else {
            std::fprintf(stderr, usage, argv[0]);
            return 2;
        }
    }

    core::LineOptions silhouettes_only;
    silhouettes_only.boundary = silhouettes_only.crease = false;
    std::vector<Case> cases = {
        {"icosphere", [] { return test::icosphere(4); }, 5'120, {}},
        {"bumpy icosphere", [] { return bumpy(test::icosphere(5), 40, 1); }, 20'480, {}},
        {"noisy torus", [] { return noisy_torus(256, 128); }, 65'536, {}},
        {"rough icosphere", [] { return rough(test::icosphere(6), 0.004, 2); }, 81'920, {}},
        {"bumpy icosphere", [] { return bumpy(test::icosphere(7), 60, 3); }, 327'680, {}},
        {"bumpy icosphere, deforming", [] { return bumpy(test::icosphere(7), 60, 3); }, 327'680, {}, true},
        {"noisy torus", [] { return noisy_torus(1024, 512); }, 1'048'576, {}},
        {"bumpy icosphere", [] { return bumpy(test::icosphere(8), 60, 4); }, 1'310'720, {}},
        {"bumpy icosphere, silhouettes only", [] { return bumpy(test::icosphere(8), 60, 4); }, 1'310'720, silhouettes_only},
        {"bumpy icosphere, walk and hierarchy", [] { return bumpy(test::icosphere(8), 60, 4); }, 1'310'720, {}, false,
         core::TrackerSearch::kWalkAndHierarchy},
    };

    for (const std::filesystem::path& file : mesh_files) {
        core::Mesh mesh;
        try {
            mesh = core::load_mesh(file).mesh;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s\n", e.what());
            return 2;
        }
        const size_t faces = mesh.triangles.size();
        cases.push_back({file.filename().string(), [mesh] { return mesh; }, faces, {}});
    }

    std::printf("%d-frame turntable, 3 degrees a frame; means over frames 2..%d (frame 1 is the full pass); "
                "times are thread CPU time.\n\n",
                frames, frames);
    std::printf("| mesh | faces | edges | silhouette edges | edges tested | max | faces tested | brute ms | "
                "incremental ms | speedup | full pass ms | build ms | missed by the walk | identical |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Case& c : cases) {
        if (c.faces > max_faces || c.name.find(only) == std::string::npos) continue;
        const Row r = run(c, frames, csv);
        // Silhouette edges that only the hierarchy found, summed over frames: the walk
        // alone would have lost them.
        const std::string missed =
            c.search == core::TrackerSearch::kWalkAndHierarchy ? std::to_string(r.proven) : std::string("-");
        std::printf("| %s | %zu | %zu | %.0f | %.2f%% | %.2f%% | %.2f%% | %.2f | %.2f | %.1fx | %.1f | %.0f | %s | %d/%d |\n",
                    r.name.c_str(), r.faces, r.edges, r.silhouette_edges, 100.0 * r.tested, 100.0 * r.tested_max,
                    100.0 * r.faces_tested, r.brute_ms, r.tracker_ms, r.brute_ms / r.tracker_ms, r.first_ms,
                    r.build_ms, missed.c_str(), r.identical, frames);
        std::fflush(stdout);
    }
    if (csv) std::fclose(csv);
    return 0;
}
