// SPDX-License-Identifier: MIT
// The pipeline per frame:
//   MeshFrames::at -> camera_at -> extract_feature_edges -> chain_feature_edges
//   -> split_by_visibility -> polylines_json / centerline_svg -> write_file_atomically
#include "cli/render.h"

#include "cli/outputs.h"

#include "core/error.h"
#include "core/lines/chaining.h"
#include "core/lines/features.h"
#include "core/lines/silhouette_tracker.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/topology.h"
#include "core/pipeline/frame_lines.h"
#include "core/scene/frame_pattern.h"
#include "core/scene/scene.h"
#include "core/strokes/strokes.h"
#include "core/visibility/exact_visibility.h"
#include "core/visibility/raycast_visibility.h"
#include "core/visibility/visibility.h"
#include "export/atomic_file.h"
#include "export/drawing.h"
#include "export/json.h"
#include "export/pdf.h"
#include "export/png.h"
#include "export/svg.h"
#include "gl/brush_tip.h"
#include "gl/context.h"
#include "gl/depth_visibility.h"
#include "gl/preview.h"

#include <glm/mat4x4.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <regex>

#include <sys/stat.h>
#include <unistd.h>

namespace inkline::cli {
namespace {

namespace fs = std::filesystem;

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

struct FrameRange {
    int first = 1;
    int last = 1;
    int count() const { return last - first + 1; }
};

// "A:B" or "A" -> inclusive frame range, within core's frame numbers.
FrameRange parse_frames(const std::string& text) {
    static const std::regex range(R"(^\s*(-?\d{1,18})\s*(?::\s*(-?\d{1,18}))?\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, range)) throw InputError("--frames '" + quote_value(text) + "': expected A:B");
    const long long first = std::stoll(m[1]), last = m[2].matched ? std::stoll(m[2]) : first;
    core::check_frame_range(first, last, "--frames '" + quote_value(text) + "'");
    return {int(first), int(last)};
}

core::ImageSize parse_size(const std::string& text, int max_side) {
    static const std::regex size(R"(^\s*(\d{1,9})\s*[xX]\s*(\d{1,9})\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, size)) throw InputError("--size '" + quote_value(text) + "': expected WxH");
    const core::ImageSize image{std::stoi(m[1]), std::stoi(m[2])};
    if (image.width <= 0 || image.height <= 0 || image.width > max_side || image.height > max_side) {
        throw InputError("--size '" + quote_value(text) + "': each side must be 1.." + std::to_string(max_side) +
                         " px (see --max-image-side)");
    }
    return image;
}

bool is_scene_file(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    return ext == ".json" || ext == ".JSON";
}

bool inside(const core::Bounds& b, const glm::dvec3& p) {
    return glm::all(glm::greaterThanEqual(p, b.min)) && glm::all(glm::lessThanEqual(p, b.max));
}

struct DrawnFrame {
    core::FrameLines lines;
    core::FrameStrokes strokes;
    const core::Mesh* mesh = nullptr;  // the frame's mesh, alive until the next draw()
    glm::dmat4 world_from_object{1.0};
};

// The occlusion test chosen for a run, and why.
struct VisibilityChoice {
    std::string mode;  // gl, raycast or exact
    std::string reason;
    std::unique_ptr<gl::Context> context;  // for gl
};

VisibilityChoice choose_visibility(const RenderArgs& args) {
    VisibilityChoice choice;
    const std::string& asked = args.visibility;
    if (asked != "auto" && asked != "gl" && asked != "raycast" && asked != "exact") {
        throw InputError("--visibility '" + quote_value(asked) + "': expected auto, gl, raycast or exact");
    }
    if (asked == "exact" || asked == "raycast") {
        choice.mode = asked;
        choice.reason = "asked for";
        if (asked == "raycast" && !core::raycast_available())
            throw InputError("--visibility raycast: this build has no Embree");
        return choice;
    }
    const gl::Backend backend = gl::parse_backend(args.gl_backend);
    // Without a GPU any context is a software renderer: no need to start one to find out.
    if (asked == "auto" && core::raycast_available() && !gl::gpu_device_present()) {
        choice.mode = "raycast";
        choice.reason = "no GPU device (/dev/dri/renderD*, /dev/nvidia*): CPU ray casting";
        return choice;
    }
    try {
        choice.context = gl::create_context(backend);
    } catch (const gl::ContextError& e) {
        if (asked == "gl") throw InputError(std::string("--visibility gl: no OpenGL context: ") + e.what());
        choice.mode = core::raycast_available() ? "raycast" : "exact";
        choice.reason = std::string("no OpenGL context (") + e.what() + ")";
        return choice;
    } catch (const OutOfMemory& e) {
        if (asked == "gl") throw;
        choice.mode = core::raycast_available() ? "raycast" : "exact";
        choice.reason = std::string("no OpenGL (") + e.what() + ")";
        return choice;
    }
    const std::string renderer = choice.context->backend_name() + std::string(": ") + choice.context->renderer();
    if (asked == "gl") {
        choice.mode = "gl";
        choice.reason = "asked for, " + renderer;
    } else if (!choice.context->is_software()) {
        choice.mode = "gl";
        choice.reason = "hardware OpenGL (" + renderer + ")";
    } else if (core::raycast_available()) {
        choice.mode = "raycast";
        choice.reason = "software OpenGL (" + renderer + "): CPU ray casting is faster";
        choice.context.reset();
    } else {
        choice.mode = "gl";
        choice.reason = "software OpenGL (" + renderer + ") and no Embree in this build";
    }
    return choice;
}

// Everything that lives across frames: the tracker, the occlusion test and stroke coherence.
class Sequence {
  public:
    Sequence(const core::Scene& scene, const RenderArgs& args, core::MeshFrames& meshes, int frame_count)
        : scene_(scene), args_(args), meshes_(meshes), visibility_(choose_visibility(args)) {
        if (args.tracker != "incremental" && args.tracker != "brute")
            throw InputError("--tracker '" + quote_value(args.tracker) + "': expected incremental or brute");
        // The tracker's cone hierarchy costs about one brute-force pass per few hundred thousand
        // faces to build and repays it over later frames; a single frame gets the identical
        // result cheaper by brute force.
        tracker_mode_ = frame_count > 1 ? args.tracker : "brute";
        if (args.verbose) std::fprintf(stderr, "inkline: visibility %s: %s\n", visibility_.mode.c_str(), visibility_.reason.c_str());
    }

    DrawnFrame draw(int frame) {
        Clock clock;
        DrawnFrame out;
        core::FrameLines& result = out.lines;
        result.frame = frame;
        result.image = scene_.image;
        result.light = scene_.light;
        const core::Mesh& mesh = meshes_.at(frame);
        const double load_ms = clock.lap_ms();
        const core::EdgeTable& table = meshes_.edges();

        const glm::dmat4 world_from_object = core::world_from_object_at(scene_, frame);
        const core::Bounds object_bounds = core::bounds_of(mesh.positions);
        result.camera = core::camera_at(scene_, frame, core::transformed(object_bounds, world_from_object));
        const core::Projection projection(result.camera, scene_.image, world_from_object);
        if (!warned_inside_ && inside(object_bounds, projection.eye_object())) {
            warned_inside_ = true;
            warn("frame " + std::to_string(frame) + ": the camera is inside the mesh's bounds; lines may be hidden");
        }

        const core::FeatureEdges features = extract(mesh, table, projection.eye_object());
        const double extract_ms = clock.lap_ms();
        const std::vector<core::Chain> chains = core::chain_feature_edges(features, table);
        const double chain_ms = clock.lap_ms();
        const core::Occlusion& occlusion = prepare_occlusion(mesh, table, projection);
        // Occluded parts are always found (the samples are classified anyway): the stroke stage
        // bridges short ones. Without lines.hidden they stay out of the output.
        const core::VisibilityOptions visibility{.keep_hidden = true};
        result.strokes = core::split_by_visibility(chains, mesh, projection, occlusion, visibility);
        if (!scene_.lines.hidden) core::set_aside_occluded(result);
        const double visibility_ms = clock.lap_ms();
        out.strokes = core::build_strokes(result, mesh, table, projection, scene_.brush, coherence_);
        out.mesh = &mesh;
        out.world_from_object = world_from_object;
        const double strokes_ms = clock.lap_ms();
        first_frame_ = false;

        core::FrameStats& stats = result.stats;
        stats.faces = mesh.triangles.size();
        stats.edges = table.edge_count();
        stats.edges_tested = features.edges_tested;
        stats.faces_tested = features.faces_tested;
        stats.feature_edges = features.count_by_kind();
        stats.silhouette_edges = stats.feature_edges[size_t(core::LineKind::kSilhouette)];
        stats.tracker = tracker_mode_;
        stats.visibility = visibility_.mode;
        stats.visibility_reason = visibility_.reason;
        if (visibility_.mode == "gl") stats.gl_context = visibility_.context->backend_name() + std::string(": ") + visibility_.context->renderer();
        core::tally_visible_length(result);
        stats.ms = {{"load", load_ms},
                    {"extract", extract_ms},
                    {"chain", chain_ms},
                    {"visibility", visibility_ms},
                    {"strokes", strokes_ms}};
        return out;
    }

    void warn(const std::string& message) const {
        if (!args_.quiet) std::fprintf(stderr, "inkline: warning: %s\n", message.c_str());
    }

    // Sets up the GL preview (--preview) before the first frame: on the depth pass's context when
    // it has one, else on a context of its own; its framebuffers are allocated at the scene's
    // image size, so a GL that cannot draw it fails the run before anything is written.
    void start_preview() {
        const gl::Context* context = visibility_.context.get();
        if (!context) {
            try {
                preview_context_ = gl::create_context(gl::parse_backend(args_.gl_backend));
            } catch (const gl::ContextError& e) {
                throw InputError(std::string("--preview: no OpenGL context: ") + e.what());
            }
            context = preview_context_.get();
        }
        gl::PreviewOptions options;
        const std::string& underlay = args_.preview_underlay;
        if (underlay == "flat") {
            options.underlay = gl::Underlay::kFlat;
        } else if (underlay == "toon") {
            options.underlay = gl::Underlay::kToon;
        } else if (underlay != "none") {
            throw InputError("--preview-underlay '" + quote_value(underlay) + "': expected none, flat or toon");
        }
        if (!args_.background.empty()) {
            const output::Rgb bg = output::parse_color(args_.background, "--background");
            options.background = glm::dvec3(bg.r, bg.g, bg.b);
        }
        const gl::BrushTip tip =
            scene_.brush.tip.empty() ? gl::default_brush_tip() : gl::load_brush_tip(scene_.brush.tip);
        preview_ = std::make_unique<gl::PreviewRenderer>(*context, scene_.brush, tip, options);
        preview_->prepare(scene_.image);
    }

    // The GL preview of a frame just drawn; start_preview() came first.
    gl::PreviewImage preview(const DrawnFrame& drawn) {
        return preview_->render(drawn.lines, drawn.strokes,
                                {.mesh = drawn.mesh, .world_from_object = drawn.world_from_object});
    }

  private:
    core::FeatureEdges extract(const core::Mesh& mesh, const core::EdgeTable& table, const glm::dvec3& eye_object) {
        if (tracker_mode_ == "brute") return core::extract_feature_edges(mesh, table, eye_object, scene_.lines);
        if (!tracker_) {
            tracker_.emplace(table, mesh, core::TrackerOptions{.deforming = meshes_.is_sequence()});
        }
        return tracker_->update(mesh, eye_object, scene_.lines);
    }

    // The occlusion test for this frame: built once for a static mesh, updated for a sequence.
    const core::Occlusion& prepare_occlusion(const core::Mesh& mesh, const core::EdgeTable& table,
                                             const core::Projection& projection) {
        const bool moved = meshes_.is_sequence() && !first_frame_;
        if (visibility_.mode == "gl") {
            if (!depth_) depth_ = std::make_unique<gl::DepthOcclusion>(*visibility_.context);
            depth_->prepare(mesh, table, projection,
                            first_frame_ ? gl::MeshChange::kTopology : moved ? gl::MeshChange::kPositions : gl::MeshChange::kNone);
            return *depth_;
        }
        if (visibility_.mode == "raycast") {
            if (!raycast_) {
                raycast_ = std::make_unique<core::RaycastOcclusion>(mesh, table);
            } else if (moved) {
                raycast_->update_positions(mesh);
            }
            return *raycast_;
        }
        if (!exact_ || moved) exact_ = std::make_unique<core::ExactOcclusion>(mesh, table);
        return *exact_;
    }

    const core::Scene& scene_;
    const RenderArgs& args_;
    core::MeshFrames& meshes_;
    VisibilityChoice visibility_;
    std::string tracker_mode_;
    std::optional<core::SilhouetteTracker> tracker_;
    std::unique_ptr<gl::DepthOcclusion> depth_;
    std::unique_ptr<core::RaycastOcclusion> raycast_;
    std::unique_ptr<core::ExactOcclusion> exact_;
    core::StrokeCoherence coherence_;
    bool first_frame_ = true;
    bool warned_inside_ = false;
    // Declared after visibility_: destroyed before the context they may run on.
    std::unique_ptr<gl::Context> preview_context_;
    std::unique_ptr<gl::PreviewRenderer> preview_;
};

// SOURCE_DATE_EPOCH when set (the reproducible-builds convention), else the input file's
// modification time: the same input gives byte-identical PDFs, whichever chunk wrote them.
std::string reproducible_date(const std::string& input) {
    std::time_t when = 0;
    if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch && *epoch) {
        when = std::time_t(std::strtoll(epoch, nullptr, 10));
    } else {
        struct stat info {};
        if (::stat(input.c_str(), &info) != 0) return "";
        when = info.st_mtime;
    }
    std::tm utc{};
    gmtime_r(&when, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
    return text;
}

// "K/N" or "slurm" (SLURM_ARRAY_TASK_ID within SLURM_ARRAY_TASK_MIN..SLURM_ARRAY_TASK_MAX).
std::pair<int, int> parse_chunk(const std::string& text) {
    if (text == "slurm") {
        auto env = [](const char* name) -> long {
            const char* v = std::getenv(name);
            if (!v || !*v) throw InputError(std::string("--chunk slurm: ") + name + " is not set (not inside a Slurm job array?)");
            static const std::regex number(R"(^\s*\d{1,9}\s*$)");
            if (!std::regex_match(v, number)) {
                throw InputError(std::string("--chunk slurm: ") + name + " is not a task number");
            }
            return std::strtol(v, nullptr, 10);
        };
        const long id = env("SLURM_ARRAY_TASK_ID"), lo = env("SLURM_ARRAY_TASK_MIN"), hi = env("SLURM_ARRAY_TASK_MAX");
        if (id < lo || id > hi || hi - lo > 1000000) throw InputError("--chunk slurm: task id outside the array's bounds");
        return {int(id - lo + 1), int(hi - lo + 1)};
    }
    static const std::regex chunk(R"(^\s*(\d{1,7})\s*/\s*(\d{1,7})\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, chunk)) throw InputError("--chunk '" + quote_value(text) + "': expected K/N or slurm");
    const int k = std::stoi(m[1]), n = std::stoi(m[2]);
    if (n < 1) throw InputError("--chunk '" + quote_value(text) + "': N must be at least 1");
    if (k < 1 || k > n) throw InputError("--chunk '" + quote_value(text) + "': K must be 1.." + std::to_string(n));
    return {k, n};
}

// A progress line rewritten in place on a terminal: frames done, frames per second, time left.
class Progress {
  public:
    Progress(int total, bool enabled) : total_(total), enabled_(enabled && ::isatty(STDERR_FILENO)) {}
    void frame_done() {
        if (!enabled_) return;
        ++done_;
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        const double fps = seconds > 0.0 ? done_ / seconds : 0.0;
        const int left = fps > 0.0 ? int((total_ - done_) / fps + 0.5) : 0;
        std::fprintf(stderr, "\rinkline: frame %d/%d  %.1f frames/s  %d:%02d left ", done_, total_, fps, left / 60,
                     left % 60);
        if (done_ == total_) std::fprintf(stderr, "\n");
    }

  private:
    int total_;
    int done_ = 0;
    bool enabled_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Writes every per-frame file of a drawn frame; collects pages of a multi-page PDF.
class Writers {
  public:
    Writers(const Outputs& outputs, const RenderArgs& args, const core::Scene& scene)
        : outputs_(outputs), centerline_(args.centerline) {
        const fs::path& mesh_name = scene.mesh.path;
        style_.color = output::hex_color(scene.brush.color);
        style_.opacity = scene.brush.opacity;
        style_.background = args.background.empty() ? std::nullopt : std::optional(args.background);
        if (style_.background) output::parse_color(*style_.background, "--background");
        pdf_options_.page = args.page.empty() ? std::nullopt : std::optional(output::parse_page_size(args.page));
        pdf_options_.margin_mm = args.margin_mm;
        pdf_options_.dpi = args.dpi;
        if (!(args.dpi > 0.0 && args.dpi <= 10000.0)) throw InputError("--dpi: must be between 0 and 10000");
        if (!(args.margin_mm >= 0.0 && args.margin_mm < 1000.0)) throw InputError("--margin: must be 0..1000 mm");
        pdf_options_.title = fs::path(mesh_name).stem().string();
        pdf_options_.creation_date = reproducible_date(args.input);
        // What Cairo cannot draw is refused before any file is written.
        if (!outputs_.png.empty() || !outputs_.preview.empty()) {
            output::check_png_size(scene.image.width, scene.image.height);
        }
        if (!outputs_.pdf.empty()) output::check_pdf_page(pdf_options_, scene.image.width, scene.image.height);
        if (!outputs_.pdf.empty() && !outputs_.pdf_per_frame) pdf_ = std::make_unique<output::PdfDocument>(pdf_options_);
    }

    // Returns the number of files written for this frame.
    size_t write(DrawnFrame& drawn) {
        core::FrameLines& frame = drawn.lines;
        size_t files = 0;
        Clock clock;
        const output::Drawing drawing = output::brush_drawing(frame, drawn.strokes, style_, centerline_);
        if (!outputs_.svg.empty()) {
            output::write_file_atomically(core::format_frame(outputs_.svg, frame.frame), output::svg_document(drawing, {}));
            ++files;
        }
        frame.stats.ms.emplace_back("svg", clock.lap_ms());
        if (!outputs_.png.empty()) {
            output::write_file_atomically(core::format_frame(outputs_.png, frame.frame), output::png_image(drawing));
            ++files;
        }
        frame.stats.ms.emplace_back("png", clock.lap_ms());
        if (outputs_.pdf_per_frame) {
            output::PdfDocument page(pdf_options_);
            page.add_page(drawing);
            output::write_file_atomically(core::format_frame(outputs_.pdf, frame.frame), page.finish());
            ++files;
        } else if (pdf_) {
            pdf_->add_page(drawing);
        }
        frame.stats.ms.emplace_back("pdf", clock.lap_ms());
        if (!outputs_.json.empty()) {
            output::write_file_atomically(core::format_frame(outputs_.json, frame.frame),
                                          output::polylines_json(frame, &drawn.strokes));
            ++files;
        }
        return files;
    }

    // Writes the multi-page PDF with the pages so far, also after a failure, so no drawn frame
    // is lost; but a run that failed never replaces a PDF already there, which may hold more of
    // the sequence. Returns the number of files written.
    size_t finish(bool complete, const std::function<void(const std::string&)>& warn) {
        if (!pdf_ || pdf_->pages() == 0) return 0;
        std::unique_ptr<output::PdfDocument> doc = std::move(pdf_);
        std::error_code ec;
        if (!complete && fs::exists(outputs_.pdf, ec)) {
            warn(quote_value(outputs_.pdf, 160) + ": kept as it was; the " + std::to_string(doc->pages()) +
                 " page(s) of this failed run are not written over it");
            return 0;
        }
        output::write_file_atomically(outputs_.pdf, doc->finish());
        return 1;
    }

  private:
    const Outputs& outputs_;
    bool centerline_;
    output::DrawStyle style_;
    output::PdfOptions pdf_options_;
    std::unique_ptr<output::PdfDocument> pdf_;
};

}  // namespace

ChunkRange chunk_range(int first, int last, int k, int n) {
    const long count = long(last) - first + 1;
    const long base = count / n, extra = count % n;
    const long begin = first + (k - 1) * base + std::min<long>(k - 1, extra);
    const long size = base + (k <= extra ? 1 : 0);
    return {int(begin), int(begin + size - 1)};
}

RenderPlan plan_render(const RenderArgs& args) {
    FrameRange frames{1, 48};  // a bare mesh's default turntable
    if (is_scene_file(args.input)) {
        const core::Scene scene = core::load_scene(args.input, args.max_image_side);
        frames = {scene.first_frame, scene.last_frame};
    }
    if (!args.frames.empty()) frames = parse_frames(args.frames);
    const Outputs o = resolve_outputs(args, frames.count());
    return {frames.first, frames.last, o.json, o.svg, o.png, o.preview, o.pdf, o.pdf_per_frame};
}

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

int run_render(const RenderArgs& args) {
    // Scene: a file, or a default turntable around a bare mesh (made once the mesh is read).
    const bool from_scene = is_scene_file(args.input);
    core::Scene scene;
    if (from_scene) {
        scene = core::load_scene(args.input, args.max_image_side);
    } else {
        scene.mesh.path = args.input;
        scene.first_frame = 1;
        scene.last_frame = 48;
    }
    FrameRange frames{scene.first_frame, scene.last_frame};
    if (!args.frames.empty()) frames = parse_frames(args.frames);
    const std::optional<core::ImageSize> size =
        args.size.empty() ? std::nullopt : std::optional(parse_size(args.size, args.max_image_side));
    const Outputs outputs = resolve_outputs(args, frames.count());
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
    core::check_cameras(scene, frames.first, frames.last);
    check_outputs(outputs, rendered.first, rendered.last, run_inputs(scene, frames.first, frames.last));

    core::MeshFrames meshes(scene.mesh, frames.first, {args.max_faces});
    const size_t faces = meshes.at(frames.first).triangles.size();
    if (faces > args.max_faces) {
        throw InputError(meshes.path_of(frames.first).string() + ": " + std::to_string(faces) +
                         " faces exceed the limit of " + std::to_string(args.max_faces) + " (raise it with --max-faces)");
    }
    if (!from_scene) {
        const int first = scene.first_frame, last = scene.last_frame;
        scene = core::default_turntable_scene(args.input, core::bounds_of(meshes.at(frames.first).positions));
        scene.first_frame = first;
        scene.last_frame = last;
    }
    // The options override the scene, the default turntable's included.
    if (size) scene.image = *size;
    if (args.hidden) scene.lines.hidden = true;

    Sequence sequence(scene, args, meshes, frames.count());
    if (!outputs.preview.empty()) sequence.start_preview();
    for (const std::string& w : meshes.warnings()) sequence.warn(w);
    Writers writers(outputs, args, scene);
    Progress progress(std::max(rendered.count(), 0), !args.quiet && !args.verbose);

    const auto warn = [&](const std::string& message) { sequence.warn(message); };
    const auto start = std::chrono::steady_clock::now();
    size_t strokes = 0, files = 0, failed = 0;
    double fast_forward_ms = 0.0;
    for (int frame = frames.first; frame <= rendered.last; ++frame) {
        if (frame < rendered.first) {
            Clock clock;
            try {
                sequence.draw(frame);
            } catch (const InputError& e) {
                if (!args.keep_going) throw;
            }
            fast_forward_ms += clock.lap_ms();
            continue;
        }
        DrawnFrame result;
        try {
            result = sequence.draw(frame);
        } catch (const InputError& e) {
            if (!args.keep_going) {
                writers.finish(false, warn);
                throw;
            }
            ++failed;
            std::fprintf(stderr, "inkline: error: frame %d: %s\n", frame, e.what());
            continue;
        }
        files += writers.write(result);
        if (!outputs.preview.empty()) {
            Clock clock;
            const gl::PreviewImage image = sequence.preview(result);
            output::write_file_atomically(core::format_frame(outputs.preview, frame),
                                          output::png_from_rgba(image.width, image.height, image.rgba));
            ++files;
            result.lines.stats.ms.emplace_back("preview", clock.lap_ms());
        }
        strokes += result.strokes.strokes.size();
        progress.frame_done();
        if (args.verbose) {
            const core::FrameStats& stats = result.lines.stats;
            std::fprintf(stderr, "frame %d: %zu strokes, %zu of %zu edges tested", frame, result.strokes.strokes.size(),
                         stats.edges_tested, stats.edges);
            for (const auto& [stage, ms] : stats.ms) std::fprintf(stderr, ", %s %.1f ms", stage.c_str(), ms);
            std::fprintf(stderr, "\n");
        }
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
    const core::LoadedMesh loaded = core::load_mesh(mesh_path);
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
    for (const std::string& w : loaded.warnings) std::printf("warning: %s\n", w.c_str());
    for (const std::string& w : core::mesh_warnings(r)) std::printf("warning: %s\n", w.c_str());
    return 0;
}

}  // namespace inkline::cli
