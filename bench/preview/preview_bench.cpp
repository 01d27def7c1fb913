// SPDX-License-Identifier: MIT
// Time per frame of the GL preview on a scene, next to Cairo's PNG of the same strokes, and the
// files docs/preview.md shows. Draws each frame with the CLI's own core::FramePipeline (as
// `inkline render --visibility exact` does: incremental tracker, exact visibility, gap bridging,
// brush strokes), then times the preview (strips, render, read back), its PNG encoding, and
// Cairo's PNG. Prints a markdown table of medians and how well the
// two PNGs' ink coverage (alpha > 1/2) agrees (intersection over union).
//
//   inkline_preview_bench [--scene samples/torus/scene.json] [--frames A:B] [--gl auto|egl|osmesa]
//                         [--samples N] [--underlay none|flat|toon] [--out DIR]
//
// With --out, writes DIR/preview_%04d.png, DIR/cairo_%04d.png, DIR/frame_%04d.svg and the brush
// tip as DIR/tip.png.

#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/frame_pattern.h"
#include "core/scene/scene.h"
#include "core/visibility/occlusion_source.h"
#include "export/drawing.h"
#include "export/png.h"
#include "export/svg.h"
#include "gl/brush_tip.h"
#include "gl/context.h"
#include "gl/preview.h"
#include "tests/support/raster.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace core = inkline::core;
namespace gl = inkline::gl;
namespace output = inkline::output;
namespace fs = std::filesystem;
namespace test = inkline::test;

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

void write(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

struct Args {
    std::string scene = "samples/torus/scene.json";
    std::string frames;
    std::string backend = "auto";
    int samples = 8;
    std::string underlay = "none";
    std::string out;
};

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i], value = argv[i + 1];
        if (key == "--scene") {
            a.scene = value;
        } else if (key == "--frames") {
            a.frames = value;
        } else if (key == "--gl") {
            a.backend = value;
        } else if (key == "--samples") {
            a.samples = std::atoi(value.c_str());
        } else if (key == "--underlay") {
            a.underlay = value;
        } else if (key == "--out") {
            a.out = value;
        } else {
            throw std::runtime_error("unknown option " + key);
        }
    }
    return a;
}

int run(const Args& args) {
    core::Scene scene = core::load_scene(args.scene);
    int first = scene.first_frame, last = scene.last_frame;
    if (!args.frames.empty()) {
        const auto colon = args.frames.find(':');
        first = std::stoi(args.frames.substr(0, colon));
        last = colon == std::string::npos ? first : std::stoi(args.frames.substr(colon + 1));
    }
    core::MeshFrames meshes(scene.mesh, first);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kExact),
                                 {.frame_count = last - first + 1});

    const auto context = gl::create_context(gl::parse_backend(args.backend));
    gl::PreviewOptions options;
    options.samples = args.samples;
    if (args.underlay == "flat") options.underlay = gl::Underlay::kFlat;
    if (args.underlay == "toon") options.underlay = gl::Underlay::kToon;
    const gl::BrushTip tip = scene.brush.tip.empty() ? gl::default_brush_tip() : gl::load_brush_tip(scene.brush.tip);
    gl::PreviewRenderer renderer(*context, scene.brush, tip, options);
    if (!args.out.empty()) {
        fs::create_directories(args.out);
        // The tip itself, as ink on a transparent background.
        std::vector<uint8_t> rgba;
        for (const uint8_t a : tip.alpha) rgba.insert(rgba.end(), {0, 0, 0, a});
        write(fs::path(args.out) / "tip.png", output::png_from_rgba(tip.width, tip.height, rgba));
    }

    output::DrawStyle style;
    style.color = output::hex_color(scene.brush.color);
    style.opacity = scene.brush.opacity;
    std::vector<double> geometry, render, readback, encode, preview_total, cairo_total, overlap;
    size_t triangles = 0;
    for (int frame = first; frame <= last; ++frame) {
        const core::FrameResult drawn = pipeline.run(frame);
        const core::FrameLines& lines = drawn.lines;
        const core::FrameStrokes& strokes = drawn.strokes;

        auto start = std::chrono::steady_clock::now();
        // As `inkline render --preview` draws it: toon normals split at the creases tone reads.
        const gl::PreviewImage image = renderer.render(
            lines, strokes,
            {.mesh = drawn.mesh,
             .world_from_object = drawn.world_from_object,
             .table = drawn.table,
             .crease_angle_deg = core::tone_crease_angle_deg(scene)});
        const std::string png = output::png_from_rgba(image.width, image.height, image.rgba);
        preview_total.push_back(ms_since(start));
        const gl::PreviewStats& stats = renderer.last_render();
        geometry.push_back(stats.geometry_ms);
        render.push_back(stats.render_ms);
        readback.push_back(stats.readback_ms);
        encode.push_back(preview_total.back() - stats.geometry_ms - stats.render_ms - stats.readback_ms);
        triangles = std::max(triangles, stats.triangles);

        start = std::chrono::steady_clock::now();
        const output::Drawing drawing = output::brush_drawing(lines, strokes, style, false);
        const std::string cairo = output::png_image(drawing);
        cairo_total.push_back(ms_since(start));
        overlap.push_back(
            test::iou(test::png_coverage(png, test::Ink::kAlpha), test::png_coverage(cairo, test::Ink::kAlpha)));

        if (!args.out.empty()) {
            write(fs::path(args.out) / core::format_frame("preview_%04d.png", frame), png);
            write(fs::path(args.out) / core::format_frame("cairo_%04d.png", frame), cairo);
            write(fs::path(args.out) / core::format_frame("frame_%04d.svg", frame), output::svg_document(drawing, {}));
        }
    }
    std::printf("%s, %s, %dx%d, frames %d-%d, %d samples, underlay %s, up to %zu triangles\n\n",
                context->backend_name(), context->renderer().c_str(), scene.image.width, scene.image.height, first,
                last, renderer.last_render().samples, args.underlay.c_str(), triangles);
    std::printf("| stage (median ms per frame) | ms |\n| --- | --- |\n");
    std::printf("| strips built and uploaded | %.2f |\n", median(geometry));
    std::printf("| render (clear, draw, resolve, finish) | %.2f |\n", median(render));
    std::printf("| read back and un-premultiply | %.2f |\n", median(readback));
    std::printf("| PNG encoding | %.2f |\n", median(encode));
    std::printf("| **preview total** | **%.2f** |\n", median(preview_total));
    std::printf("| Cairo PNG of the outlines, for comparison | %.2f |\n", median(cairo_total));
    std::printf("\nink coverage IoU with the Cairo PNG: median %.4f, lowest %.4f\n", median(overlap),
                *std::min_element(overlap.begin(), overlap.end()));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(parse(argc, argv));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_preview_bench: %s\n", e.what());
        return 1;
    }
}
