// SPDX-License-Identifier: MIT
// One frame from mesh to strokes, as `inkline render` draws it, with the state that carries from
// frame to frame: the silhouette tracker, the occlusion test and stroke coherence.
//
//   MeshFrames::at -> camera_at -> SilhouetteTracker::update (or extract_feature_edges)
//   -> chain_feature_edges -> OcclusionSource::prepare -> split_by_visibility
//   -> set_aside_occluded (without lines.hidden) -> build_strokes -> DrawingOrder::assign
//   -> Stippler::stipple or Hatcher::hatch (with a scene "tone")
//
// Writers (export/) take the result: output::polylines_json(result.lines, &result.strokes,
// &result.tone), output::brush_drawing(result.lines, result.strokes, ...) with
// output::tone_layer(result.tone, scene.tone) as its tone.
#pragma once

#include "core/lines/chaining.h"
#include "core/lines/intersections.h"
#include "core/lines/silhouette_tracker.h"
#include "core/lines/smooth_contours.h"
#include "core/lines/smooth_pieces.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_frames.h"
#include "core/pipeline/frame_lines.h"
#include "core/scene/scene.h"
#include "core/strokes/drawing_order.h"
#include "core/strokes/strokes.h"
#include "core/tone/tone.h"
#include "core/visibility/occlusion_source.h"

#include <glm/mat4x4.hpp>

#include <array>
#include <functional>
#include <future>
#include <span>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkline::core {

namespace internal {
class Worker;
}  // namespace internal

struct PipelineOptions {
    TrackerMode tracker = TrackerMode::kIncremental;
    // The number of frames the run draws; 0: the scene's frame range. A run of one frame finds
    // its feature edges by brute force whatever `tracker` says: the tracker's cone hierarchy
    // costs about one brute-force pass per few hundred thousand faces to build and repays it
    // only over later frames, and both give the same edges.
    int frame_count = 0;
    // Why the occlusion test is the one given, for FrameStats::visibility_reason. The default is
    // what `inkline render --visibility MODE` says.
    std::string visibility_reason = "asked for";
    // Called as each step of run() ends, with its name: "load", "tracker build" (the cone
    // hierarchy, on the tracker's first frame), "extract", "chain", "occlusion" (prepare: a BVH
    // or tree built or refitted, a depth pass), "visibility", "strokes". For benchmarks that time
    // the steps with clocks of their own; FrameStats::ms counts the tracker build in "extract"
    // and the occlusion step in "visibility". With it set, every step runs in run() on the
    // calling thread: no frame's lines are found ahead.
    std::function<void(const char* step)> step_done{};
};

// One frame drawn.
struct FrameResult {
    FrameLines lines;      // camera, light, visible polylines (occluded ones too with lines.hidden), stats
    FrameStrokes strokes;  // brush strokes of lines
    FrameTone tone;        // the tone's dots (mode kNone and none without a scene "tone")
    const Mesh* mesh = nullptr;  // the frame's mesh (object space), valid until the next run()
    const EdgeTable* table = nullptr;  // its edge table, valid as long as the pipeline
    glm::dmat4 world_from_object{1.0};
    // Drawable but odd input found drawing this frame (the camera inside the mesh's bounds, the
    // mesh wholly outside the view, stippling held back by its sample bound: each said once a
    // run), for the caller to show; the pipeline prints nothing.
    std::vector<std::string> warnings;
};

class FramePipeline {
  public:
    // `meshes` must outlive the pipeline; the scene is copied. The occlusion test is prepared
    // for every frame (gl::DepthOcclusionSource, make_cpu_occlusion); it must not be null.
    FramePipeline(const Scene& scene, MeshFrames& meshes, std::unique_ptr<OcclusionSource> occlusion,
                  PipelineOptions options = {});
    ~FramePipeline();
    FramePipeline(const FramePipeline&) = delete;
    FramePipeline& operator=(const FramePipeline&) = delete;

    // Draws a frame. Stroke ids and coherence carry from one call to the next, so frames are
    // drawn in order (a chunk of a sequence replays the frames before it). Throws InputError
    // for a frame that cannot be drawn (its mesh file, its camera); the next call may go on.
    // The next frame's lines are then found on a second thread while the caller uses this
    // result (docs/pipeline.md).
    FrameResult run(int frame);

    // The extraction in use: options.tracker, or kBrute for a run of one frame.
    TrackerMode tracker_mode() const { return tracker_mode_; }
    const OcclusionSource& occlusion() const { return *occlusion_; }

  private:
    // A frame's lines: its mesh and camera, the chains of its feature edges, smooth contours and
    // intersection lines, with what the stats need of them; then (visible) the polylines split
    // by visibility, the chains dropped.
    struct FoundLines {
        FrameLines lines;  // frame, image, light, camera, stats (faces, edges, tested, feature
                           // edges); the polylines once visible
        const Mesh* mesh = nullptr;
        glm::dmat4 world_from_object{1.0};
        MeshChange change = MeshChange::kNone;
        Bounds object_bounds;  // of the mesh, object space (the camera's fit)
        std::vector<Chain> chains;
        bool smooth_contours = false;
        const Occlusion* occlusion = nullptr;  // the frame's occlusion test; null until visible
        double load_ms = 0.0, extract_ms = 0.0, chain_ms = 0.0, visibility_ms = 0.0;
        std::vector<std::string> warnings;
    };
    // Finds a frame's lines (and with_visibility, what of them is visible); the tracers' state
    // moves on to that frame.
    FoundLines find_lines(int frame, bool with_visibility);
    // Splits the found lines by visibility.
    void find_visible(FoundLines& found);
    // The frame's lines: found ahead, or found now, visible or not.
    FoundLines lines_of(int frame);
    // Starts finding a frame's lines on another thread (where lines_ahead_ allows).
    void find_lines_ahead(int frame);

    // The object of the first of these mesh edges; -1 without objects.
    int32_t object_of(std::span<const uint32_t> edges) const;

    Scene scene_;
    MeshFrames& meshes_;
    std::unique_ptr<OcclusionSource> occlusion_;
    PipelineOptions options_;
    TrackerMode tracker_mode_;
    std::optional<SilhouetteTracker> tracker_;
    std::optional<IntersectionTracer> intersections_;  // when intersection lines can be drawn
    std::optional<SmoothContourTracer> smooth_;         // with lines.contour "smooth"
    // With smooth contours on a mesh that does not change, its boundary and crease edges.
    std::optional<std::vector<FeatureEdge>> still_edges_;
    StrokeCoherence coherence_;
    // The last frame's strokes and what they were drawn from, kept while the next frame may be
    // held (the same camera next frame): a frame with the same lines, camera, light and mesh
    // draws the same strokes. Drawn again, the repairs that read the strokes of the frame before
    // could answer otherwise in a tangle, and alternate.
    struct HeldStrokes {
        std::vector<Polyline> polylines, occluded;
        Camera camera;
        Light light;
        glm::dmat4 world_from_object{1.0};
        size_t positions_hash = 0;  // of a moving mesh's positions (which a held frame repeats)
        FrameStrokes strokes;
        std::optional<FrameTone> tone;  // with a scene "tone"
    };
    std::optional<HeldStrokes> held_;
    // The last frame's visible lines and occlusion test, kept while the mesh holds still and
    // the next frame's camera is this frame's: a frame under that camera takes them without
    // looking again (where its visibility is found with its lines, without extracting them
    // either). Read and written only where visibility is found (one thread at a time).
    struct HeldLines {
        std::vector<Polyline> polylines, occluded;
        std::vector<MeshObject> objects;
        FrameStats stats;  // what extraction found (the edges and faces it tested: none when held)
        bool smooth_contours = false;
        Camera camera;
        glm::dmat4 world_from_object{1.0};
        const Occlusion* occlusion = nullptr;
    };
    std::optional<HeldLines> held_lines_;
    // Whether the found lines' frame repeats the held lines' (a still mesh, the same camera).
    bool holds_lines(const FoundLines& found) const;
    // The held lines as the found ones, with their extraction's stats when it did not run.
    void take_held_lines(FoundLines& found, bool with_stats) const;
    // Whether frame + 1 may repeat this frame: the same object motion and camera (the mesh
    // holding still, its bounds the same).
    bool next_may_hold(int frame, const FrameLines& lines, const glm::dmat4& world_from_object,
                       const Bounds& object_bounds) const;
    Bounds object_bounds_;              // of the mesh, while it holds still
    VertexNormalCache stroke_normals_;  // the strokes' vertex normals, while the mesh holds still
    DrawingOrder drawing_order_;
    // The tone's marks of each mode, with the state each keeps from frame to frame.
    std::optional<Stippler> stippler_;
    std::optional<Hatcher> hatcher_, crosshatcher_;
    // The normals the tone reads its light from: those of the mesh's smooth pieces, split at
    // creases (tone.crease_angle_deg, else lines.crease_angle_deg), with each face's edges that
    // finding them needs.
    SmoothPieces tone_pieces_;
    std::vector<glm::uvec3> tone_face_edges_;
    // One mode's marks on the faces shaded with it (scene "objects" may give an object a mode
    // of its own).
    struct TonePass {
        ToneMode mode = ToneMode::kNone;
        // Per face: 0 where it is unshaded in this pass, else 1 + the index of its object's
        // tone curve in tone_curves_; empty: every face on the scene's curve.
        std::vector<uint16_t> faces;
    };
    std::vector<TonePass> tone_passes_;  // set on the first frame with tone
    std::vector<ToneCurve> tone_curves_;
    // The inks of the shaded objects (FrameTone::inks; empty: the scene's alone) and each
    // object's index in them (one entry for a mesh without objects).
    std::vector<ToneInk> tone_inks_;
    std::vector<uint16_t> ink_of_object_;
    void plan_tone_passes(size_t faces);
    void ink_tone_marks(FrameTone& r_tone) const;
    // Per object: the kinds of line it draws (object_line_kinds); empty without objects.
    std::vector<std::array<bool, kLineKindCount>> object_kinds_;
    bool trace_intersections_ = false;
    bool first_lines_ = true;    // no frame's lines found yet
    bool lines_ahead_ = false;   // the next frame's lines may be found while a frame is drawn
    bool visibility_ahead_ = false;  // ... and their visibility
    bool ahead_after_tone_ = false;  // ... but only once the frame's tone is done
    bool warned_inside_ = false;
    bool warned_outside_ = false;
    bool warned_samples_ = false;  // stippling held back by ToneOptions::max_samples
    // The next frame's lines, being found while a frame is drawn, on a thread of the pipeline's
    // own (started on the first frame found ahead). Last, so that the thread stops before the
    // state it uses goes.
    std::future<FoundLines> ahead_;
    int ahead_frame_ = 0;
    std::unique_ptr<internal::Worker> ahead_worker_;
};

}  // namespace inkline::core
