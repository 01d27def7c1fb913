// SPDX-License-Identifier: MIT
// GL depth-map visibility vs exact ray casting (CGAL AABB tree) on generated meshes of 5k to 1M
// faces and on mesh files given on the command line: time per frame of a 1024x1024 turntable,
// and how closely the depth pass agrees with the exact reference. Prints a markdown table.
// Times the visibility stage alone on purpose: it calls split_by_visibility with each occlusion
// test directly, not core::FramePipeline (inkline_pipeline_bench times the whole pipeline).
//
//   inkline_visibility_bench [--frames N] [--size PX] [--min-faces N] [--max-faces N]
//                            [--gl auto|egl|osmesa]
//                            [--supersampling 1,2,4] [--ray-test on|off|both] [MESH ...]
//
// Real meshes, e.g. from Debian's libcgal-demo:
//   tar xzf /usr/share/doc/libcgal-dev/data.tar.gz data/meshes/armadillo.off

#include "core/lines/chaining.h"
#include "core/lines/features.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"
#include "core/scene/scene.h"
#include "core/visibility/exact_visibility.h"
#include "core/visibility/visibility.h"
#include "gl/context.h"
#include "gl/depth_visibility.h"
#include "tests/support/agreement.h"
#include "tests/support/shapes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace core = inkline::core;
namespace gl = inkline::gl;
namespace test = inkline::test;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// A unit sphere pushed out by Gaussian bumps at `count` points and jittered radially by up to
// `rough`: bumps hide parts of each other's silhouettes, jitter adds short silhouette loops.
core::Mesh bumpy_sphere(int levels, int count, double rough, uint32_t seed) {
    return test::bumpy_sphere(test::icosphere(levels), {.count = count,
                                                        .seed = seed,
                                                        .height_min = 0.05,
                                                        .height_max = 0.2,
                                                        .width_min = 0.1,
                                                        .width_max = 0.3,
                                                        .jitter = rough});
}

// Torus around y with a tube radius modulated by waves.
core::Mesh noisy_torus(int major_segments, int minor_segments) {
    return test::wavy_torus(major_segments, minor_segments, 0.15, 0.06);
}

struct Case {
    std::string name;
    size_t faces;  // known before generating, for --max-faces
    std::function<core::Mesh()> make;
};

struct Config {
    int supersampling;
    bool ray_test;
};

struct Row {
    std::string name;
    size_t faces = 0;
    Config config{};
    int frames = 0;
    double exact_build_ms = 0.0;  // AABB tree, once per mesh
    double exact_ms = 0.0;        // split_by_visibility with ExactOcclusion, per frame
    double pass_ms = 0.0;         // depth pass: render + read back, per frame
    double test_ms = 0.0;         // split_by_visibility with DepthOcclusion, per frame
    test::VisibilityAgreement lines;   // split outputs compared: what a user sees
    test::VisibilityAgreement direct;  // both occlusion tests asked on the same fine samples
    double worst_lines = 1.0;          // lowest per-frame agreement of the split outputs
    double worst_direct = 1.0;         // lowest per-frame agreement of the tests
};

struct Args {
    int frames = 8;
    int size = 1024;
    size_t min_faces = 0;
    size_t max_faces = 1100000;
    std::string backend = "auto";
    std::vector<int> supersampling{gl::DepthVisibilityOptions{}.supersampling};
    std::vector<bool> ray_test{true};
    std::vector<std::string> meshes;
};

std::vector<int> parse_list(const std::string& text) {
    std::vector<int> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) out.push_back(std::stoi(item));
    return out;
}

Args parse_args(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", arg.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (arg == "--frames") {
            a.frames = std::stoi(value());
        } else if (arg == "--size") {
            a.size = std::stoi(value());
        } else if (arg == "--min-faces") {
            a.min_faces = std::stoul(value());
        } else if (arg == "--max-faces") {
            a.max_faces = std::stoul(value());
        } else if (arg == "--gl") {
            a.backend = value();
        } else if (arg == "--supersampling") {
            a.supersampling = parse_list(value());
        } else if (arg == "--ray-test") {
            const std::string v = value();
            a.ray_test = v == "both" ? std::vector<bool>{true, false} : std::vector<bool>{v == "on"};
        } else if (!arg.empty() && arg[0] == '-') {
            std::fprintf(stderr, "unknown option %s\n", arg.c_str());
            std::exit(2);
        } else {
            a.meshes.push_back(arg);
        }
    }
    return a;
}

// One frame of a turntable around a mesh, as `inkline render mesh` frames it: the camera orbits.
struct TurntableFrame {
    core::Projection projection;
    std::vector<core::Chain> chains;
};

std::vector<TurntableFrame> turntable(const core::Mesh& mesh, const core::EdgeTable& table, int frames, int size) {
    const core::Bounds bounds = core::bounds_of(mesh.positions);
    core::Scene scene = core::default_turntable_scene("bench", bounds);
    scene.first_frame = 0;
    scene.last_frame = frames - 1;
    scene.image = {size, size};
    std::vector<TurntableFrame> out;
    for (int frame = 0; frame < frames; ++frame) {
        const core::Camera camera = core::camera_at(scene, frame, bounds);
        const core::Projection projection(camera, scene.image, glm::dmat4(1.0));
        const core::FeatureEdges features =
            core::extract_feature_edges(mesh, table, projection.eye_object(), scene.lines);
        out.push_back({projection, core::chain_feature_edges(features, table)});
    }
    return out;
}

std::vector<Row> run(const std::string& name, const core::Mesh& mesh, const Args& args, const gl::Context& context) {
    const core::EdgeTable table = core::build_edge_table(mesh);
    const std::vector<TurntableFrame> frames = turntable(mesh, table, args.frames, args.size);
    core::VisibilityOptions options;

    // Exact reference: the tree is built once; rigid turntables reuse it.
    auto start = Clock::now();
    const core::ExactOcclusion exact(mesh, table);
    const double build_ms = ms_since(start);
    std::vector<std::vector<core::Polyline>> reference;
    double exact_ms = 0.0;
    for (const TurntableFrame& f : frames) {
        start = Clock::now();
        reference.push_back(core::split_by_visibility(f.chains, mesh, f.projection, exact, options));
        exact_ms += ms_since(start);
    }

    std::vector<Row> rows;
    for (int ss : args.supersampling) {
        for (bool ray_test : args.ray_test) {
            Row row;
            row.name = name;
            row.faces = mesh.triangles.size();
            row.config = {ss, ray_test};
            row.frames = int(frames.size());
            row.exact_build_ms = build_ms;
            row.exact_ms = exact_ms / double(frames.size());
            gl::DepthOcclusion depth(context, {.supersampling = ss, .local_ray_test = ray_test});
            // Warm-up: uploads the mesh and compiles the pipeline, as the first frame of a run would.
            depth.prepare(mesh, table, frames[0].projection, core::MeshChange::kTopology);
            for (size_t i = 0; i < frames.size(); ++i) {
                const TurntableFrame& f = frames[i];
                start = Clock::now();
                depth.prepare(mesh, table, f.projection, core::MeshChange::kNone);
                row.pass_ms += ms_since(start);
                start = Clock::now();
                const std::vector<core::Polyline> lines = core::split_by_visibility(f.chains, mesh, f.projection, depth, options);
                row.test_ms += ms_since(start);
                const test::VisibilityAgreement frame_lines =
                    test::compare_visibility(f.chains, mesh, f.projection, reference[i], lines);
                const test::VisibilityAgreement frame_direct = test::compare_occlusion(f.chains, mesh, f.projection, exact, depth);
                row.lines.add(frame_lines);
                row.direct.add(frame_direct);
                row.worst_lines = std::min(row.worst_lines, frame_lines.agreement());
                row.worst_direct = std::min(row.worst_direct, frame_direct.agreement());
            }
            row.pass_ms /= double(frames.size());
            row.test_ms /= double(frames.size());
            rows.push_back(row);
            std::fprintf(stderr, "  %s ss %d ray test %s: %.1f + %.1f ms/frame (exact %.1f), lines %.3f%% / %.2f px, test %.3f%% / %.2f px\n",
                         name.c_str(), ss, ray_test ? "on" : "off", row.pass_ms, row.test_ms, row.exact_ms,
                         100.0 * row.lines.agreement(), row.lines.longest_disagreement_px,
                         100.0 * row.direct.agreement(), row.direct.longest_disagreement_px);
        }
    }
    return rows;
}

}  // namespace

int main(int argc, char** argv) {
    const Args args = parse_args(argc, argv);
    std::unique_ptr<gl::Context> context;
    try {
        context = gl::create_context(gl::parse_backend(args.backend));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_visibility_bench: %s\n", e.what());
        return 1;
    }

    std::vector<Case> cases = {
        {"bumpy sphere", 5120, [] { return bumpy_sphere(4, 40, 0.0, 1); }},
        {"noisy torus", 5000, [] { return noisy_torus(100, 25); }},
        {"bumpy sphere", 81920, [] { return bumpy_sphere(6, 120, 0.002, 2); }},
        {"noisy torus", 100000, [] { return noisy_torus(400, 125); }},
        {"bumpy sphere", 327680, [] { return bumpy_sphere(7, 300, 0.001, 3); }},
        {"noisy torus", 1000000, [] { return noisy_torus(1000, 500); }},
    };
    std::vector<Row> rows;
    for (const Case& c : cases) {
        if (c.faces > args.max_faces || c.faces < args.min_faces) continue;
        std::fprintf(stderr, "%s, %zu faces\n", c.name.c_str(), c.faces);
        for (Row& r : run(c.name, c.make(), args, *context)) rows.push_back(r);
    }
    for (const std::string& path : args.meshes) {
        std::fprintf(stderr, "%s\n", path.c_str());
        try {
            const core::Mesh mesh = core::load_mesh(path).mesh;
            for (Row& r : run(std::filesystem::path(path).stem().string(), mesh, args, *context)) rows.push_back(r);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "  skipped: %s\n", e.what());
        }
    }

    std::printf("GL: %s, %s (%s); %d frames of a %dx%d turntable per mesh\n\n", context->backend_name(),
                context->renderer().c_str(), context->version().c_str(), args.frames, args.size, args.size);
    std::printf("| mesh | faces | ss | ray test | exact ms/frame | depth pass ms | depth test ms | gl ms/frame | speed-up "
                "| lines agree %% (worst frame) | longest run px | test agree %% (worst frame) | test longest px |\n");
    std::printf("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Row& r : rows) {
        const double gl_ms = r.pass_ms + r.test_ms;
        std::printf("| %s | %zu | %d | %s | %.1f | %.1f | %.1f | %.1f | %.2fx | %.3f (%.3f) | %.2f | %.3f (%.3f) | %.2f |\n",
                    r.name.c_str(), r.faces, r.config.supersampling, r.config.ray_test ? "on" : "off", r.exact_ms,
                    r.pass_ms, r.test_ms, gl_ms, r.exact_ms / gl_ms, 100.0 * r.lines.agreement(), 100.0 * r.worst_lines,
                    r.lines.longest_disagreement_px, 100.0 * r.direct.agreement(), 100.0 * r.worst_direct,
                    r.direct.longest_disagreement_px);
    }
    std::printf("\nExact: AABB tree built once per mesh, not in ms/frame:");
    for (size_t i = 0; i < rows.size(); ++i) {
        if (i > 0 && rows[i].name == rows[i - 1].name && rows[i].faces == rows[i - 1].faces) continue;
        std::printf(" %s (%zu) %.0f ms;", rows[i].name.c_str(), rows[i].faces, rows[i].exact_build_ms);
    }
    std::printf("\n");
    return 0;
}
