// SPDX-License-Identifier: MIT
// PNG output per frame, Cairo's encoder next to inkline's (export/png.cpp), on the same drawings,
// alternating frame by frame in one run. Draws each frame with the CLI's own core::FramePipeline
// (ray-cast visibility, brush strokes) and the CLI's drawing (brush_drawing), then times:
//   - drawing alone (Cairo rasterises the drawing into an ARGB32 image),
//   - Cairo's PNG: drawing + cairo_surface_write_to_png_stream (what png_image() did before),
//   - png_image(): drawing + libpng at inkline's settings,
// and checks that both files decode to the same pixels. Prints a markdown table of medians.
//
//   inkline_png_bench [--scene samples/torus/scene.json] [--frames A:B] [--size WxH] [--background #rrggbb]

#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/scene/scene.h"
#include "core/visibility/occlusion_source.h"
#include "export/drawing.h"
#include "export/internal/cairo_paint.h"
#include "export/png.h"

#include <cairo.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace core = inkline::core;
namespace output = inkline::output;
using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct Args {
    std::string scene = "samples/torus/scene.json";
    std::string frames;
    std::string size;
    std::string background;
};

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i], value = argv[i + 1];
        if (key == "--scene") {
            a.scene = value;
        } else if (key == "--frames") {
            a.frames = value;
        } else if (key == "--size") {
            a.size = value;
        } else if (key == "--background") {
            a.background = value;
        } else {
            throw std::runtime_error("unknown option " + key);
        }
    }
    return a;
}

Surface drawn(const output::Drawing& drawing) {
    Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, drawing.image.width, drawing.image.height),
                    cairo_surface_destroy);
    cairo_t* cr = cairo_create(surface.get());
    output::internal::paint_drawing(cr, drawing);
    cairo_destroy(cr);
    cairo_surface_flush(surface.get());
    return surface;
}

std::string cairo_png(const output::Drawing& drawing) {
    const Surface surface = drawn(drawing);
    std::string bytes;
    if (cairo_surface_write_to_png_stream(surface.get(), output::internal::append_to_string, &bytes) !=
        CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error("Cairo cannot encode the PNG");
    }
    return bytes;
}

struct Reader {
    const std::string* bytes;
    size_t at = 0;
};

cairo_status_t read(void* closure, unsigned char* out, unsigned int length) {
    auto* r = static_cast<Reader*>(closure);
    if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
    std::copy_n(r->bytes->data() + r->at, length, out);
    r->at += length;
    return CAIRO_STATUS_SUCCESS;
}

// Cairo's reading of a PNG: premultiplied ARGB32 rows.
std::vector<unsigned char> pixels(const std::string& png) {
    Reader reader{&png};
    const Surface image(cairo_image_surface_create_from_png_stream(read, &reader), cairo_surface_destroy);
    const unsigned char* data = cairo_image_surface_get_data(image.get());
    if (!data) throw std::runtime_error("Cairo cannot read the PNG");
    const int width = cairo_image_surface_get_width(image.get()), height = cairo_image_surface_get_height(image.get());
    const int stride = cairo_image_surface_get_stride(image.get());
    std::vector<unsigned char> out;
    for (int y = 0; y < height; ++y) out.insert(out.end(), data + y * stride, data + y * stride + width * 4);
    return out;
}

int run(const Args& args) {
    core::Scene scene = core::load_scene(args.scene);
    if (!args.size.empty()) {
        const auto x = args.size.find('x');
        scene.image = {std::stoi(args.size.substr(0, x)), std::stoi(args.size.substr(x + 1))};
    }
    int first = scene.first_frame, last = scene.last_frame;
    if (!args.frames.empty()) {
        const auto colon = args.frames.find(':');
        first = std::stoi(args.frames.substr(0, colon));
        last = colon == std::string::npos ? first : std::stoi(args.frames.substr(colon + 1));
    }
    core::MeshFrames meshes(scene.mesh, first);
    core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast),
                                 {.frame_count = last - first + 1});
    output::DrawStyle style = output::brush_draw_style(scene.brush);
    if (!args.background.empty()) style.background = args.background;

    std::vector<double> draw_ms, cairo_ms, ours_ms;
    size_t cairo_bytes = 0, our_bytes = 0, frames = 0, differing = 0;
    for (int frame = first; frame <= last; ++frame) {
        const core::FrameResult result = pipeline.run(frame);
        const output::Drawing drawing = output::brush_drawing(result.lines, result.strokes, style, false);
        std::string cairo, ours;
        // Alternate which goes first, so neither always finds the caches warm.
        for (int k = 0; k < 2; ++k) {
            if ((k == 0) == (frame % 2 == 0)) {
                const auto start = std::chrono::steady_clock::now();
                cairo = cairo_png(drawing);
                cairo_ms.push_back(ms_since(start));
            } else {
                const auto start = std::chrono::steady_clock::now();
                ours = output::png_image(drawing);
                ours_ms.push_back(ms_since(start));
            }
        }
        const auto start = std::chrono::steady_clock::now();
        drawn(drawing);
        draw_ms.push_back(ms_since(start));
        cairo_bytes += cairo.size();
        our_bytes += ours.size();
        differing += pixels(cairo) != pixels(ours);
        ++frames;
    }
    std::printf("%s, %dx%d, frames %d-%d%s\n\n", args.scene.c_str(), scene.image.width, scene.image.height, first, last,
                args.background.empty() ? ", transparent" : (", background " + args.background).c_str());
    std::printf("| per frame (median) | ms | bytes (mean) |\n| --- | --- | --- |\n");
    std::printf("| drawing alone (Cairo rasterises) | %.2f | |\n", median(draw_ms));
    std::printf("| Cairo's PNG: drawing + cairo_surface_write_to_png_stream | %.2f | %zu |\n", median(cairo_ms),
                cairo_bytes / std::max<size_t>(frames, 1));
    std::printf("| png_image(): drawing + libpng | %.2f | %zu |\n", median(ours_ms),
                our_bytes / std::max<size_t>(frames, 1));
    std::printf("\nencoding alone: Cairo %.2f ms, ours %.2f ms; frames whose pixels differ: %zu of %zu\n",
                median(cairo_ms) - median(draw_ms), median(ours_ms) - median(draw_ms), differing, frames);
    return differing ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(parse(argc, argv));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_png_bench: %s\n", e.what());
        return 1;
    }
}
