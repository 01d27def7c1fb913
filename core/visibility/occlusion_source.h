// SPDX-License-Identifier: MIT
// The occlusion test of a run, kept across its frames: built for the first frame's mesh and
// brought up to date as the mesh moves. core::FramePipeline prepares it once per frame and hands
// it to split_by_visibility. The CPU tests (ray casting, exact) are made here; the GL depth pass
// implements the same interface in gl/ (gl/depth_visibility.h), so core knows no GL.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"
#include "core/scene/camera.h"
#include "core/visibility/visibility.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace inkline::core {

// The occlusion tests (`--visibility`); all answer the definition in visibility.h.
enum class VisibilityMode : uint8_t {
    kGl,       // a depth map rendered with OpenGL, settled by local ray tests (gl/depth_visibility.h)
    kRaycast,  // Embree occlusion rays on the CPU (raycast_visibility.h)
    kExact,    // CGAL segment queries: the reference (exact_visibility.h)
};

// "gl", "raycast" or "exact".
const char* visibility_mode_name(VisibilityMode mode);
// The mode of that name; nullopt for any other text.
std::optional<VisibilityMode> visibility_mode_from_name(std::string_view name);
// The mode of that name; throws InputError "KEY 'TEXT': expected gl, raycast or exact".
VisibilityMode parse_visibility_mode(std::string_view text, const char* key);

// What changed in the mesh since the previous OcclusionSource::prepare().
enum class MeshChange : uint8_t {
    kNone,       // same mesh; only the projection may differ (camera, rigid object motion)
    kPositions,  // same triangles, new vertex positions (a deforming sequence)
    kTopology,   // a different mesh
};

class OcclusionSource {
  public:
    virtual ~OcclusionSource() = default;

    // The occlusion test of `mesh` (object space) seen through `projection`, for
    // split_by_visibility with that projection: built on the first call and for kTopology,
    // brought up to date for kPositions, reused for kNone (rigid motion travels in the
    // projection). `mesh` and `table` must stay alive and unchanged until this frame's queries
    // are done; the test returned is valid until the next call.
    virtual const Occlusion& prepare(const Mesh& mesh, const EdgeTable& table, const Projection& projection,
                                     MeshChange change) = 0;

    virtual VisibilityMode mode() const = 0;

    // What runs the test when it is not inkline's own CPU code, as FrameStats::gl_context names
    // it ("egl: <renderer>"); empty for the CPU tests.
    virtual std::string device() const { return {}; }
};

// The ray-cast (kRaycast: a BVH built once, refitted for new positions) or exact (kExact: a tree
// rebuilt whenever the mesh changed) test. Throws InputError for kRaycast in a build without
// Embree (raycast_available()), InternalError for kGl: gl::DepthOcclusionSource makes that one.
std::unique_ptr<OcclusionSource> make_cpu_occlusion(VisibilityMode mode);

}  // namespace inkline::core
