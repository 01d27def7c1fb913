// SPDX-License-Identifier: MIT
// Per-frame visibility cost of ray casting (Embree) vs the exact CGAL reference on generated
// meshes of 10k to 1M+ faces at 1024x1024: a rigid turntable (trees built once, the eye moves in
// object space) and a deforming variant (exact rebuilds its tree every frame, raycast refits).
// Mesh files given on the command line join the generated ones, moved to centre on the origin.
// Prints a markdown table. Times the visibility stage alone on purpose: it calls
// split_by_visibility with each occlusion test directly, not core::FramePipeline
// (inkline_pipeline_bench times the whole pipeline).
//
//   inkline_raycast_bench [--max-faces N] [--frames N] [--size PX] [MESH ...]
//
// Real meshes, e.g. from Debian's libcgal-dev:
//   tar xzf /usr/share/doc/libcgal-dev/data.tar.gz data/meshes/armadillo.off

#include "core/lines/chaining.h"
#include "core/lines/features.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"
#include "core/scene/scene.h"
#include "core/visibility/exact_visibility.h"
#include "core/visibility/raycast_visibility.h"
#include "core/visibility/visibility.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include <time.h>

namespace {

namespace core = inkline::core;
namespace test = inkline::test;
constexpr double kPi = std::numbers::pi;

// Wall-clock and whole-process CPU time, ms. The machines these run on are shared: wall time
// there measures the neighbours too, CPU time (summed over threads) only this work.
struct Timer {
    std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
    double cpu = process_cpu_ms();

    static double process_cpu_ms() {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
    }
    double wall_ms() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall).count();
    }
    double cpu_ms() const { return process_cpu_ms() - cpu; }
};

// Smooth bumps of about `amplitude` on a surface point with direction d (a cheap stand-in for
// scanned detail: it makes silhouettes break into many short pieces, as on real meshes).
double bumps(const glm::dvec3& d, double amplitude) {
    return amplitude * (0.6 * std::sin(23.0 * d.x + 3.0 * d.y) * std::sin(19.0 * d.y - 5.0 * d.z) +
                        0.4 * std::sin(41.0 * d.z + 7.0 * d.x) * std::cos(37.0 * d.x - 11.0 * d.y));
}

// Bumpy torus around y, major radius 1, tube 0.4: 2 * major * minor faces.
core::Mesh bumpy_torus(int major, int minor) {
    core::Mesh m;
    for (int i = 0; i < major; ++i) {
        const double u = 2.0 * kPi * i / major;
        for (int j = 0; j < minor; ++j) {
            const double v = 2.0 * kPi * j / minor;
            const glm::dvec3 n(std::cos(v) * std::cos(u), std::sin(v), -std::cos(v) * std::sin(u));
            const double r = 0.4 + bumps(n + glm::dvec3(std::cos(u), 0.0, -std::sin(u)), 0.03);
            const glm::dvec3 p = glm::dvec3(std::cos(u), 0.0, -std::sin(u)) + r * n;
            m.positions.emplace_back(p);
        }
    }
    auto at = [&](int i, int j) { return unsigned((i % major) * minor + (j % minor)); };
    for (int i = 0; i < major; ++i) {
        for (int j = 0; j < minor; ++j) {
            m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return m;
}

// Bumpy unit icosphere (20 * 4^levels faces).
core::Mesh bumpy_icosphere(int levels) {
    core::Mesh m = test::icosphere(levels);
    for (glm::vec3& p : m.positions) {
        const glm::dvec3 d(p);
        p = glm::vec3(d * (1.0 + bumps(d, 0.04)));
    }
    return m;
}

// The deforming variant at a phase: a travelling radial wave, up to 6% of the size (the mesh
// centred on the origin).
core::Mesh wobbled(const core::Mesh& base, double phase) {
    core::Mesh m = base;
    const double radius = core::bounds_of(base.positions).radius();
    for (glm::vec3& p : m.positions) {
        const double angle = std::atan2(double(p.z), double(p.x));
        p *= float(1.0 + 0.06 * std::sin(3.0 * angle + 2.0 * double(p.y) / radius + phase));
    }
    return m;
}

// Counts what split_by_visibility asks of an occlusion test.
class CountingOcclusion final : public core::Occlusion {
  public:
    explicit CountingOcclusion(const core::Occlusion& inner) : inner_(inner) {}
    void occluded(const core::Viewpoint& eye_object, std::span<const core::OcclusionQuery> queries,
                  std::span<uint8_t> r_occluded) const override {
        // split_by_visibility tests the coarse samples in one call, then one point per call.
        (queries.size() > 1 ? coarse_ : bisection_) += queries.size();
        inner_.occluded(eye_object, queries, r_occluded);
    }
    size_t coarse() const { return coarse_; }
    size_t bisection() const { return bisection_; }

  private:
    const core::Occlusion& inner_;
    mutable size_t coarse_ = 0;
    mutable size_t bisection_ = 0;
};

struct Shape {
    std::string name;
    core::Mesh mesh;
};

struct Measure {
    double setup_ms = 0.0;                // first tree build (wall)
    std::vector<double> wall_ms, cpu_ms;  // per frame: update or rebuild + split_by_visibility
    std::vector<double> update_ms;        // per deforming frame: the refit or rebuild alone (wall)
    std::vector<double> lines_ms;         // per frame: extraction and chaining (wall)
    double visible_px = 0.0;              // summed over frames
    size_t coarse = 0, bisection = 0;     // queries, summed over frames
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

double visible_length(const std::vector<core::Polyline>& lines) {
    double len = 0.0;
    for (const core::Polyline& line : lines) len += line.visible ? line.length_px() : 0.0;
    return len;
}

struct Frame {
    core::Mesh mesh;
    glm::dmat4 world_from_object;
};

// One run of a motion with one kind of occlusion test. `make` builds a tree; `update` returns
// false when the kind cannot follow a deformation in place (then it is rebuilt).
Measure run(const std::vector<Frame>& frames, const core::EdgeTable& table, bool deforming, int size,
            const std::function<std::unique_ptr<core::Occlusion>(const core::Mesh&)>& make,
            const std::function<bool(core::Occlusion&, const core::Mesh&)>& update) {
    Measure out;
    const Timer setup;
    std::unique_ptr<core::Occlusion> occlusion = make(frames.front().mesh);
    out.setup_ms = setup.wall_ms();
    core::LineOptions lines;
    for (size_t f = 0; f < frames.size(); ++f) {
        const core::Mesh& mesh = frames[f].mesh;
        const core::Bounds b = core::bounds_of(mesh.positions);
        const double radius = b.radius();
        core::Camera camera;
        camera.eye = glm::dvec3(0.0, 0.9, 3.2) * radius;
        camera.fov_y_deg = 40.0;
        camera.near = 0.5 * radius;
        camera.far = 10.0 * radius;
        const core::Projection projection(camera, {size, size}, frames[f].world_from_object);
        const Timer lines_timer;
        const core::FeatureEdges features =
            core::extract_feature_edges(mesh, table, projection.eye_object(), lines);
        const std::vector<core::Chain> chains = core::chain_feature_edges(features, table);

        out.lines_ms.push_back(lines_timer.wall_ms());

        const Timer frame;
        if (deforming) {
            if (!update(*occlusion, mesh)) occlusion = make(mesh);
            out.update_ms.push_back(frame.wall_ms());
        }
        const CountingOcclusion counted(*occlusion);
        const std::vector<core::Polyline> strokes = core::split_by_visibility(chains, mesh, projection, counted, {});
        out.wall_ms.push_back(frame.wall_ms());
        out.cpu_ms.push_back(frame.cpu_ms());
        out.visible_px += visible_length(strokes);
        out.coarse += counted.coarse();
        out.bisection += counted.bisection();
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    size_t max_faces = 1'400'000;
    int frame_count = 4;
    int size = 1024;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool has_value = i + 1 < argc;
        if (arg == "--max-faces" && has_value) {
            max_faces = size_t(std::atol(argv[++i]));
        } else if (arg == "--frames" && has_value) {
            frame_count = std::max(2, std::atoi(argv[++i]));
        } else if (arg == "--size" && has_value) {
            size = std::atoi(argv[++i]);
        } else if (arg.starts_with("-")) {
            std::fprintf(stderr, "usage: %s [--max-faces N] [--frames N] [--size PX] [MESH ...]\n", argv[0]);
            return 2;
        } else {
            files.push_back(arg);
        }
    }
    if (!core::raycast_available()) {
        std::fprintf(stderr, "inkline_raycast_bench: this build has no Embree\n");
        return 1;
    }

    std::vector<Shape> shapes;
    for (auto [major, minor] : {std::pair{100, 50}, std::pair{316, 158}, std::pair{1000, 500}}) {
        if (size_t(2 * major * minor) <= max_faces) shapes.push_back({"bumpy torus", bumpy_torus(major, minor)});
    }
    for (int levels : {5, 7, 8}) {
        if ((size_t(20) << (2 * levels)) <= max_faces) shapes.push_back({"bumpy icosphere", bumpy_icosphere(levels)});
    }
    for (const std::string& file : files) {
        try {
            core::Mesh mesh = core::load_mesh(file).mesh;
            const glm::vec3 center(core::bounds_of(mesh.positions).center());
            for (glm::vec3& p : mesh.positions) p -= center;
            shapes.push_back({std::filesystem::path(file).filename().string(), std::move(mesh)});
        } catch (const std::exception& e) {
            std::fprintf(stderr, "inkline_raycast_bench: %s\n", e.what());
            return 2;
        }
    }

    std::printf("%d frames per motion at %dx%d, %u hardware threads. Per frame: visibility of the\n", frame_count,
                size, size, std::thread::hardware_concurrency());
    std::printf("extracted chains (split_by_visibility), plus the tree rebuild (exact) or refit (raycast)\n");
    std::printf("when deforming. Median over frames; wall ms / CPU ms summed over threads.\n\n");
    std::printf("| mesh | faces | motion | lines ms | queries/frame coarse + bisection | exact tree ms "
                "| exact ms/frame | raycast tree ms | raycast ms/frame | speed-up (wall) "
                "| visible length raycast/exact |\n");
    std::printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Shape& shape : shapes) {
        const core::EdgeTable table = core::build_edge_table(shape.mesh);
        for (bool deforming : {false, true}) {
            std::vector<Frame> frames;
            for (int f = 0; f < frame_count; ++f) {
                const double turn = 2.0 * kPi * f / frame_count;
                if (deforming) {
                    frames.push_back({wobbled(shape.mesh, turn), glm::dmat4(1.0)});
                } else {
                    const glm::dvec3 axis = glm::normalize(glm::dvec3(1.0, 0.3, 0.2));
                    frames.push_back({shape.mesh, glm::rotate(glm::dmat4(1.0), turn, axis)});
                }
            }
            const Measure exact = run(
                frames, table, deforming, size,
                [&](const core::Mesh& m) { return std::make_unique<core::ExactOcclusion>(m, table); },
                [](core::Occlusion&, const core::Mesh&) { return false; });
            const Measure raycast = run(
                frames, table, deforming, size,
                [&](const core::Mesh& m) { return std::make_unique<core::RaycastOcclusion>(m, table); },
                [](core::Occlusion& o, const core::Mesh& m) {
                    static_cast<core::RaycastOcclusion&>(o).update_positions(m);
                    return true;
                });
            // Tree: the first build; when deforming also the per-frame rebuild (exact) or refit.
            auto tree = [deforming](const Measure& m) {
                char text[64];
                if (deforming) {
                    std::snprintf(text, sizeof text, "%.0f, %.1f/frame", m.setup_ms, median(m.update_ms));
                } else {
                    std::snprintf(text, sizeof text, "%.0f", m.setup_ms);
                }
                return std::string(text);
            };
            const size_t n = frames.size();
            std::printf("| %s | %zu | %s | %.1f | %zu + %zu | %s | %.1f / %.1f | %s | %.1f / %.1f | %.1fx | %.5f |\n",
                        shape.name.c_str(), shape.mesh.triangles.size(), deforming ? "deforming" : "rigid",
                        median(raycast.lines_ms), raycast.coarse / n, raycast.bisection / n, tree(exact).c_str(),
                        median(exact.wall_ms), median(exact.cpu_ms), tree(raycast).c_str(), median(raycast.wall_ms),
                        median(raycast.cpu_ms), median(exact.wall_ms) / median(raycast.wall_ms),
                        raycast.visible_px / exact.visible_px);
            std::fflush(stdout);
        }
    }
    return 0;
}
