// SPDX-License-Identifier: MIT
#include "core/pipeline/frame_pipeline.h"

#include "core/error.h"
#include "core/internal/view_clip.h"
#include "core/internal/worker.h"
#include "core/lines/chaining.h"
#include "core/lines/features.h"
#include "core/pipeline/stopwatch.h"
#include "core/visibility/visibility.h"

#include <glm/matrix.hpp>
#include <glm/vector_relational.hpp>

#include <exception>
#include <functional>
#include <new>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace inkline::core {
namespace {

// A hash of the mesh's positions, bit for bit.
size_t positions_hash(const Mesh& mesh) {
    const std::string_view bytes(reinterpret_cast<const char*>(mesh.positions.data()),
                                 mesh.positions.size() * sizeof(glm::vec3));
    return std::hash<std::string_view>{}(bytes);
}

bool inside(const Bounds& b, const glm::dvec3& p) {
    return glm::all(glm::greaterThanEqual(p, b.min)) && glm::all(glm::lessThanEqual(p, b.max));
}

// True when no point of the box can be seen: its eight corners all lie beyond one of the view's
// planes (the near plane or one of the image's sides).
bool out_of_view(const Bounds& b, const Projection& projection) {
    for (int plane = 0; plane < 5; ++plane) {
        bool all_beyond = true;
        for (int k = 0; k < 8 && all_beyond; ++k) {
            const glm::dvec3 corner(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y, k & 4 ? b.max.z : b.min.z);
            all_beyond = internal::inside_view_by(projection, plane, projection.clip(corner)) < 0.0;
        }
        if (all_beyond) return true;
    }
    return false;
}

// Times the steps of a run, one after another: each call returns the ms since the last (or since
// construction) and tells PipelineOptions::step_done, when there is one, that the step ended.
class StepClock {
  public:
    explicit StepClock(const std::function<void(const char*)>& done) : done_(done) {}
    double operator()(const char* name) {
        const double ms = laps_.lap_ms();
        if (done_) done_(name);
        return ms;
    }

  private:
    Stopwatch laps_;
    const std::function<void(const char*)>& done_;
};

}  // namespace

FramePipeline::FramePipeline(const Scene& scene, MeshFrames& meshes, std::unique_ptr<OcclusionSource> occlusion,
                             PipelineOptions options)
    : scene_(scene), meshes_(meshes), occlusion_(std::move(occlusion)), options_(std::move(options)) {
    INKLINE_CHECK(occlusion_ != nullptr);
    const long long frames =
        options_.frame_count > 0 ? options_.frame_count : (long long)scene_.last_frame - scene_.first_frame + 1;
    tracker_mode_ = frames > 1 ? options_.tracker : TrackerMode::kBrute;
    // The next frame's lines are found while a frame is drawn, unless a caller times the steps.
    // That touches nothing the frame reads: a deforming mesh's next positions go to a second
    // buffer (MeshFrames::at). Their visibility too, unless it is a GL depth test, which runs
    // where its context was made; the occlusion test of a deforming mesh is brought up to date
    // for the next frame, so there the tone, which queries it, comes first.
    lines_ahead_ = frames > 1 && !options_.step_done;
    visibility_ahead_ = occlusion_->mode() != VisibilityMode::kGl;
    ahead_after_tone_ = meshes_.deforming() && visibility_ahead_ && scene_.tone.mode != ToneMode::kNone;
    for (const MeshObject& object : meshes_.objects()) object_kinds_.push_back(object_line_kinds(scene_, object.name));
    // Intersection lines need an object that draws them, and a second object or self intersections.
    bool any_crossing_object = object_kinds_.empty() && scene_.lines.intersection;
    for (const auto& kinds : object_kinds_) any_crossing_object |= kinds[size_t(LineKind::kIntersection)];
    trace_intersections_ = any_crossing_object && (object_kinds_.size() > 1 || scene_.lines.self_intersection);
}

int32_t FramePipeline::object_of(std::span<const uint32_t> edges) const {
    if (object_kinds_.empty() || edges.empty()) return -1;
    return int32_t(meshes_.object_of_face(meshes_.edges().faces_of(edges.front()).front()));
}

FramePipeline::~FramePipeline() = default;

FramePipeline::FoundLines FramePipeline::find_lines(int frame, bool with_visibility) {
    StepClock step(options_.step_done);
    FoundLines found;
    found.lines.frame = frame;
    found.lines.image = scene_.image;
    found.lines.light = scene_.light;
    const Mesh& mesh = meshes_.at(frame);
    found.mesh = &mesh;
    found.load_ms = step("load");
    const EdgeTable& table = meshes_.edges();

    // The camera, fitted to the object's bounds where it moves (object space: extraction and
    // occlusion move the eye instead of the mesh).
    found.world_from_object = world_from_object_at(scene_, frame);
    found.change = first_lines_             ? MeshChange::kTopology
                   : meshes_.deforming()    ? MeshChange::kPositions
                                            : MeshChange::kNone;
    first_lines_ = false;
    if (found.change != MeshChange::kNone) object_bounds_ = bounds_of(mesh.positions);
    const Bounds& object_bounds = object_bounds_;
    found.object_bounds = object_bounds;
    found.lines.camera = camera_at(scene_, frame, transformed(object_bounds, found.world_from_object));
    const Projection projection(found.lines.camera, scene_.image, found.world_from_object);
    if (!warned_inside_ && !projection.orthographic() && inside(object_bounds, projection.eye_object().xyz)) {
        warned_inside_ = true;
        found.warnings.push_back("frame " + std::to_string(frame) +
                                 ": the camera is inside the mesh's bounds; lines may be hidden");
    }
    if (!warned_outside_ && object_bounds.valid && out_of_view(object_bounds, projection)) {
        warned_outside_ = true;
        found.warnings.push_back("frame " + std::to_string(frame) +
                                 ": the mesh is wholly outside the camera's view; nothing is drawn");
    }
    if (with_visibility && holds_lines(found)) {
        take_held_lines(found, true);
        found.visibility_ms = step("visibility");
        return found;
    }

    // Feature edges and chains. Smooth contours replace the silhouette edges.
    double tracker_build_ms = 0.0;
    FeatureEdges features;
    const bool smooth = scene_.lines.silhouette && scene_.lines.contour == ContourMode::kSmooth;
    LineOptions edge_lines = scene_.lines;
    if (smooth) edge_lines.silhouette = false;
    if (tracker_mode_ == TrackerMode::kBrute) {
        features = extract_feature_edges(mesh, table, projection.eye_object(), edge_lines);
    } else if (smooth && !meshes_.deforming()) {
        // Boundaries and creases alone, of a mesh that does not change: found once.
        if (!still_edges_) {
            features = extract_feature_edges(mesh, table, projection.eye_object(), edge_lines);
            still_edges_ = features.edges;
        } else {
            features.edges = *still_edges_;
        }
    } else {
        if (!tracker_) {
            tracker_.emplace(table, mesh, TrackerOptions{.deforming = meshes_.deforming()});
            tracker_build_ms = step("tracker build");
        }
        features = tracker_->update(mesh, projection.eye_object(), edge_lines);
    }
    const std::vector<Chain>* contours = nullptr;
    if (smooth) {
        if (!smooth_) {
            smooth_.emplace(mesh, table,
                            SmoothContourOptions{.mode = tracker_mode_,
                                                 .deforming = meshes_.deforming(),
                                                 .crease_angle_deg = scene_.lines.crease_angle_deg});
        }
        contours = &smooth_->trace(mesh, table, projection.eye_object());
    }
    // Intersection lines, where objects cross (and, with lines.self_intersection, where one
    // crosses itself); retraced only when the mesh moved.
    const std::vector<Chain>* crossings = nullptr;
    if (trace_intersections_) {
        if (!intersections_) {
            intersections_.emplace(IntersectionOptions{.between_objects = meshes_.objects().size() > 1,
                                                       .self = scene_.lines.self_intersection});
        }
        crossings = &intersections_->trace(mesh, table, meshes_.face_objects(), found.change != MeshChange::kNone);
    }
    found.extract_ms = tracker_build_ms + step("extract");
    found.chains = chain_feature_edges(features, table);
    // Crease edges on the outline are drawn with the smooth contours, not as creases.
    if (contours) found.chains = cut_crease_outline(std::move(found.chains), smooth_->crease_outline(), mesh, table);
    if (contours) found.chains.insert(found.chains.end(), contours->begin(), contours->end());
    if (crossings) {
        const size_t first = found.chains.size();
        found.chains.insert(found.chains.end(), crossings->begin(), crossings->end());
        // With smooth contours, the back of a closed surface hides the intersection lines on it
        // where its contour says it turns away, so that they end where that contour crosses them.
        if (contours) {
            for (size_t c = first; c < found.chains.size(); ++c) smooth_->set_facing(mesh, found.chains[c]);
        }
    }
    found.chain_ms = step("chain");

    // What the stats need of the tracers, read now: the next frame's lines may be traced while
    // this frame is drawn.
    FrameStats& stats = found.lines.stats;
    stats.faces = mesh.triangles.size();
    stats.edges = table.edge_count();
    stats.edges_tested = features.edges_tested;
    stats.faces_tested = features.faces_tested;
    stats.feature_edges = features.count_by_kind();
    stats.intersections = crossings != nullptr;
    if (crossings) stats.feature_edges[size_t(LineKind::kIntersection)] = intersections_->stats().segments;
    if (contours) {
        // Smooth contours: the faces whose corner signs were compared, and the faces crossed.
        stats.faces_tested += smooth_->stats().faces_tested;
        stats.feature_edges[size_t(LineKind::kSilhouette)] = smooth_->stats().segments;
    }
    stats.silhouette_edges = stats.feature_edges[size_t(LineKind::kSilhouette)];
    found.smooth_contours = contours != nullptr;
    if (with_visibility) find_visible(found);
    return found;
}

void FramePipeline::find_visible(FoundLines& found) {
    StepClock step(options_.step_done);
    const Mesh& mesh = *found.mesh;
    const EdgeTable& table = meshes_.edges();
    FrameLines& result = found.lines;
    const Projection projection(result.camera, scene_.image, found.world_from_object);

    // Visibility. Occluded parts are always found (the samples are classified anyway): the
    // stroke stage bridges short ones. Without lines.hidden they stay out of the output.
    if (holds_lines(found)) {
        take_held_lines(found, false);
        found.visibility_ms = step("visibility");
        return;
    }
    held_lines_.reset();
    found.occlusion = &occlusion_->prepare(mesh, table, projection, found.change);
    const double occlusion_ms = step("occlusion");
    result.polylines = split_by_visibility(found.chains, mesh, table, projection, *found.occlusion, {.keep_hidden = true});
    found.chains = std::vector<Chain>();
    if (!object_kinds_.empty()) {
        // Each line's object; holdouts and the kinds an object turns off draw nothing, though
        // their faces still hide other lines.
        result.objects = meshes_.objects();
        for (Polyline& line : result.polylines) line.object = object_of(line.edges);
        // An intersection line is drawn when both of its objects draw the kind.
        const auto draws = [&](const Polyline& line) {
            if (line.object < 0) return true;
            const size_t kind = size_t(line.kind);
            if (!object_kinds_[size_t(line.object)][kind]) return false;
            return line.crossing_faces.empty() ||
                   object_kinds_[meshes_.object_of_face(line.crossing_faces.front())][kind];
        };
        std::erase_if(result.polylines, [&](const Polyline& line) { return !draws(line); });
        for (size_t i = 0; i < result.polylines.size(); ++i) result.polylines[i].id = uint32_t(i);
    }
    if (!scene_.lines.hidden) set_aside_occluded(result);
    if (!meshes_.deforming() && next_may_hold(result.frame, result, found.world_from_object, found.object_bounds)) {
        held_lines_ = HeldLines{.polylines = result.polylines,
                                .occluded = result.occluded,
                                .objects = result.objects,
                                .stats = result.stats,
                                .smooth_contours = found.smooth_contours,
                                .camera = result.camera,
                                .world_from_object = found.world_from_object,
                                .occlusion = found.occlusion};
    }
    found.visibility_ms = occlusion_ms + step("visibility");
}

bool FramePipeline::holds_lines(const FoundLines& found) const {
    return held_lines_ && !meshes_.deforming() && held_lines_->camera == found.lines.camera &&
           held_lines_->world_from_object == found.world_from_object;
}

void FramePipeline::take_held_lines(FoundLines& found, bool with_stats) const {
    FrameLines& lines = found.lines;
    found.occlusion = held_lines_->occlusion;
    lines.polylines = held_lines_->polylines;
    lines.occluded = held_lines_->occluded;
    lines.objects = held_lines_->objects;
    found.chains = std::vector<Chain>();
    if (with_stats) {
        lines.stats = held_lines_->stats;
        lines.stats.edges_tested = 0;
        lines.stats.faces_tested = 0;
        found.smooth_contours = held_lines_->smooth_contours;
    }
}

FramePipeline::FoundLines FramePipeline::lines_of(int frame) {
    if (ahead_worker_ && ahead_worker_->forked()) {
        // A forked process: the worker thread is not here, and what it was finding never comes.
        // The tracers it may have been updating are built again.
        ahead_ = {};
        ahead_worker_.reset();
        tracker_.reset();
        smooth_.reset();
        intersections_.reset();
    }
    if (ahead_.valid()) {
        const int ahead_frame = ahead_frame_;
        std::future<FoundLines> ahead = std::move(ahead_);
        if (ahead_frame == frame) return ahead.get();  // an error finding them is this frame's
        try {
            ahead.get();  // not the frame asked for: finished, then dropped
        } catch (...) {
        }
    }
    return find_lines(frame, true);
}

void FramePipeline::find_lines_ahead(int frame) {
    if (!lines_ahead_ || frame > scene_.last_frame) return;
    try {
        if (!ahead_worker_) ahead_worker_ = std::make_unique<internal::Worker>();
        ahead_ = ahead_worker_->submit([this, frame] { return find_lines(frame, visibility_ahead_); });
        ahead_frame_ = frame;
    } catch (const std::system_error&) {
        // No thread to be had (limits): the frame's lines are found when it is drawn.
    } catch (const std::bad_alloc&) {
        // Nor the memory to start one: the same.
    }
}

FrameResult FramePipeline::run(int frame) {
    FoundLines found = lines_of(frame);
    if (!ahead_after_tone_) find_lines_ahead(frame + 1);

    StepClock step(options_.step_done);
    FrameResult out;
    out.warnings = std::move(found.warnings);
    if (!found.occlusion) find_visible(found);  // where it must run on this thread (a GL context)
    out.lines = std::move(found.lines);
    FrameLines& result = out.lines;
    const Mesh& mesh = *found.mesh;
    const EdgeTable& table = meshes_.edges();
    const glm::dmat4& world_from_object = found.world_from_object;
    const MeshChange change = found.change;
    const Projection projection(result.camera, scene_.image, world_from_object);
    const Occlusion& occlusion = *found.occlusion;

    // Strokes, coherent with the last frame's; a held frame draws the strokes the last one drew.
    if (change != MeshChange::kNone) stroke_normals_.clear();
    const bool moving = change != MeshChange::kNone;
    const bool held = held_ && change != MeshChange::kTopology && held_->camera == result.camera &&
                      held_->light == result.light && held_->world_from_object == world_from_object &&
                      held_->polylines == result.polylines && held_->occluded == result.occluded &&
                      (!moving || held_->positions_hash == positions_hash(mesh));
    if (held) {
        out.strokes = held_->strokes;
        out.strokes.frame = frame;
        StrokeStats& s = out.strokes.stats;
        s.inherited = out.strokes.strokes.size();
        s.inherited_length_px = s.visible_length_px;
    } else {
        out.strokes = build_strokes(
            result, mesh, table, projection, scene_.brush, coherence_, scene_.styles,
            [this](std::span<const uint32_t> edges) { return object_of(edges); }, &stroke_normals_);
        if (found.smooth_contours) {
            const glm::dmat4 object_from_world = glm::inverse(world_from_object);
            for (Stroke& stroke : out.strokes.strokes) {
                const StrokeGeometry& g = stroke.geometry;
                if (g.kind != LineKind::kSilhouette) continue;
                std::vector<glm::dvec3> points;
                points.reserve(g.points_world.size());
                for (const glm::dvec3& p : g.points_world) points.emplace_back(object_from_world * glm::dvec4(p, 1.0));
                stroke.faces = faces_crossed(mesh, table, points, g.edges);
            }
        }
        drawing_order_.assign(out.strokes.strokes);
        held_.reset();
        if (next_may_hold(frame, result, world_from_object, found.object_bounds)) {
            held_ = HeldStrokes{.polylines = result.polylines,
                                .occluded = result.occluded,
                                .camera = result.camera,
                                .light = result.light,
                                .world_from_object = world_from_object,
                                .positions_hash = moving ? positions_hash(mesh) : 0,
                                .strokes = out.strokes,
                                .tone = std::nullopt};
        }
    }
    out.mesh = &mesh;
    out.table = &table;
    out.world_from_object = world_from_object;
    const double strokes_ms = step("strokes");

    // Tone: dots on the visible surface, none under the strokes' ink; a held frame's as they were.
    double tone_ms = 0.0;
    if (held && held_->tone) {
        out.tone = *held_->tone;
        tone_ms = step("tone");
    } else if (scene_.tone.mode != ToneMode::kNone) {
        if (change == MeshChange::kTopology || tone_face_edges_.size() != mesh.triangles.size()) {
            tone_face_edges_ = face_edges(mesh, table);
        }
        if (change != MeshChange::kNone || tone_pieces_.face_groups.size() != mesh.triangles.size()) {
            smooth_pieces(mesh, table, tone_face_edges_,
                          tone_crease_angle_deg(scene_), tone_pieces_);
        }
        const ToneNormals tone_normals(tone_pieces_.normals, tone_pieces_.face_groups, tone_pieces_.group_vertex);
        out.tone.mode = scene_.tone.mode;
        if (tone_passes_.empty()) plan_tone_passes(mesh.triangles.size());
        const bool new_topology = change == MeshChange::kTopology;
        for (const TonePass& pass : tone_passes_) {
            const FaceTones face_tones{pass.faces, tone_curves_};
            out.tone.modes.push_back(pass.mode);
            // The scene's options with the pass's mode, for the marks' first frame.
            const auto options = [&] {
                ToneOptions o = scene_.tone;
                o.mode = pass.mode;
                return o;
            };
            if (pass.mode == ToneMode::kStipple) {
                if (!stippler_) stippler_.emplace(options());
                out.tone.dots = stippler_->stipple(mesh, table, tone_normals, projection, scene_.light, occlusion,
                                                   out.strokes.strokes, new_topology, face_tones);
                out.tone.stipple_stats = stippler_->stats();
                const StippleStats& st = out.tone.stipple_stats;
                if (!warned_samples_ && st.asked > st.samples && st.samples > 0) {
                    warned_samples_ = true;
                    out.warnings.push_back("frame " + std::to_string(frame) + ": stippling asks for " +
                                           std::to_string(st.asked) + " surface samples and keeps " +
                                           std::to_string(st.samples) +
                                           " (tone.max_samples): dots where the surface is seen closest are sparser "
                                           "than the tone asks");
                }
                continue;
            }
            std::optional<Hatcher>& hatcher = pass.mode == ToneMode::kHatch ? hatcher_ : crosshatcher_;
            if (!hatcher) hatcher.emplace(options());
            std::vector<Hatch> hatches = hatcher->hatch(mesh, table, tone_normals, projection, scene_.light, occlusion,
                                                        out.strokes.strokes, new_topology, face_tones);
            out.tone.hatches.insert(out.tone.hatches.end(), std::make_move_iterator(hatches.begin()),
                                    std::make_move_iterator(hatches.end()));
            out.tone.hatch_stats += hatcher->stats();
        }
        ink_tone_marks(out.tone);
        if (held_) held_->tone = out.tone;
        tone_ms = step("tone");
    }
    if (ahead_after_tone_) find_lines_ahead(frame + 1);
    FrameStats& stats = result.stats;
    stats.tracker = tracker_mode_name(tracker_mode_);
    stats.visibility = visibility_mode_name(occlusion_->mode());
    stats.visibility_reason = options_.visibility_reason;
    stats.gl_context = occlusion_->device();
    tally_visible_length(result);
    stats.ms = {{"load", found.load_ms},
                {"extract", found.extract_ms},
                {"chain", found.chain_ms},
                {"visibility", found.visibility_ms},
                {"strokes", strokes_ms}};
    if (scene_.tone.mode != ToneMode::kNone) stats.ms.emplace_back("tone", tone_ms);
    return out;
}

bool FramePipeline::next_may_hold(int frame, const FrameLines& lines, const glm::dmat4& world_from_object,
                                  const Bounds& object_bounds) const {
    const glm::dmat4 next_motion = world_from_object_at(scene_, frame + 1);
    if (next_motion != world_from_object) return false;
    try {
        return camera_at(scene_, frame + 1, transformed(object_bounds, next_motion)) == lines.camera;
    } catch (const InputError&) {
        return false;  // no camera for it: that frame fails when it comes
    }
}

void FramePipeline::plan_tone_passes(size_t faces) {
    const ToneMode scene_mode = scene_.tone.mode;
    const ToneCurve& scene_curve = scene_.tone.curve;
    const ToneInk scene_ink{scene_.tone.color, scene_.tone.opacity, ""};
    // Each object's tone; a mesh without objects is one object, which only style rules without
    // an object selector apply to.
    std::vector<ObjectTone> tones;
    if (meshes_.objects().empty()) tones.push_back(object_tone(scene_, std::nullopt));
    for (const MeshObject& object : meshes_.objects()) tones.push_back(object_tone(scene_, object.name));
    const std::span<const uint32_t> face_objects = meshes_.face_objects();
    const auto object_of_face = [&](size_t f) { return face_objects.empty() ? 0u : face_objects[f]; };
    // Faces keep their curve and their ink in 16 bits.
    const auto index16 = [&](size_t index, const char* what) {
        if (index >= 0xffffu) {
            const std::string file = scene_.file.empty() ? "scene" : scene_.file.string();
            throw InputError(file + ": key 'objects': more than 65,534 distinct tone " + what + " among the objects");
        }
        return uint16_t(index);
    };

    // The inks of the shaded objects, the scene's first where some object is drawn in it.
    const auto shaded_in = [&](const ToneInk& ink) {
        return std::any_of(tones.begin(), tones.end(),
                           [&](const ObjectTone& t) { return t.mode != ToneMode::kNone && t.ink == ink; });
    };
    if (shaded_in(scene_ink)) tone_inks_.push_back(scene_ink);
    for (const ObjectTone& t : tones) {
        auto it = std::find(tone_inks_.begin(), tone_inks_.end(), t.ink);
        if (t.mode != ToneMode::kNone && it == tone_inks_.end()) it = tone_inks_.insert(tone_inks_.end(), t.ink);
        ink_of_object_.push_back(index16(it == tone_inks_.end() ? 0 : size_t(it - tone_inks_.begin()), "inks"));
    }
    if (tone_inks_.size() == 1 && tone_inks_.front() == scene_ink) tone_inks_.clear();

    // Each object's curve (0: unshaded, else 1 + its index in tone_curves_) and mode; faces
    // keep the scene's curve in one pass of the scene's mode unless some object is unshaded or
    // has a curve or a mode of its own.
    std::vector<uint16_t> curve_of_object;
    std::vector<ToneMode> mode_of_object;
    bool own = false;
    for (const ObjectTone& t : tones) {
        mode_of_object.push_back(t.mode);
        if (t.mode == ToneMode::kNone) {
            curve_of_object.push_back(0);
            own = true;
            continue;
        }
        own |= t.curve != scene_curve || t.mode != scene_mode;
        auto it = std::find(tone_curves_.begin(), tone_curves_.end(), t.curve);
        if (it == tone_curves_.end()) it = tone_curves_.insert(it, t.curve);
        curve_of_object.push_back(index16(size_t(1 + (it - tone_curves_.begin())), "curves"));
    }
    if (!own) {
        tone_passes_.push_back({scene_mode, {}});
        return;
    }
    // A pass per mode some object is shaded with, the scene's first (the scene's alone, every
    // face unshaded, when no object is shaded).
    const auto used = [&](ToneMode mode) {
        return std::find(mode_of_object.begin(), mode_of_object.end(), mode) != mode_of_object.end();
    };
    std::vector<ToneMode> modes;
    if (used(scene_mode)) modes.push_back(scene_mode);
    for (const ToneMode mode : {ToneMode::kStipple, ToneMode::kHatch, ToneMode::kCrosshatch}) {
        if (mode != scene_mode && used(mode)) modes.push_back(mode);
    }
    if (modes.empty()) modes.push_back(scene_mode);
    for (const ToneMode mode : modes) {
        TonePass pass{mode, {}};
        pass.faces.reserve(faces);
        for (size_t f = 0; f < faces; ++f) {
            const uint32_t object = object_of_face(f);
            pass.faces.push_back(mode_of_object[object] == mode ? curve_of_object[object] : 0);
        }
        tone_passes_.push_back(std::move(pass));
    }
}

// Each mark's ink: its object's.
void FramePipeline::ink_tone_marks(FrameTone& r_tone) const {
    r_tone.inks = tone_inks_;
    if (tone_inks_.size() < 2) return;
    const std::span<const uint32_t> face_objects = meshes_.face_objects();
    const auto ink_of_face = [&](uint32_t face) {
        return ink_of_object_[face_objects.empty() ? 0u : face_objects[face]];
    };
    for (Dot& dot : r_tone.dots) dot.ink = ink_of_face(dot.face);
    for (Hatch& hatch : r_tone.hatches) {
        if (!hatch.faces.empty()) hatch.ink = ink_of_face(hatch.faces.front());
    }
}

}  // namespace inkline::core
