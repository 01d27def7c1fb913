// SPDX-License-Identifier: MIT
// Stippled tone (issue 24) on the Stanford bunny and a sphere, measured outside core/tone:
//   coverage   ink coverage of the dots (rasterised 8 x 8 a pixel, overlaps once) against the
//              tone asked for, per band of N.L (the sphere's analytic normal; the mesh's
//              interpolated vertex normals through a z-buffer), lines off, side light;
//   turntable  the objects turning 2 degrees a frame under a fixed light, drawn as `inkline
//              render --visibility raycast` draws them (lines on): per frame the tone stage's
//              time (FrameStats::ms "tone"), the dots, the share of them drawn the frame before
//              (by surface sample) and the share an exact segment test finds hidden.
//
//   inkline_tone_bench BUNNY.off [--frames N] [--size PX] [--max T] [--sphere-levels L]
//
// BUNNY.off: data/meshes/bunny00.off of Debian's libcgal-demo (bench/tone/README.md). The
// sphere is an icosphere (default 6 levels: 81920 faces, near the bunny's 75408). Times are
// wall clock; the tone stage includes its occlusion queries.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/mesh_io.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/tone/stipple.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "tests/support/segment_occlusion.h"
#include "tests/support/shapes.h"
#include "tests/support/tone_raster.h"

namespace {

namespace core = inkline::core;
namespace test = inkline::test;

struct Args {
    std::filesystem::path bunny;
    int frames = 24;
    int size = 1024;
    double max = 0.4;
    int sphere_levels = 6;
};

[[noreturn]] void usage(const char* why) {
    std::fprintf(stderr,
                 "inkline_tone_bench: %s\nusage: inkline_tone_bench BUNNY.off [--frames N] [--size PX] [--max T] "
                 "[--sphere-levels L]\n",
                 why);
    std::exit(2);
}

Args parse(int argc, char** argv) {
    Args args;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(("missing value after " + a).c_str());
            return argv[++i];
        };
        if (a == "--frames") {
            args.frames = std::stoi(value());
        } else if (a == "--size") {
            args.size = std::stoi(value());
        } else if (a == "--max") {
            args.max = std::stod(value());
        } else if (a == "--sphere-levels") {
            args.sphere_levels = std::stoi(value());
        } else if (!a.empty() && a[0] == '-') {
            usage(("unknown option " + a).c_str());
        } else {
            args.bunny = a;
        }
    }
    if (args.bunny.empty()) usage("give the bunny's path (data/meshes/bunny00.off)");
    if (args.frames < 2 || args.size < 16 || !(args.max > 0.0 && args.max <= 0.9)) usage("bad option value");
    return args;
}

// Light from the camera's right (+x) and a little above: N.L spans -1 to 1 over what is seen.
const core::Light kSideLight{.direction = {-1.0, -0.2, 0.0}};

struct Subject {
    std::string name;
    core::Mesh mesh;
    bool sphere = false;  // a unit sphere at the origin: N.L from the analytic sphere
};

// The default turntable's framing (core::default_turntable_scene) without its orbit, at size x size.
core::Scene framed(const core::Mesh& mesh, int size) {
    core::Scene scene = core::default_turntable_scene({}, core::bounds_of(mesh.positions));
    scene.camera.orbit.reset();
    scene.image = {size, size};
    scene.first_frame = scene.last_frame = 1;
    scene.light = kSideLight;
    return scene;
}

double tone_ms(const core::FrameResult& result) {
    for (const auto& [stage, ms] : result.lines.stats.ms) {
        if (stage == "tone") return ms;
    }
    return 0.0;
}


double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Coverage per band of N.L, lines off, one frame; returns the largest error over the bands
// with a target of at least 0.05.
double coverage(const Subject& subject, const Args& args, double max, core::VisibilityMode mode) {
    core::Scene scene = framed(subject.mesh, args.size);
    scene.lines.silhouette = scene.lines.boundary = scene.lines.crease = scene.lines.intersection = false;
    scene.tone = {.mode = core::ToneMode::kStipple, .curve = {.max = max}};
    core::MeshFrames meshes(subject.mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(mode));
    const core::FrameResult result = pipeline.run(1);
    const core::Projection projection(result.lines.camera, scene.image, result.world_from_object);
    const std::vector<double> ink = test::dot_coverage(result.tone.dots, scene.image);
    const test::SurfacePixels surface =
        subject.sphere ? test::sphere_pixels(glm::dvec3(0.0), 1.0, projection, scene.light)
                       : test::mesh_pixels(subject.mesh, core::vertex_normals(subject.mesh), projection, scene.light);
    const std::vector<test::ToneBand> bands = test::tone_bands(surface, ink, result.tone.dots, scene.tone);
    std::printf("\n### %s: coverage per band of N.L, max %.2f (%zu dots, %d px, lines off)\n\n%s", subject.name.c_str(),
                max, result.tone.dots.size(), args.size, test::band_table(bands).c_str());
    double worst = 0.0;
    for (const test::ToneBand& band : bands) {
        if (band.target >= 0.05) worst = std::max(worst, std::abs(band.relative_error()));
    }
    std::printf("  worst |error| over bands with target >= 0.05: %.1f%% (bound 10%%)\n", 100.0 * worst);
    return worst;
}

struct TurntableSummary {
    double first_ms = 0.0, median_ms = 0.0, max_ms = 0.0, mean_dots = 0.0, ms_per_10k = 0.0, median_per_10k = 0.0;
    int grew = 0;  // frames after the first that added surface samples
    double max_hidden = 0.0, mean_hidden = 0.0, min_kept = 1.0, mean_kept = 0.0;
};

TurntableSummary turntable(const Subject& subject, const Args& args, core::VisibilityMode mode) {
    core::Scene scene = framed(subject.mesh, args.size);
    scene.tone = {.mode = core::ToneMode::kStipple, .curve = {.max = args.max}};
    scene.last_frame = args.frames;
    scene.object_rotation =
        core::Rotation{.axis = {0.0, 1.0, 0.0}, .degrees = 2.0 * args.frames, .center = core::bounds_of(subject.mesh.positions).center()};
    core::MeshFrames meshes(subject.mesh);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(mode),
                                 {.tracker = core::TrackerMode::kIncremental, .frame_count = args.frames});
    const test::SegmentOcclusion exact(subject.mesh);

    std::printf("\n### %s: turntable, 2 degrees a frame, max %.2f, %d px, lines on, %s visibility\n\n", subject.name.c_str(),
                args.max, args.size, core::visibility_mode_name(mode));
    std::printf("  frame   tone ms     dots   ms/10k dots   kept   hidden (exact)   samples  considered  inked  occluded\n");
    TurntableSummary s;
    std::vector<double> later_ms, later_per_10k;
    size_t samples = 0;
    double later_dots = 0.0, hidden_sum = 0.0, kept_sum = 0.0;
    std::vector<core::Dot> before;
    for (int frame = 1; frame <= args.frames; ++frame) {
        const core::FrameResult result = pipeline.run(frame);
        const core::FrameTone& tone = result.tone;
        const double ms = tone_ms(result);
        const core::Projection projection(result.lines.camera, scene.image, result.world_from_object);
        const double hidden = exact.hidden_share(projection.eye_object(), tone.dots);
        const double kept = frame == 1 ? 1.0 : test::kept_share(before, tone.dots);
        char kept_text[16] = "     -";
        if (frame > 1) std::snprintf(kept_text, sizeof kept_text, "%.4f", kept);
        std::printf("  %5d  %8.2f  %7zu      %8.2f  %s   %.4f%%        %9zu  %10zu  %5zu  %8zu\n", frame, ms,
                    tone.dots.size(), tone.dots.empty() ? 0.0 : 1e4 * ms / double(tone.dots.size()), kept_text,
                    100.0 * hidden, tone.stipple_stats.samples, tone.stipple_stats.considered, tone.stipple_stats.inked, tone.stipple_stats.occluded);
        s.max_hidden = std::max(s.max_hidden, hidden);
        hidden_sum += hidden;
        s.mean_dots += double(tone.dots.size());
        if (frame == 1) {
            s.first_ms = ms;
        } else {
            later_ms.push_back(ms);
            later_per_10k.push_back(tone.dots.empty() ? 0.0 : 1e4 * ms / double(tone.dots.size()));
            s.grew += tone.stipple_stats.samples > samples ? 1 : 0;
            later_dots += double(tone.dots.size());
            s.min_kept = std::min(s.min_kept, kept);
            kept_sum += kept;
        }
        before = tone.dots;
        samples = tone.stipple_stats.samples;
    }
    s.mean_dots /= args.frames;
    s.mean_hidden = hidden_sum / args.frames;
    s.mean_kept = kept_sum / double(args.frames - 1);
    s.median_ms = median(later_ms);
    s.max_ms = *std::max_element(later_ms.begin(), later_ms.end());
    s.median_per_10k = median(later_per_10k);
    s.ms_per_10k = later_dots > 0.0 ? 1e4 * std::accumulate(later_ms.begin(), later_ms.end(), 0.0) / later_dots : 0.0;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Args args = parse(argc, argv);
        const core::VisibilityMode mode =
            core::raycast_available() ? core::VisibilityMode::kRaycast : core::VisibilityMode::kExact;
        if (mode != core::VisibilityMode::kRaycast) std::printf("note: this build has no Embree; exact visibility\n");
        std::vector<Subject> subjects;
        subjects.push_back({"bunny", core::load_mesh(args.bunny).mesh, false});
        subjects.push_back({"sphere (icosphere " + std::to_string(args.sphere_levels) + ")",
                            test::icosphere(args.sphere_levels), true});
        for (const Subject& s : subjects) std::printf("%s: %zu faces\n", s.name.c_str(), s.mesh.triangles.size());

        std::vector<double> worst_coverage;
        for (const Subject& s : subjects) {
            for (const double max : {0.4, 0.7}) worst_coverage.push_back(coverage(s, args, max, mode));
        }
        std::vector<TurntableSummary> summaries;
        for (const Subject& s : subjects) summaries.push_back(turntable(s, args, mode));

        std::printf("\n## Summary (%d px, %d frames; must show: coverage within 10%%, hidden <= 0.5%%, kept >= 95%%, "
                    "< 10 ms per 10k dots)\n\n",
                    args.size, args.frames);
        std::printf("  %-22s %8s %8s %7s %9s %9s %8s %5s %7s %7s %8s %8s %9s\n", "subject", "cov 0.4", "cov 0.7", "dots",
                    "ms frame1", "ms median", "ms max", "grew", "ms/10k", "median", "hidden", "kept min", "kept mean");
        for (size_t i = 0; i < subjects.size(); ++i) {
            const TurntableSummary& s = summaries[i];
            std::printf("  %-22s %7.1f%% %7.1f%% %7.0f %9.2f %9.2f %8.2f %5d %7.2f %7.2f %7.3f%% %8.4f %9.4f\n",
                        subjects[i].name.c_str(), 100.0 * worst_coverage[2 * i], 100.0 * worst_coverage[2 * i + 1],
                        s.mean_dots, s.first_ms, s.median_ms, s.max_ms, s.grew, s.ms_per_10k, s.median_per_10k,
                        100.0 * s.max_hidden, s.min_kept, s.mean_kept);
        }
        std::printf("\n  cov: worst |coverage - target| / target over bands with target >= 0.05; ms: the tone stage,\n"
                    "  frames 2.. (frame 1 builds the surface samples); grew: frames 2.. that added samples (a\n"
                    "  level, about doubling them); ms/10k: frames 2..'s total ms over their dots, and the median\n"
                    "  of each frame's; hidden: the largest share of a frame's dots an exact segment test finds hidden.\n");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_tone_bench: %s\n", e.what());
        return 1;
    }
}
