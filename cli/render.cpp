// SPDX-License-Identifier: MIT
#include "cli/render.h"

#include "cli/outputs.h"
#include "cli/parse.h"
#include "cli/preview.h"
#include "cli/visibility_choice.h"
#include "cli/writers.h"

#include "core/error.h"
#include "core/lines/silhouette_tracker.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/pipeline/shot.h"
#include "core/pipeline/stopwatch.h"
#include "core/scene/frame_pattern.h"
#include "core/scene/gltf_shot.h"
#include "core/scene/scene.h"
#include "core/strokes/write_on.h"
#include "export/drawing.h"
#include "gl/context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

namespace inkline::cli {
namespace {

// The files a run reads, for check_outputs.
std::vector<InputFile> run_inputs(const core::Scene& scene, int first, int last) {
    std::vector<InputFile> inputs;
    if (!scene.file.empty()) inputs.push_back({"scene", scene.file});
    if (scene.mesh.is_sequence) {
        for (int frame = first; frame <= last; ++frame)
            inputs.push_back({"mesh", core::format_frame(scene.mesh.path.string(), frame)});
    } else {
        inputs.push_back({"mesh", scene.mesh.path});
    }
    if (!scene.brush.tip.empty()) inputs.push_back({"brush tip", scene.brush.tip});
    return inputs;
}

// What the arguments ask to draw.
core::ShotRequest shot_request(const RenderArgs& args) {
    return {.input = args.input,
            .max_image_side = args.max_image_side,
            .max_faces = args.max_faces,
            .gltf_scene = args.gltf_scene,
            .animation = args.animation,
            .camera = args.camera,
            .fps = args.fps,
            .write_on = args.write_on,
            .names = {}};
}

// The frames to draw: --frames, else the input's.
FrameRange frames_of(const core::Shot& shot, const RenderArgs& args) {
    if (!args.frames.empty()) return parse_frames(args.frames);
    return {shot.first_frame, shot.last_frame};
}

// --contour: mesh or smooth; nothing when not given.
std::optional<core::ContourMode> parse_contour_option(const std::string& text) {
    if (text.empty()) return std::nullopt;
    if (const std::optional<core::ContourMode> mode = core::contour_mode_from_name(text)) return mode;
    throw InputError("--contour '" + quote_value(text) + "': expected mesh or smooth");
}

// The frames a run writes: the frames it draws, and with a write-on those of the drawing of frame
// F shown at time (F - first) / fps, the last frame's held until the write-on is done.
struct WriteOnPlan {
    double seconds = 0.0;  // 0: no write-on
    double fps = 24.0;
    int first = 1;
    int written_last = 1;
    double time_at(int frame) const { return (frame - first) / fps; }
};

WriteOnPlan plan_write_on(const core::Scene& scene, const FrameRange& frames, const RenderArgs& args) {
    WriteOnPlan plan{scene.write_on_s, scene.fps, frames.first, frames.last};
    if (plan.seconds == 0.0) {
        if (!args.animated_svg.empty()) throw InputError("--animated-svg: needs a write-on (--write-on or the scene's write_on)");
        return plan;
    }
    if (!args.chunk.empty()) throw InputError("--chunk: a write-on cannot be split into chunks");
    const double steps = std::ceil(plan.seconds * plan.fps - 1e-9);
    const double done = double(frames.first) + steps;
    if (done > double(core::kMaxFrame)) {
        throw InputError("--write-on: " + quote_value(std::to_string(plan.seconds)) + " s at " + std::to_string(plan.fps) +
                         " fps runs past frame " + std::to_string(core::kMaxFrame));
    }
    plan.written_last = std::max(frames.last, int(done));
    return plan;
}

}  // namespace

ChunkRange chunk_range(int first, int last, int k, int n) {
    const long count = long(last) - first + 1;
    const long base = count / n, extra = count % n;
    const long begin = first + (k - 1) * base + std::min<long>(k - 1, extra);
    const long size = base + (k <= extra ? 1 : 0);
    return {int(begin), int(begin + size - 1)};
}

RenderPlan plan_render(const RenderArgs& args) {
    // The modes too, so that `inkline farm` refuses a bad one before it writes its job scripts.
    core::parse_tracker_mode(args.tracker, "--tracker");
    parse_contour_option(args.contour);
    output::parse_path_format(args.path_format, "--path-format");
    parse_visibility_option(args.visibility);
    gl::parse_backend(args.gl_backend);
    if (!args.tone.empty()) parse_tone(args.tone);
    const core::Shot shot = core::open_shot(shot_request(args));
    const FrameRange frames = frames_of(shot, args);
    const WriteOnPlan write_on = plan_write_on(shot.scene, frames, args);
    const Outputs o = resolve_outputs(args, frames.count(), write_on.written_last - frames.first + 1);
    return {frames.first, write_on.written_last, o.json, o.svg, o.png, o.preview, o.pdf, o.pdf_per_frame, write_on.seconds > 0.0};
}

int run_render(const RenderArgs& args) {
    // The modes, parsed once.
    const core::TrackerMode tracker = core::parse_tracker_mode(args.tracker, "--tracker");
    const std::optional<core::VisibilityMode> asked_visibility = parse_visibility_option(args.visibility);
    const std::optional<core::ToneMode> tone = args.tone.empty() ? std::nullopt : std::optional(parse_tone(args.tone));
    // Scene: a file, a glTF shot, or a default turntable around a bare mesh (made once the mesh is read).
    const core::ShotRequest request = shot_request(args);
    core::Shot shot = core::open_shot(request);
    // --tone overrides the scene's tone mode; without a "tone" block, stipple takes its defaults.
    if (tone) shot.scene.tone.mode = *tone;
    const core::Scene& scene = shot.scene;
    const FrameRange frames = frames_of(shot, args);
    const std::optional<core::ImageSize> size =
        args.size.empty() ? std::nullopt : std::optional(parse_size(args.size, args.max_image_side));
    const WriteOnPlan write_on = plan_write_on(scene, frames, args);
    const Outputs outputs = resolve_outputs(args, frames.count(), write_on.written_last - frames.first + 1);
    // A chunk renders its frames after replaying the earlier ones without output: stroke ids,
    // propagated u and loop starts depend on every earlier frame.
    FrameRange rendered = frames;
    if (!args.chunk.empty()) {
        const auto [k, n] = parse_chunk(args.chunk);
        const ChunkRange c = chunk_range(frames.first, frames.last, k, n);
        if (!outputs.pdf.empty() && !outputs.pdf_per_frame) {
            throw InputError("--pdf '" + outputs.pdf + "': with --chunk, give a per-frame pattern such as pdf/frame_%04d.pdf");
        }
        rendered = {c.first, c.last};
    }
    core::settle_cameras(shot, frames.first, frames.last, size);
    check_outputs(outputs, rendered.first, rendered.last, std::max(rendered.last, write_on.written_last),
                  run_inputs(scene, frames.first, frames.last));
    // The options override the scene, the default turntable's included.
    const std::unique_ptr<core::MeshFrames> mesh_frames =
        core::load_meshes(shot, request, frames.first, {.size = size, .hidden = args.hidden, .contour = parse_contour_option(args.contour)});
    core::MeshFrames& meshes = *mesh_frames;

    // The frame pipeline on the chosen occlusion test; the context outlives both users.
    const VisibilityChoice visibility = choose_visibility(asked_visibility, args.gl_backend);
    if (args.verbose) {
        std::fprintf(stderr, "inkline: visibility %s: %s\n", core::visibility_mode_name(visibility.mode),
                     visibility.reason.c_str());
    }
    const auto warn = [&](const std::string& message) {
        if (!args.quiet) std::fprintf(stderr, "inkline: warning: %s\n", message.c_str());
    };
    core::FramePipeline pipeline(scene, meshes, make_occlusion(visibility),
                                 {.tracker = tracker,
                                  .frame_count = frames.count(),
                                  .visibility_reason = visibility.reason});
    std::optional<Preview> preview;
    if (!outputs.preview.empty()) preview.emplace(visibility.context.get(), args, scene);
    for (const std::string& w : meshes.warnings()) warn(w);
    Writers writers(outputs, args, scene);
    Progress progress(std::max(rendered.count(), 0), !args.quiet && !args.verbose);
    size_t files = 0;
    // Once a drawn frame's files are all written: its line with -v.
    const auto written = [&](int frame) -> Writers::Written {
        return [&, frame](const core::FrameStats& stats, size_t strokes, size_t) {
            if (!args.verbose) return;
            std::fprintf(stderr, "frame %d: %zu strokes, %zu of %zu edges tested", frame, strokes, stats.edges_tested,
                         stats.edges);
            for (const auto& [stage, ms] : stats.ms) std::fprintf(stderr, ", %s %.1f ms", stage.c_str(), ms);
            std::fprintf(stderr, "\n");
        };
    };
    // Hands a drawn frame to the writers: once, or with a write-on as the frames that show it.
    const auto write = [&](core::FrameResult& result) {
        const int frame = result.lines.frame;
        if (preview) {
            preview->write(result, outputs.preview);
            ++files;
        }
        if (write_on.seconds == 0.0) {
            files += writers.write(std::move(result), written(frame));
            return;
        }
        const core::WriteOnSchedule schedule = core::schedule_write_on(result.strokes, write_on.seconds);
        files += writers.write_animated_svg(result, schedule);
        const int until = frame == frames.last ? write_on.written_last : frame;
        for (int shown_frame = frame; shown_frame <= until; ++shown_frame) {
            core::FrameResult shown;
            shown.lines = result.lines;
            shown.lines.frame = shown_frame;
            shown.strokes = core::strokes_at(result.strokes, schedule, write_on.time_at(shown_frame));
            shown.strokes.frame = shown_frame;
            shown.tone = result.tone;  // the tone is there from the start, under the strokes being drawn
            shown.mesh = result.mesh;
            shown.table = result.table;
            shown.world_from_object = result.world_from_object;
            if (preview) {
                preview->write(shown, outputs.preview);
                ++files;
            }
            // The drawn frame's line once the last frame showing it is written.
            files += writers.write(std::move(shown), shown_frame == until ? written(frame) : Writers::Written{});
        }
    };

    const auto start = std::chrono::steady_clock::now();
    size_t strokes = 0, failed = 0;
    double fast_forward_ms = 0.0;
    for (int frame = frames.first; frame <= rendered.last; ++frame) {
        if (frame < rendered.first) {
            core::Stopwatch clock;
            try {
                for (const std::string& w : pipeline.run(frame).warnings) warn(w);
            } catch (const InputError& e) {
                if (!args.keep_going) throw;
            }
            fast_forward_ms += clock.lap_ms();
            continue;
        }
        core::FrameResult result;
        try {
            result = pipeline.run(frame);
        } catch (const InputError& e) {
            if (!args.keep_going) {
                writers.finish(false, warn);
                throw;
            }
            ++failed;
            std::fprintf(stderr, "inkline: error: frame %d: %s\n", frame, e.what());
            continue;
        }
        for (const std::string& w : result.warnings) warn(w);
        strokes += result.strokes.strokes.size();
        write(result);
        progress.frame_done();
    }
    files += writers.finish(failed == 0, warn);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int skipped = rendered.first - frames.first;
    if (!args.quiet) {
        const int count = std::max(rendered.count(), 0);
        std::fprintf(stderr, "inkline: %d frame(s)%s, %zu strokes, %zu files in %.2f s (%.1f ms/frame)", count - int(failed),
                     failed ? (" (" + std::to_string(failed) + " failed)").c_str() : "", strokes, files, seconds,
                     count > 0 ? 1000.0 * (seconds - fast_forward_ms / 1000.0) / count : 0.0);
        if (skipped > 0) std::fprintf(stderr, "; fast-forward %d frame(s) at %.1f ms/frame", skipped, fast_forward_ms / skipped);
        std::fprintf(stderr, "\n");
    }
    return failed ? 2 : 0;
}

int run_info(const std::string& mesh_path) {
    // A glTF shot is reported as the mesh of its first frame, with its objects and animation.
    core::LoadedMesh loaded;
    std::optional<core::GltfShot> shot;
    if (core::is_gltf_path(mesh_path)) {
        shot.emplace(mesh_path);
        loaded.mesh = shot->rest();
        loaded.warnings = shot->warnings();
    } else {
        loaded = core::load_mesh(mesh_path);
    }
    const core::EdgeTable table = core::build_edge_table(loaded.mesh);
    const core::MeshReport r = core::describe_mesh(loaded.mesh, table);
    const core::Bounds b = core::bounds_of(loaded.mesh.positions);
    std::printf("file: %s\n", mesh_path.c_str());
    std::printf("vertices: %zu\nfaces: %zu\nedges: %zu\nboundary edges: %zu\nnon-manifold edges: %zu\n"
                "non-manifold vertices: %zu\n",
                r.vertices, r.faces, r.edges, r.boundary_edges, r.non_manifold_edges, r.non_manifold_vertices);
    std::printf("degenerate faces: %zu\nduplicate faces: %zu\ninconsistently oriented edges: %zu\nconnected components: %zu\n",
                r.degenerate_faces, r.duplicate_faces, r.inconsistent_edges, r.connected_components);
    std::printf("bounds: [%g, %g, %g] .. [%g, %g, %g]\n", b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z);
    if (shot) {
        std::printf("objects: %zu\n", shot->objects().size());
        for (const core::GltfObject& o : shot->objects()) std::printf("  %s (node %d): %u faces\n", o.name.c_str(), o.node, o.faces);
        if (const auto range = shot->frame_range()) std::printf("frames: %d..%d at %g fps\n", range->first, range->second, shot->fps());
        const std::vector<std::string> animations = shot->animations();
        if (!animations.empty()) {
            std::printf("animations: %zu (--animation NAME or INDEX)\n", animations.size());
            for (size_t a = 0; a < animations.size(); ++a) std::printf("  %zu: %s\n", a, animations[a].c_str());
        }
        if (shot->camera()) std::printf("camera: %s (%s)\n", shot->camera()->name.c_str(), shot->camera()->orthographic ? "orthographic" : "perspective");
        if (shot->cameras().size() > 1) {
            std::printf("cameras: %zu (--camera NAME or INDEX)\n", shot->cameras().size());
            for (const core::GltfCamera& c : shot->cameras()) {
                std::printf("  %zu: %s (node %d, %s)\n", c.index, c.name.c_str(), c.node,
                            c.orthographic ? "orthographic" : "perspective");
            }
        }
    }
    for (const std::string& w : loaded.warnings) std::printf("warning: %s\n", w.c_str());
    for (const std::string& w : core::mesh_warnings(r)) std::printf("warning: %s\n", w.c_str());
    return 0;
}

}  // namespace inkline::cli
