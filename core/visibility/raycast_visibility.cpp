// SPDX-License-Identifier: MIT
// Ray-cast occlusion with Embree 3: one occlusion ray per query, the edge's own faces rejected
// by an occlusion filter that reads them from the ray's intersect context.
#include "core/visibility/raycast_visibility.h"

#include "core/error.h"
#include "core/internal/parallel.h"
#include "core/visibility/internal/face_tests.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

namespace inkline::core {
namespace {

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
// the filter the address of `base`, which is also the address of the whole struct.
struct OwnFacesContext {
    RTCIntersectContext base;
    std::span<const uint32_t> own_faces;  // mesh faces of the query's edge
    const uint32_t* face_of;              // Embree primitive -> mesh face; null: the same number
};
static_assert(std::is_standard_layout_v<OwnFacesContext> && offsetof(OwnFacesContext, base) == 0);

void reject_own_faces(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const OwnFacesContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const uint32_t primitive = RTCHitN_primID(args->hit, args->N, i);
        const uint32_t face = context->face_of ? context->face_of[primitive] : primitive;
        if (internal::is_own_face(context->own_faces, face)) args->valid[i] = 0;
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
    DevicePtr device;
    ScenePtr scene;
    GeometryPtr geometry;  // null when the mesh has no valid face

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
    void build(const Mesh& mesh, bool two_level) {
        geometry.reset();
        scene.reset(rtcNewScene(device.get()));
        refittable = two_level;
        if (two_level) {
            rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
            rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_LOW);
        } else {
            rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT);
        }
        face_of.clear();
        primitives = size_t(std::count(table.face_valid.begin(), table.face_valid.end(), uint8_t(1)));
        if (primitives < mesh.triangles.size()) {
            face_of.reserve(primitives);
            for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
                if (table.face_valid[f]) face_of.push_back(f);
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
            auto* indices = static_cast<glm::uvec3*>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(glm::uvec3), primitives));
            check_device(device.get(), "allocating the mesh buffers");
            copy_scaled(mesh, static_cast<glm::vec3*>(vertices));
            for (size_t i = 0; i < primitives; ++i) indices[i] = mesh.triangles[face_of.empty() ? i : face_of[i]];
            rtcSetGeometryOccludedFilterFunction(g, reject_own_faces);
            rtcAttachGeometry(scene.get(), g);
        }
        commit();
    }

    // Sets scale and reach for the mesh's positions and writes them, scaled, to r_vertices.
    void copy_scaled(const Mesh& mesh, glm::vec3* r_vertices) {
        scale = internal::raycast_scale(mesh.positions);
        reach = occlusion_reach(mesh.positions);
        for (size_t v = 0; v < mesh.positions.size(); ++v) r_vertices[v] = glm::vec3(glm::dvec3(mesh.positions[v]) * scale);
    }

    void commit() {
        if (geometry) rtcCommitGeometry(geometry.get());
        rtcCommitScene(scene.get());
        check_device(device.get(), "building the BVH");
    }
};

RaycastOcclusion::RaycastOcclusion(const Mesh& mesh, const EdgeTable& table)
    : impl_(std::make_unique<Impl>(table)) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    Impl& impl = *impl_;

    // One build thread per core; queries run on our own threads, after the build.
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
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
    if (!impl.geometry) return;
    if (!impl.refittable) {
        // The first deformation: rebuild once in the two-level mode, refit from then on.
        impl.build(mesh, true);
        return;
    }
    RTCGeometry geometry = impl.geometry.get();
    impl.copy_scaled(mesh, static_cast<glm::vec3*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0)));
    rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    impl.commit();
}

void RaycastOcclusion::occluded(const glm::dvec3& eye_object, std::span<const OcclusionQuery> queries,
                                std::span<uint8_t> r_occluded) const {
    INKLINE_CHECK_EQ(queries.size(), r_occluded.size());
    const Impl& impl = *impl_;
    if (!impl.geometry) {
        std::fill(r_occluded.begin(), r_occluded.end(), uint8_t(0));
        return;
    }
    internal::parallel_for(queries.size(), kMinParallelQueries, [&](size_t begin, size_t end) {
        OwnFacesContext context;
        rtcInitIntersectContext(&context.base);
        context.face_of = impl.face_of.empty() ? nullptr : impl.face_of.data();
        for (size_t i = begin; i < end; ++i) {
            const OcclusionQuery& q = queries[i];
            context.own_faces = impl.table.faces_of(q.edge);
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
