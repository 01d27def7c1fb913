// SPDX-License-Identifier: MIT
// Depth-map visibility (`--visibility gl`): once per frame the mesh's depth is rendered into a
// float framebuffer at the image size times a supersampling factor and read back; every chain
// sample is then tested against it on the CPU. Sampling, bisection and splitting stay in
// core::split_by_visibility, which asks this class through core::Occlusion.
// Based on: the visibility mask of X. Yuan, M. X. Nguyen, N. Zhang, B. Chen. Stippling and
// Silhouettes Rendering in Geometry-Image Space. Eurographics Symposium on Rendering 2005,
// section 7. Robustness at silhouettes: docs/visibility.md.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/scene/camera.h"
#include "core/visibility/occlusion_source.h"
#include "core/visibility/visibility.h"
#include "gl/context.h"

#include <memory>

namespace inkline::gl {

struct DepthVisibilityOptions {
    // Depth-map texels per image pixel along each axis. With the local ray test, 1 agreed with
    // the exact test at least as well as 2 on every measured mesh at under half the pass cost:
    // the ray test, not the texels, settles sub-pixel geometry (docs/visibility.md).
    int supersampling = 1;
    // Settle what texels cannot resolve by intersecting the segment from the eye to the point
    // with nearby faces: those around the point's own edge (sub-texel slivers along mesh
    // silhouettes), on a depth discontinuity those seen in the texels around it, and their
    // neighbours that project within 3 texels; a point the texels hide is confirmed by the faces
    // seen there. Off: the depth map alone decides, which disagrees with the exact test on a
    // fifth to half of the visible length of dense meshes.
    bool local_ray_test = true;
};

// Size and timings of the last depth pass.
struct DepthPassStats {
    int width = 0;          // depth map, texels
    int height = 0;         // depth map, texels
    int supersampling = 0;  // the factor used: the option, lowered for GL's size limit or 2^26 texels
    double upload_ms = 0.0;    // mesh buffers sent to GL
    double render_ms = 0.0;    // clear, draw and finish
    double readback_ms = 0.0;  // depth map copied to the CPU
};

// core::Occlusion answered from a GL depth map: the surfaces seen at the four texels around a
// point, each extended along its own plane, hide it, show it or disagree; a local exact ray test
// against nearby faces settles what the texels cannot (docs/visibility.md).
class DepthOcclusion final : public core::Occlusion {
  public:
    // `context` must be current on this thread and outlive this object. Throws ContextError
    // when the context cannot run the pass (missing entry points, shader or framebuffer errors).
    explicit DepthOcclusion(const Context& context, const DepthVisibilityOptions& options = {});
    ~DepthOcclusion() override;
    DepthOcclusion(const DepthOcclusion&) = delete;
    DepthOcclusion& operator=(const DepthOcclusion&) = delete;

    // Renders and reads back the depth map of `mesh` (object space) seen through `projection`;
    // call once per frame before core::split_by_visibility with the same projection. `mesh` and
    // its `table` must stay alive and unchanged until the queries of this frame are done. Uploads
    // triangles and positions on the first call and for kTopology, only positions for
    // kPositions, nothing for kNone: rigid motion travels in the projection's matrix.
    // Throws InputError when even one texel per pixel exceeds GL's framebuffer size limit.
    void prepare(const core::Mesh& mesh, const core::EdgeTable& table, const core::Projection& projection,
                 core::MeshChange change);

    // Tests each query against the depth map of the last prepare(); eye_object must be that
    // projection's eye. The point's own faces pass both tests: their planes contain it, and the
    // ray stops just short of it. Not safe to call from two threads at once.
    void occluded(const core::Viewpoint& eye_object, std::span<const core::OcclusionQuery> queries,
                  std::span<uint8_t> r_occluded) const override;

    const DepthPassStats& last_pass() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The depth pass as core's occlusion provider (`--visibility gl`), for core::FramePipeline: sets
// up its DepthOcclusion on the first prepare(), on `context`, which must be current on this
// thread and outlive this object.
class DepthOcclusionSource final : public core::OcclusionSource {
  public:
    explicit DepthOcclusionSource(const Context& context, const DepthVisibilityOptions& options = {});
    ~DepthOcclusionSource() override;

    // Renders this frame's depth map (DepthOcclusion::prepare). Throws ContextError when the
    // context cannot run the pass, InputError when the image exceeds GL's framebuffer size.
    const core::Occlusion& prepare(const core::Mesh& mesh, const core::EdgeTable& table,
                                   const core::Projection& projection, core::MeshChange change) override;
    core::VisibilityMode mode() const override { return core::VisibilityMode::kGl; }
    // "<backend>: <renderer>", e.g. "egl: llvmpipe (LLVM 15.0.6, 256 bits)".
    std::string device() const override;

  private:
    const Context& context_;
    DepthVisibilityOptions options_;
    std::unique_ptr<DepthOcclusion> depth_;
};

}  // namespace inkline::gl
