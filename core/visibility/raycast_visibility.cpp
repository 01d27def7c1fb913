// SPDX-License-Identifier: MIT
// Ray-cast occlusion with Embree 3: one occlusion ray per query, the edge's own faces rejected
// by an occlusion filter that reads them from the ray's intersect context. The faces of fans
// (core/visibility/internal/fan_index.h) are not Embree triangles: each fan is one user
// primitive, whose occlusion callback finds the few faces the ray can meet and tests them in
// double precision.
#include "core/visibility/raycast_visibility.h"

#include "core/error.h"
#include "core/internal/float_round.h"
#include "core/internal/parallel.h"
#include "core/visibility/internal/face_tests.h"
#include "core/visibility/internal/fan_index.h"

#include <embree3/rtcore.h>
#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace inkline::core {
namespace {

using internal::float_above;
using internal::float_below;

// Below this many queries a call runs on the calling thread; starting threads costs more.
constexpr size_t kMinParallelQueries = 4096;

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "Mesh positions are copied as packed float3");

struct DeviceRelease {
    void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneRelease {
    void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
struct GeometryRelease {
    void operator()(RTCGeometry g) const { rtcReleaseGeometry(g); }
};
using DevicePtr = std::unique_ptr<RTCDeviceTy, DeviceRelease>;
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneRelease>;
using GeometryPtr = std::unique_ptr<RTCGeometryTy, GeometryRelease>;

const char* error_name(RTCError error) {
    switch (error) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
        default: return "unknown error";
    }
}

// Embree reports errors per device; a failure is a resource problem or a bug, never bad input.
// Running out of memory is std::bad_alloc, as for any other allocation.
[[noreturn]] void embree_failed(RTCError error, const char* what) {
    if (error == RTC_ERROR_OUT_OF_MEMORY) throw std::bad_alloc();
    throw std::runtime_error(std::string("Embree: ") + what + ": " + error_name(error));
}

void check_device(RTCDevice device, const char* what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE) embree_failed(error, what);
}

// Extends Embree's intersect context with the faces the current ray must ignore. Embree hands
// the filter and the fans' callback the address of `base`, which is also the address of the
// whole struct.
struct OwnFacesContext {
    RTCIntersectContext base;
    internal::OwnFaces own_faces;         // faces the query's ray ignores
    const uint32_t* face_of;              // Embree primitive -> mesh face; null: the same number
};
static_assert(std::is_standard_layout_v<OwnFacesContext> && offsetof(OwnFacesContext, base) == 0);

void reject_own_faces(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const OwnFacesContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const uint32_t primitive = RTCHitN_primID(args->hit, args->N, i);
        const uint32_t face = context->face_of ? context->face_of[primitive] : primitive;
        if (context->own_faces.has(face)) args->valid[i] = 0;
    }
}

// Fan boxes grow by this fraction of their largest coordinate on every side before they are
// rounded outwards to float. A flat fan (a disc cap) has a box of no thickness, and a ray in its
// plane meets that box's faces at 0 * infinity in Embree's slab test, which misses; a ray through
// a corner of the box can miss it by rounding. Neither can miss a box that is a little larger.
constexpr double kFanBoxPad = 1e-6;


// Bounds of one fan (a user primitive), in the scaled frame: padded, then rounded outwards.
void fan_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* fans = static_cast<const internal::FanIndex*>(args->geometryUserPtr);
    const Bounds b = fans->bounds(args->primID);
    const glm::dvec3 largest = glm::max(glm::abs(b.min), glm::abs(b.max));
    const double pad = kFanBoxPad * std::max({largest.x, largest.y, largest.z});
    RTCBounds& out = *args->bounds_o;
    out.lower_x = float_below(b.min.x - pad);
    out.lower_y = float_below(b.min.y - pad);
    out.lower_z = float_below(b.min.z - pad);
    out.upper_x = float_above(b.max.x + pad);
    out.upper_y = float_above(b.max.y + pad);
    out.upper_z = float_above(b.max.z + pad);
}

// Occlusion by one fan: its candidate faces other than the ray's own, each tested as Embree
// tests a triangle, in double. An occluded ray gets tfar = -infinity, as Embree marks it.
void fan_occluded(const RTCOccludedFunctionNArguments* args) {
    const auto* fans = static_cast<const internal::FanIndex*>(args->geometryUserPtr);
    const auto* context = reinterpret_cast<const OwnFacesContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        RTCRayN* ray = args->ray;
        internal::ScaledRay scaled;
        const unsigned n = args->N;
        scaled.origin = {RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)};
        scaled.direction = {RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)};
        scaled.tnear = RTCRayN_tnear(ray, n, i);
        scaled.tfar = RTCRayN_tfar(ray, n, i);
        const internal::RayTriangleTest test(scaled);
        const bool hit = fans->find_face(
            args->primID, glm::dvec3(scaled.origin), glm::dvec3(scaled.direction), double(scaled.tnear),
            double(scaled.tfar),
            [&](uint32_t face, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
                return !context->own_faces.has(face) && test.meets(a, b, c);
            });
        if (hit) RTCRayN_tfar(ray, n, i) = -std::numeric_limits<float>::infinity();
    }
}

}  // namespace

bool raycast_available() { return true; }

struct RaycastOcclusion::Impl {
    const EdgeTable& table;
    std::vector<uint32_t> face_of;  // Embree primitive -> mesh face (valid faces only); empty when all are
    size_t primitives = 0;
    size_t vertex_count = 0;
    double scale = 1.0;             // internal::raycast_scale of the mesh
    double reach = 1.0;             // occlusion_reach of the mesh, object units
    bool refittable = false;        // built in the two-level mode that update_positions refits
    internal::FanIndex fans;        // faces Embree does not hold as triangles
    DevicePtr device;
    ScenePtr scene;
    GeometryPtr geometry;      // the triangles; null when no valid face is left for it
    GeometryPtr fan_geometry;  // one user primitive per fan; null when the mesh has none

    explicit Impl(const EdgeTable& t) : table(t) {}

    // Builds the BVH over the valid faces at the mesh's positions.
    //
    // Robust: watertight triangle tests, so no ray slips through the edge between two occluders.
    // A static mesh gets a compact one-level BVH of the default (SAH) quality. At 1M triangles,
    // against the two-level build: half the build time and, for the whole render, peak memory
    // 263 -> 208 MB (55 MB of it from the compact layout), for queries a third slower (+3 ms a
    // frame) and the same answers. Embree 3 refits only in its two-level mode, which the dynamic
    // flag with scene quality LOW selects; the mesh's REFIT quality then builds its BVH once with
    // SAH and refits it on every vertex update (1M triangles: about 25 ms instead of 320 ms).
    //
    // Fans take their faces out of the triangles. A mesh without fans gets no user geometry.
    void build(const Mesh& mesh, bool two_level) {
        geometry.reset();
        fan_geometry.reset();
        scene.reset(rtcNewScene(device.get()));
        refittable = two_level;
        if (two_level) {
            rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
            rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_LOW);
        } else {
            rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT);
        }
        set_scale(mesh);
        fans = internal::FanIndex(mesh, table, scale);
        const std::vector<uint8_t>& in_fan = fans.in_fan();
        const auto is_triangle = [&](uint32_t f) { return table.face_valid[f] && (in_fan.empty() || !in_fan[f]); };
        face_of.clear();
        primitives = 0;
        for (uint32_t f = 0; f < mesh.triangles.size(); ++f) primitives += is_triangle(f);
        if (primitives < mesh.triangles.size()) {
            face_of.reserve(primitives);
            for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
                if (is_triangle(f)) face_of.push_back(f);
            }
        }
        vertex_count = mesh.positions.size();
        if (primitives > 0) {
            geometry.reset(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
            check_device(device.get(), "creating the triangle geometry");
            RTCGeometry g = geometry.get();
            if (two_level) rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_REFIT);
            void* vertices = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                     sizeof(glm::vec3), vertex_count);
            glm::uvec3* indices = nullptr;
            if (face_of.empty() && !two_level) {
                // Every face is a primitive of a BVH that is never refitted: Embree reads the
                // mesh's own triangles (12 MB not copied at 1M faces). A refittable build keeps a
                // copy: a deforming mesh's later frames may come in other storage.
                rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(), 0,
                                           sizeof(glm::uvec3), primitives);
            } else {
                indices = static_cast<glm::uvec3*>(rtcSetNewGeometryBuffer(
                    g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(glm::uvec3), primitives));
            }
            check_device(device.get(), "allocating the mesh buffers");
            copy_scaled(mesh, static_cast<glm::vec3*>(vertices));
            if (indices) {
                for (size_t i = 0; i < primitives; ++i) indices[i] = mesh.triangles[face_of.empty() ? i : face_of[i]];
            }
            rtcSetGeometryOccludedFilterFunction(g, reject_own_faces);
            rtcAttachGeometry(scene.get(), g);
        }
        if (!fans.empty()) {
            fan_geometry.reset(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER));
            check_device(device.get(), "creating the fan geometry");
            RTCGeometry g = fan_geometry.get();
            if (two_level) rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_REFIT);
            rtcSetGeometryUserPrimitiveCount(g, unsigned(fans.fan_count()));
            rtcSetGeometryUserData(g, &fans);
            rtcSetGeometryBoundsFunction(g, fan_bounds, nullptr);
            rtcSetGeometryOccludedFunction(g, fan_occluded);
            rtcAttachGeometry(scene.get(), g);
        }
        commit();
    }

    // Sets scale and reach for the mesh's positions.
    void set_scale(const Mesh& mesh) {
        scale = internal::raycast_scale(mesh.positions);
        reach = occlusion_reach(mesh.positions);
    }

    // Writes the mesh's positions, scaled, to r_vertices.
    void copy_scaled(const Mesh& mesh, glm::vec3* r_vertices) const {
        for (size_t v = 0; v < mesh.positions.size(); ++v) r_vertices[v] = glm::vec3(glm::dvec3(mesh.positions[v]) * scale);
    }

    void commit() {
        if (geometry) rtcCommitGeometry(geometry.get());
        if (fan_geometry) rtcCommitGeometry(fan_geometry.get());
        rtcCommitScene(scene.get());
        check_device(device.get(), "building the BVH");
    }
};

RaycastOcclusion::RaycastOcclusion(const Mesh& mesh, const EdgeTable& table)
    : impl_(std::make_unique<Impl>(table)) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    Impl& impl = *impl_;

    // One build thread per core; queries run on our own threads, after the build.
    const size_t threads = internal::hardware_threads();
    const std::string config = "threads=" + std::to_string(threads);
    impl.device.reset(rtcNewDevice(config.c_str()));
    if (!impl.device) {
        embree_failed(rtcGetDeviceError(nullptr), "creating the device");
    }
    // A mesh is taken as static until its first update_positions.
    impl.build(mesh, false);
}

RaycastOcclusion::~RaycastOcclusion() = default;

void RaycastOcclusion::update_positions(const Mesh& mesh) {
    Impl& impl = *impl_;
    INKLINE_CHECK_EQ(mesh.positions.size(), impl.vertex_count);
    if (!impl.geometry && !impl.fan_geometry) return;
    if (!impl.refittable) {
        // The first deformation: rebuild once in the two-level mode, refit from then on.
        impl.build(mesh, true);
        return;
    }
    impl.set_scale(mesh);
    if (impl.geometry) {
        RTCGeometry geometry = impl.geometry.get();
        impl.copy_scaled(mesh, static_cast<glm::vec3*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0)));
        rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    }
    // The fans keep their ring order (topology) and fit their boxes again; committing the user
    // geometry asks Embree for the new bounds.
    if (impl.fan_geometry) impl.fans.update_positions(mesh, impl.scale);
    impl.commit();
}

void RaycastOcclusion::occluded(const Viewpoint& eye_object, std::span<const OcclusionQuery> queries,
                                std::span<uint8_t> r_occluded) const {
    INKLINE_CHECK_EQ(queries.size(), r_occluded.size());
    const Impl& impl = *impl_;
    if (!impl.geometry && !impl.fan_geometry) {
        std::fill(r_occluded.begin(), r_occluded.end(), uint8_t(0));
        return;
    }
    internal::parallel_for(queries.size(), kMinParallelQueries, [&](size_t begin, size_t end) {
        OwnFacesContext context;
        rtcInitIntersectContext(&context.base);
        context.face_of = impl.face_of.empty() ? nullptr : impl.face_of.data();
        for (size_t i = begin; i < end; ++i) {
            const OcclusionQuery& q = queries[i];
            context.own_faces = internal::own_faces_of(q, impl.table);
            const internal::ScaledRay cast = internal::occlusion_ray(q.p_object, eye_object, impl.reach, impl.scale);
            RTCRay ray;
            ray.org_x = cast.origin.x;
            ray.org_y = cast.origin.y;
            ray.org_z = cast.origin.z;
            ray.tnear = cast.tnear;
            ray.dir_x = cast.direction.x;
            ray.dir_y = cast.direction.y;
            ray.dir_z = cast.direction.z;
            ray.time = 0.0f;
            ray.tfar = cast.tfar;
            ray.mask = ~0u;
            ray.id = 0;
            ray.flags = 0;
            rtcOccluded1(impl.scene.get(), &context.base, &ray);
            // Embree marks an occluded ray by setting tfar to -infinity.
            r_occluded[i] = ray.tfar < 0.0f ? 1 : 0;
        }
    });
}

}  // namespace inkline::core
