// SPDX-License-Identifier: MIT
// The native part of the Python module (`inkline._inkline`): a shot opened from a file or from
// arrays, drawn frame by frame by the library's frame pipeline, and a frame's strokes and tone as
// numpy arrays and its files (polylines JSON, SVG, PDF, PNG) as the program writes them. The Python
// package (python/inkline/) is the interface users see.
#include "core/error.h"
#include "core/lines/silhouette_tracker.h"
#include "core/mesh/mesh_frames.h"
#include "core/mesh/mesh_io.h"
#include "core/pipeline/frame_pipeline.h"
#include "core/pipeline/shot.h"
#include "core/scene/scene.h"
#include "core/version.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/raycast_visibility.h"
#include "export/atomic_file.h"
#include "export/drawing.h"
#include "export/json.h"
#include "export/pdf.h"
#include "export/png.h"
#include "export/svg.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace py = pybind11;
namespace core = inkline::core;
namespace output = inkline::output;
using inkline::InputError;

namespace {

// --- arrays -------------------------------------------------------------------------------

template <typename T>
py::array_t<T> array_of(const std::vector<T>& values) {
    py::array_t<T> a(py::ssize_t(values.size()));
    if (!values.empty()) std::memcpy(a.mutable_data(), values.data(), values.size() * sizeof(T));
    return a;
}

// n x D doubles from n glm vectors of D doubles.
template <typename Vec>
py::array_t<double> rows_of(const std::vector<Vec>& points) {
    constexpr py::ssize_t kColumns = Vec::length();
    py::array_t<double> a({py::ssize_t(points.size()), kColumns});
    double* out = a.mutable_data();
    for (const Vec& p : points) {
        for (py::ssize_t k = 0; k < kColumns; ++k) *out++ = p[int(k)];
    }
    return a;
}

py::dict camera_dict(const core::Camera& c) {
    py::dict d;
    d["eye"] = py::make_tuple(c.eye.x, c.eye.y, c.eye.z);
    d["target"] = py::make_tuple(c.target.x, c.target.y, c.target.z);
    d["up"] = py::make_tuple(c.up.x, c.up.y, c.up.z);
    if (c.ortho_height) {
        d["ortho_height"] = *c.ortho_height;
    } else {
        d["fov_y_deg"] = c.fov_y_deg;
    }
    d["near"] = c.near;
    d["far"] = c.far;
    return d;
}

// --- options ------------------------------------------------------------------------------

std::unique_ptr<core::OcclusionSource> occlusion_for(const std::string& visibility) {
    if (visibility == "auto") {
        return core::make_cpu_occlusion(core::raycast_available() ? core::VisibilityMode::kRaycast
                                                                  : core::VisibilityMode::kExact);
    }
    const core::VisibilityMode mode = core::parse_visibility_mode(visibility, "visibility");
    if (mode == core::VisibilityMode::kGl) {
        throw InputError("visibility 'gl': the Python module draws with raycast or exact visibility (the program has gl)");
    }
    return core::make_cpu_occlusion(mode);
}

std::optional<core::ImageSize> size_of(const std::optional<std::pair<int, int>>& size, int max_side) {
    if (!size) return std::nullopt;
    const auto [w, h] = *size;
    if (w < 1 || h < 1 || w > max_side || h > max_side) {
        throw InputError("size (" + std::to_string(w) + ", " + std::to_string(h) + "): each side must be 1.." +
                         std::to_string(max_side) + " px");
    }
    return core::ImageSize{w, h};
}

// tone="stipple", "hatch", "crosshatch" or "none", as --tone takes it.
std::optional<core::ToneMode> tone_mode_of(const std::optional<std::string>& text) {
    if (!text) return std::nullopt;
    if (const auto mode = core::tone_mode_from_name(*text)) return mode;
    throw InputError("tone '" + inkline::quote_value(*text) + "': expected stipple, hatch, crosshatch or none");
}

std::optional<core::ContourMode> contour_of(const std::optional<std::string>& text) {
    if (!text) return std::nullopt;
    if (const auto mode = core::contour_mode_from_name(*text)) return mode;
    throw InputError("contour '" + inkline::quote_value(*text) + "': expected mesh or smooth");
}

// Runs `open`, saying the module's argument where a reader's message names the program's option.
template <typename Open>
void with_python_names(Open open) {
    try {
        open();
    } catch (const InputError& e) {
        std::string message = e.what();
        if (const size_t at = message.find("--max-faces"); at != std::string::npos) message.replace(at, 11, "max_faces=");
        throw InputError(message);
    }
}

// --- a frame ------------------------------------------------------------------------------

// One drawn frame, with what its files need from the shot.
struct Frame {
    core::FrameResult result;
    output::DrawStyle style;
    core::ToneOptions tone;     // the scene's: the colour and opacity of the tone's dots
    std::string title;          // the PDF's: the mesh file's stem
    std::string creation_date;  // the PDF's (reproducible)

    output::Drawing drawing(const std::string& path_format, bool centerline, const std::optional<std::string>& background) const {
        output::DrawStyle s = style;
        s.path_format = output::parse_path_format(path_format, "path_format");
        if (background) {
            output::parse_color(*background, "background");
            s.background = *background;
        }
        output::Drawing d = output::brush_drawing(result.lines, result.strokes, s, centerline);
        d.tone = output::tone_layer(result.tone, tone);
        return d;
    }
};

output::LayerGrouping layer_grouping(const std::string& layers) {
    if (layers == "kind") return output::LayerGrouping::kKind;
    if (layers == "object") return output::LayerGrouping::kObject;
    if (layers == "style") return output::LayerGrouping::kStyle;
    throw InputError("layers '" + inkline::quote_value(layers) + "': expected kind, object or style");
}

output::SvgOptions svg_options(const std::string& layers) {
    output::SvgOptions o;
    o.layers = layer_grouping(layers);
    return o;
}

py::list strokes_of(const Frame& frame) {
    const core::FrameStrokes& fs = frame.result.strokes;
    const std::vector<core::MeshObject>& objects = frame.result.lines.objects;
    py::list out;
    for (const core::Stroke& s : fs.strokes) {
        const core::StrokeGeometry& g = s.geometry;
        py::dict d;
        d["id"] = s.id;
        d["kind"] = core::line_kind_name(g.kind);
        d["closed"] = g.closed;
        d["visible"] = g.visible;
        d["drawn"] = s.drawn;
        d["ends"] = py::make_tuple(core::stroke_end_name(g.ends[0]), core::stroke_end_name(g.ends[1]));
        d["points"] = rows_of(g.points_px);
        d["world"] = rows_of(g.points_world);
        d["edges"] = array_of(s.faces.empty() ? g.edges : s.faces);
        d["u"] = array_of(s.u);
        d["intensity"] = array_of(s.intensity);
        d["width"] = array_of(s.width);
        py::list outline;
        for (const core::Ring& ring : s.outline) outline.append(rows_of(ring));
        d["outline"] = outline;
        std::vector<int64_t> hidden;
        for (size_t k = 0; k < g.bridged.size(); ++k) {
            if (g.bridged[k]) hidden.push_back(int64_t(k));
        }
        d["hidden_segments"] = array_of(hidden);
        d["object"] = g.object >= 0 && size_t(g.object) < objects.size() ? py::object(py::str(objects[size_t(g.object)].name)) : py::none();
        d["group"] = s.group;
        d["level"] = s.level;
        d["parent"] = s.parent >= 0 ? py::object(py::int_(s.parent)) : py::none();
        d["order"] = s.order;
        d["style"] = s.style != 0 && s.style < fs.styles.size() ? py::object(py::str(fs.styles[s.style].name)) : py::none();
        out.append(d);
    }
    return out;
}

// The frame's tone as arrays, one row per dot; None without tone.
py::object tone_of(const Frame& frame) {
    const core::FrameTone& tone = frame.result.tone;
    if (tone.mode == core::ToneMode::kNone) return py::none();
    std::vector<glm::dvec2> points;
    std::vector<glm::dvec3> world, barycentric;
    std::vector<uint32_t> faces, inks;
    std::vector<uint64_t> samples;
    std::vector<double> radius, value;
    for (const core::Dot& d : tone.dots) {
        inks.push_back(d.ink);
        points.push_back(d.point_px);
        world.push_back(d.point_world);
        barycentric.push_back(d.barycentric);
        faces.push_back(d.face);
        samples.push_back(d.sample);
        radius.push_back(d.radius_px);
        value.push_back(d.tone);
    }
    const auto stipple_stats = [](const core::StippleStats& s) {
        py::dict d;
        d["samples"] = s.samples;
        d["considered"] = s.considered;
        d["wanted"] = s.wanted;
        d["inked"] = s.inked;
        d["occluded"] = s.occluded;
        return d;
    };
    const auto hatch_stats = [](const core::HatchStats& s) {
        py::dict d;
        d["faces"] = s.faces;
        d["segments"] = s.segments;
        d["points"] = s.points;
        d["occluded"] = s.occluded;
        d["inked"] = s.inked;
        return d;
    };
    const bool stipple = tone.mode == core::ToneMode::kStipple;
    const py::dict stats = stipple ? stipple_stats(tone.stipple_stats) : hatch_stats(tone.hatch_stats);
    // Hatches: one dict of arrays each, as the JSON lists them.
    py::list hatches;
    for (const core::Hatch& h : tone.hatches) {
        py::dict hatch;
        hatch["family"] = h.family;
        hatch["plane"] = h.plane;
        hatch["level"] = h.level;
        hatch["points"] = rows_of(h.points_px);
        hatch["world"] = rows_of(h.points_world);
        hatch["edges"] = array_of(h.edges);
        hatch["faces"] = array_of(h.faces);
        hatch["width"] = array_of(h.width_px);
        hatch["ink"] = h.ink;
        hatches.append(hatch);
    }
    py::dict out;
    out["mode"] = core::tone_mode_name(tone.mode);
    out["points"] = rows_of(points);
    out["world"] = rows_of(world);
    out["faces"] = array_of(faces);
    out["barycentric"] = rows_of(barycentric);
    out["radius"] = array_of(radius);
    out["tone"] = array_of(value);
    out["samples"] = array_of(samples);
    out["ink"] = array_of(inks);
    out["hatches"] = hatches;
    // The inks the marks are drawn in where objects have inks of their own (scene "objects" and
    // "styles"), as the JSON's tone.inks; empty: the scene's alone.
    py::list ink_list;
    for (const core::ToneInk& ink : tone.inks) {
        py::dict d;
        d["color"] = core::color_hex(ink.color);
        d["opacity"] = ink.opacity;
        d["style"] = ink.style;
        ink_list.append(d);
    }
    out["inks"] = ink_list;
    out["stats"] = stats;
    // Where objects have modes of their own: the modes drawn, and the other kind's stats.
    py::list modes;
    for (const core::ToneMode m : tone.modes) modes.append(core::tone_mode_name(m));
    out["modes"] = modes;
    if (stipple && (tone.has(core::ToneMode::kHatch) || tone.has(core::ToneMode::kCrosshatch))) {
        out["hatch_stats"] = hatch_stats(tone.hatch_stats);
    }
    if (!stipple && tone.has(core::ToneMode::kStipple)) out["stipple_stats"] = stipple_stats(tone.stipple_stats);
    return out;
}

// --- a shot -------------------------------------------------------------------------------

// An in-code animation: one set of positions per frame over one topology.
class ArrayAnimation final : public core::AnimatedMesh {
  public:
    ArrayAnimation(core::Mesh rest, std::vector<std::vector<glm::vec3>> frames, int first)
        : rest_(std::move(rest)), frames_(std::move(frames)), first_(first) {}
    const core::Mesh& rest() const override { return rest_; }
    bool deforms() const override { return frames_.size() > 1; }
    void positions_at(int frame, std::vector<glm::vec3>& r_positions) const override {
        const long k = long(frame) - first_;
        if (k < 0 || size_t(k) >= frames_.size()) {
            throw InputError("vertices: no positions for frame " + std::to_string(frame) + " (frames " + std::to_string(first_) +
                             ".." + std::to_string(first_ + long(frames_.size()) - 1) + ")");
        }
        r_positions = frames_[size_t(k)];
    }

  private:
    core::Mesh rest_;
    std::vector<std::vector<glm::vec3>> frames_;
    int first_;
};

struct ShotArgs {
    std::optional<std::pair<int, int>> frames;
    std::optional<std::pair<int, int>> size;
    bool hidden = false;
    std::optional<std::string> contour;
    std::string visibility = "auto";
    std::string tracker = "incremental";
    std::optional<std::string> tone;  // "stipple" or "none": overrides the scene's tone mode
};

class Shot {
  public:
    // A scene, mesh or glTF file.
    Shot(const std::string& path, const ShotArgs& args, int gltf_scene, const std::string& animation, const std::string& camera,
         double fps, size_t max_faces, int max_image_side) {
        request_ = {.input = path,
                    .max_image_side = max_image_side,
                    .max_faces = max_faces,
                    .gltf_scene = gltf_scene,
                    .animation = animation,
                    .camera = camera,
                    .fps = fps,
                    .names = {"gltf_scene", "animation", "camera", "fps", "max_faces"}};
        with_python_names([&] {
            shot_ = core::open_shot(request_);
            start(args, nullptr);
        });
    }

    // Scene JSON text (its mesh key names the arrays) and the mesh as arrays: positions of
    // shape (V, 3), or (F, V, 3) for frames first.. of a deforming mesh; triangles (T, 3).
    Shot(const std::string& scene_json, const std::string& name, py::array_t<double, py::array::c_style | py::array::forcecast> vertices,
         py::array_t<int64_t, py::array::c_style | py::array::forcecast> faces, const ShotArgs& args, size_t max_faces,
         int max_image_side) {
        request_.max_faces = max_faces;
        request_.max_image_side = max_image_side;
        request_.names.max_faces = "max_faces";
        shot_.scene = core::parse_scene(scene_json, name, max_image_side);
        shot_.from_scene = true;
        if (shot_.scene.gltf || shot_.scene.mesh.is_sequence) throw InputError(name + ": key 'mesh': the mesh is given as arrays");
        shot_.first_frame = shot_.scene.first_frame;
        shot_.last_frame = shot_.scene.last_frame;
        if (faces.ndim() != 2 || faces.shape(1) != 3) throw InputError("faces: expected an array of shape (T, 3)");
        const std::span<const int64_t> indices(faces.data(), size_t(faces.size()));
        if (vertices.ndim() == 2) {
            if (vertices.shape(1) != 3) throw InputError("vertices: expected an array of shape (V, 3) or (F, V, 3)");
            const std::span<const double> xyz(vertices.data(), size_t(vertices.size()));
            start(args, std::make_unique<core::MeshFrames>(
                            core::mesh_from_arrays(xyz, indices, "vertices", "faces", {.max_faces = max_faces})));
            return;
        }
        if (vertices.ndim() != 3 || vertices.shape(2) != 3 || vertices.shape(0) < 1) {
            throw InputError("vertices: expected an array of shape (V, 3) or (F, V, 3)");
        }
        const size_t frame_count = size_t(vertices.shape(0)), per_frame = size_t(vertices.shape(1)) * 3;
        if (long(frame_count) != long(shot_.last_frame) - shot_.first_frame + 1) {
            throw InputError("vertices: " + std::to_string(frame_count) + " frames of positions for frames " +
                             std::to_string(shot_.first_frame) + ".." + std::to_string(shot_.last_frame) + " (one set per frame)");
        }
        std::vector<std::vector<glm::vec3>> frames(frame_count);
        core::Mesh rest;
        for (size_t f = 0; f < frame_count; ++f) {
            const std::span<const double> xyz(vertices.data() + f * per_frame, per_frame);
            core::Mesh m = core::mesh_from_arrays(xyz, indices, "vertices[" + std::to_string(f) + "]", "faces",
                                                  {.max_faces = max_faces});
            frames[f] = m.positions;
            if (f == 0) rest = std::move(m);
        }
        auto animation = std::make_shared<ArrayAnimation>(std::move(rest), std::move(frames), shot_.first_frame);
        start(args, std::make_unique<core::MeshFrames>(std::move(animation), name));
    }

    int first_frame() const { return first_; }
    int last_frame() const { return last_; }
    const std::vector<std::string>& warnings() const { return warnings_; }

    std::shared_ptr<Frame> render(int frame) {
        // Cameras and meshes were checked for these frames only.
        if (frame < first_ || frame > last_) {
            throw InputError("frame " + std::to_string(frame) + ": outside the shot's frames " + std::to_string(first_) + ".." +
                             std::to_string(last_) + " (open it with frames=(first, last))");
        }
        auto out = std::make_shared<Frame>();
        {
            py::gil_scoped_release release;
            std::lock_guard lock(mutex_);
            out->result = pipeline_->run(frame);
        }
        out->style = style_;
        out->tone = shot_.scene.tone;
        out->title = title_;
        out->creation_date = creation_date_;
        out->result.mesh = nullptr;  // valid only until the next run
        out->result.table = nullptr;  // valid only as long as the shot, which a frame may outlive
        return out;
    }

  private:
    // Frames, cameras, meshes and the pipeline; `meshes` given for arrays, else loaded.
    void start(const ShotArgs& args, std::unique_ptr<core::MeshFrames> meshes) {
        const core::TrackerMode tracker = core::parse_tracker_mode(args.tracker, "tracker");
        if (const std::optional<core::ToneMode> tone = tone_mode_of(args.tone)) shot_.scene.tone.mode = *tone;
        first_ = shot_.first_frame;
        last_ = shot_.last_frame;
        if (args.frames) {
            std::tie(first_, last_) = *args.frames;
            if (first_ > last_) {
                throw InputError("frames (" + std::to_string(first_) + ", " + std::to_string(last_) + "): the first is after the last");
            }
        }
        const std::optional<core::ImageSize> size = size_of(args.size, request_.max_image_side);
        core::settle_cameras(shot_, first_, last_, size);
        const core::ShotOverrides overrides{.size = size, .hidden = args.hidden, .contour = contour_of(args.contour)};
        if (meshes) {
            core::apply_overrides(shot_.scene, overrides);
            meshes_ = std::move(meshes);
        } else {
            meshes_ = core::load_meshes(shot_, request_, first_, overrides);
        }
        warnings_ = meshes_->warnings();
        std::unique_ptr<core::OcclusionSource> occlusion = occlusion_for(args.visibility);
        const std::string reason = args.visibility == "auto" ? "the Python module draws on the CPU" : "asked for";
        pipeline_ = std::make_unique<core::FramePipeline>(
            shot_.scene, *meshes_, std::move(occlusion),
            core::PipelineOptions{.tracker = tracker, .frame_count = last_ - first_ + 1, .visibility_reason = reason});
        style_ = output::brush_draw_style(shot_.scene.brush);
        title_ = shot_.scene.mesh.path.stem().string();
        creation_date_ = output::reproducible_creation_date(request_.input.empty() ? shot_.scene.mesh.path : request_.input);
    }

    core::ShotRequest request_;
    core::Shot shot_;
    std::unique_ptr<core::MeshFrames> meshes_;
    std::unique_ptr<core::FramePipeline> pipeline_;
    std::mutex mutex_;  // one frame at a time: the pipeline carries state between frames
    output::DrawStyle style_;
    std::string title_, creation_date_;
    std::vector<std::string> warnings_;
    int first_ = 1, last_ = 1;
};

}  // namespace

PYBIND11_MODULE(_inkline, m) {
    m.doc() = "inkline's native part; use the inkline package";
    m.attr("__version__") = std::string(inkline::kVersion);

    py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
    py::register_exception<inkline::OutputError>(m, "OutputError", PyExc_OSError);
    py::register_exception<inkline::InternalError>(m, "InternalError", PyExc_RuntimeError);

    py::class_<ShotArgs>(m, "ShotArgs")
        .def(py::init<>())
        .def_readwrite("frames", &ShotArgs::frames)
        .def_readwrite("size", &ShotArgs::size)
        .def_readwrite("hidden", &ShotArgs::hidden)
        .def_readwrite("contour", &ShotArgs::contour)
        .def_readwrite("visibility", &ShotArgs::visibility)
        .def_readwrite("tracker", &ShotArgs::tracker)
        .def_readwrite("tone", &ShotArgs::tone);

    py::class_<Frame, std::shared_ptr<Frame>>(m, "Frame")
        .def_property_readonly("number", [](const Frame& f) { return f.result.lines.frame; })
        .def_property_readonly("image", [](const Frame& f) { return py::make_tuple(f.result.lines.image.width, f.result.lines.image.height); })
        .def_property_readonly("camera", [](const Frame& f) { return camera_dict(f.result.lines.camera); })
        .def_property_readonly("warnings", [](const Frame& f) { return f.result.warnings; })
        .def("strokes", &strokes_of)
        .def("tone", &tone_of)
        .def("json", [](const Frame& f) {
            py::gil_scoped_release release;
            return output::polylines_json(f.result.lines, &f.result.strokes, &f.result.tone);
        })
        .def("svg", [](const Frame& f, const std::string& layers, const std::string& path_format, bool centerline,
                       const std::optional<std::string>& background) {
                 const output::SvgOptions options = svg_options(layers);
                 py::gil_scoped_release release;
                 return output::svg_document(f.drawing(path_format, centerline, background), options);
             },
             py::arg("layers"), py::arg("path_format"), py::arg("centerline"), py::arg("background"))
        .def("png", [](const Frame& f, const std::string& path_format, bool centerline, const std::optional<std::string>& background) {
                 const core::ImageSize& image = f.result.lines.image;
                 output::check_png_size(image.width, image.height);
                 std::string bytes;
                 {
                     py::gil_scoped_release release;
                     bytes = output::png_image(f.drawing(path_format, centerline, background));
                 }
                 return py::bytes(bytes);
             },
             py::arg("path_format"), py::arg("centerline"), py::arg("background"))
        .def("pdf", [](const Frame& f, const std::optional<std::string>& page, double margin_mm, double dpi,
                       const std::string& path_format, bool centerline, const std::optional<std::string>& background,
                       const std::string& layers) {
                 output::PdfOptions options;
                 options.layers = layer_grouping(layers);
                 options.page = page ? std::optional(output::parse_page_size(*page)) : std::nullopt;
                 options.margin_mm = margin_mm;
                 options.dpi = dpi;
                 if (!(dpi > 0.0 && dpi <= 10000.0)) throw InputError("dpi: must be between 0 and 10000");
                 if (!(margin_mm >= 0.0 && margin_mm < 1000.0)) throw InputError("margin_mm: must be 0..1000 mm");
                 options.title = f.title;
                 options.creation_date = f.creation_date;
                 output::check_pdf_page(options, f.result.lines.image.width, f.result.lines.image.height);
                 std::string bytes;
                 {
                     py::gil_scoped_release release;
                     output::PdfDocument doc(options);
                     doc.add_page(f.drawing(path_format, centerline, background));
                     bytes = doc.finish();
                 }
                 return py::bytes(bytes);
             },
             py::arg("page"), py::arg("margin_mm"), py::arg("dpi"), py::arg("path_format"), py::arg("centerline"),
             py::arg("background"), py::arg("layers"));

    py::class_<Shot>(m, "Shot")
        .def(py::init<const std::string&, const ShotArgs&, int, const std::string&, const std::string&, double, size_t, int>(),
             py::arg("path"), py::arg("args"), py::arg("gltf_scene"), py::arg("animation"), py::arg("camera"), py::arg("fps"),
             py::arg("max_faces"), py::arg("max_image_side"))
        .def(py::init<const std::string&, const std::string&, py::array_t<double, py::array::c_style | py::array::forcecast>,
                      py::array_t<int64_t, py::array::c_style | py::array::forcecast>, const ShotArgs&, size_t, int>(),
             py::arg("scene_json"), py::arg("name"), py::arg("vertices"), py::arg("faces"), py::arg("args"), py::arg("max_faces"),
             py::arg("max_image_side"))
        .def_property_readonly("first_frame", &Shot::first_frame)
        .def_property_readonly("last_frame", &Shot::last_frame)
        .def_property_readonly("warnings", &Shot::warnings)
        .def("render", &Shot::render, py::arg("frame"));

    m.def("write_file", [](const std::string& path, py::bytes contents) {
              std::string data = contents;
              py::gil_scoped_release release;
              output::write_file_atomically(path, data);
          },
          py::arg("path"), py::arg("contents"), "Writes the whole file or nothing (a temporary renamed into place).");
}
