// SPDX-License-Identifier: MIT
#include "gl/depth_visibility.h"

#include "core/error.h"
#include "gl/internal/depth_map.h"
#include "gl/internal/functions.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

namespace inkline::gl {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 p_object;
uniform mat4 clip_from_object;
noperspective out float ortho_q;
void main() {
    gl_Position = clip_from_object * vec4(p_object, 1.0);
    ortho_q = 2.0 - gl_Position.z;
}
)";

// q, larger nearer the eye, is affine in window space on a planar triangle: its screen
// derivatives are the triangle's own depth slope, constant over it, so storing them lets the
// CPU test extend the seen surface exactly to a point between texel centres. In perspective q
// is gl_FragCoord.w, 1 / w_clip; in orthographic projection (w_clip = 1) it is 2 - z_clip,
// from 1 at the near plane to 3 at the far plane (depth_q). The face id (exact as a float below
// 2^24) names the candidates for the exact test at edges.
constexpr const char* kFragmentShader = R"(#version 330 core
layout(location = 0) out vec4 plane;
uniform bool orthographic;
noperspective in float ortho_q;
void main() {
    float q = orthographic ? ortho_q : gl_FragCoord.w;
    plane = vec4(q, dFdx(q), dFdy(q), float(gl_PrimitiveID + 1));
}
)";

// The depth map's q of a clip-space point in front of the eye (kFragmentShader).
double depth_q(const core::Projection& projection, const glm::dvec4& clip) {
    return projection.orthographic() ? 2.0 - clip.z : 1.0 / clip.w;
}

// Largest depth map supersampling may make: 2^26 texels are 1 GiB of RGBA32F plus 256 MiB of
// depth, already 8192x8192 at 1 texel per pixel. Larger images get fewer texels per pixel.
constexpr double kMaxTexels = double(1 << 26);

// Texels beyond the bilinear footprint, on every side, whose faces are candidates at a depth
// discontinuity: a 6x6 window. On the bench's meshes at 2x supersampling a 4x4 window loses up
// to 0.15% of agreement with the exact test and lengthens the longest disagreeing run.
constexpr int kSeenRings = 2;

// Candidate vertices grow through mesh edges to every vertex that projects within this many
// texels of the point: where faces are smaller than texels, the slivers hiding a silhouette
// lie several rings from it. At 2x supersampling, 3 texels brought a 328k-face mesh at 1024 px
// from 96.7% to 99.96% agreement; 2 texels reach 99.6%, 4 no more than 3.
constexpr double kNearTexels = 3.0;

// The segment from the eye stops this fraction of its length short of the point, so faces that
// merely touch the point (its own faces, those around a vertex) never count: the same end gap
// as core::ExactOcclusion, so both answer the same where the depth map defers to geometry.
constexpr double kEndGap = 1e-6;

// True when the segment from -> p, without its last kEndGap, crosses the triangle
// (Moller-Trumbore in double precision). `from` is the eye, or for an eye at infinity the
// point core::occlusion_segment_end gives.
bool segment_hits(const glm::dvec3& from, const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                  const glm::dvec3& c) {
    const glm::dvec3 dir = p - from;
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 h = glm::cross(dir, e2);
    const double det = glm::dot(e1, h);
    if (det == 0.0) return false;  // parallel, or a degenerate face
    const double inv = 1.0 / det;
    const glm::dvec3 s = from - a;
    const double u = glm::dot(s, h) * inv;
    if (u < 0.0 || u > 1.0) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(dir, q) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    const double t = glm::dot(e2, q) * inv;
    return t > 0.0 && t < 1.0 - kEndGap;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The projection's matrix, read back through its public clip(): clip(0) is the last column
// and clip(e_k) - clip(0) column k. Exact up to one rounding of the double products.
glm::dmat4 clip_from_object_of(const core::Projection& projection) {
    const glm::dvec4 origin = projection.clip(glm::dvec3(0.0));
    glm::dmat4 m(1.0);
    for (int k = 0; k < 3; ++k) {
        glm::dvec3 axis(0.0);
        axis[k] = 1.0;
        m[k] = projection.clip(axis) - origin;
    }
    m[3] = origin;
    return m;
}

void check_gl(const internal::Functions& fn, const char* step) {
    const GLenum error = fn.GetError();
    if (error != GL_NO_ERROR) {
        throw ContextError(std::string("GL error ") + std::to_string(error) + " while " + step +
                           " (out of memory for the depth map? try a smaller supersampling)");
    }
}

}  // namespace

struct DepthOcclusion::Impl {
    internal::Functions fn;
    DepthVisibilityOptions options;
    GLuint program = 0, vao = 0, positions = 0, indices = 0;
    GLuint framebuffer = 0, color = 0, depth = 0;
    GLint clip_from_object_location = -1;
    GLint orthographic_location = -1;
    GLint max_size = 0;          // largest framebuffer side GL allows
    size_t vertex_count = 0;     // uploaded
    GLsizei index_count = 0;     // uploaded
    bool uploaded = false;

    // Faces around each vertex (CSR), rebuilt with the topology: the neighbours of seen faces.
    std::vector<uint32_t> vertex_face_offsets;  // #V+1
    std::vector<uint32_t> vertex_faces;

    // Scratch for occluded(): per-vertex and per-face marks of the current query, told apart by
    // an epoch so nothing is cleared between queries, and the candidate lists. It makes
    // occluded() unsafe to call from two threads at once, which split_by_visibility never does.
    mutable std::vector<uint32_t> vertex_mark, face_mark;
    mutable uint32_t epoch = 0;
    mutable std::vector<uint32_t> candidates, seen;

    internal::DepthMap map;
    std::optional<core::Projection> projection;  // of the last prepare()
    double reach = 0.0;  // occlusion_reach of the last prepare()'s mesh, for an orthographic eye
    const core::Mesh* frame_mesh = nullptr;      // of the last prepare()
    const core::EdgeTable* frame_table = nullptr;
    DepthPassStats stats;

    ~Impl() {
        if (!fn.DeleteProgram) return;  // loading failed: nothing was created
        fn.DeleteFramebuffers(1, &framebuffer);
        fn.DeleteRenderbuffers(1, &color);
        fn.DeleteRenderbuffers(1, &depth);
        fn.DeleteBuffers(1, &positions);
        fn.DeleteBuffers(1, &indices);
        fn.DeleteVertexArrays(1, &vao);
        fn.DeleteProgram(program);
    }

    void upload(const core::Mesh& mesh, core::MeshChange change) {
        const bool everything = !uploaded || change == core::MeshChange::kTopology;
        if (!everything) {
            // Same topology promised: a different mesh here would draw stale buffers.
            INKLINE_CHECK_EQ(mesh.positions.size(), vertex_count);
            INKLINE_CHECK_EQ(GLsizei(3 * mesh.triangles.size()), index_count);
            if (change == core::MeshChange::kNone) return;
        }
        const auto position_bytes = GLsizeiptr(mesh.positions.size() * sizeof(glm::vec3));
        fn.BindVertexArray(vao);
        fn.BindBuffer(GL_ARRAY_BUFFER, positions);
        if (everything) {
            fn.BufferData(GL_ARRAY_BUFFER, position_bytes, mesh.positions.data(), GL_DYNAMIC_DRAW);
            fn.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
            fn.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.triangles.size() * sizeof(glm::uvec3)),
                          mesh.triangles.data(), GL_STATIC_DRAW);
            vertex_count = mesh.positions.size();
            index_count = GLsizei(3 * mesh.triangles.size());
            uploaded = true;
            build_vertex_faces(mesh);
            vertex_mark.assign(mesh.positions.size(), 0);
            face_mark.assign(mesh.triangles.size(), 0);
            epoch = 0;
        } else {
            fn.BufferSubData(GL_ARRAY_BUFFER, 0, position_bytes, mesh.positions.data());
        }
        check_gl(fn, "uploading the mesh");
    }

    // The local ray test: does a face near the query, which the texels may have missed, cross
    // the segment from the eye to it? Candidates are the faces around a set of vertices: the
    // ends of the query's edge (along a mesh silhouette, the faces next to the edge are grazing
    // slivers thinner than a texel that can still cover it); on a depth discontinuity also the
    // corners of the faces seen around the point (the texels cannot say on which side of the
    // occluder's outline the point lies; those faces and their neighbours can); then every
    // vertex reached from these through mesh edges that projects within kNearTexels.
    bool covered_nearby(const glm::dvec3& from, const core::OcclusionQuery& query, const internal::DepthSample& sample,
                        internal::DepthVerdict verdict) const {
        const core::Mesh& mesh = *frame_mesh;
        const core::EdgeTable& table = *frame_table;
        // Marks of this query: a new epoch, or a clean slate when the counter wraps.
        if (++epoch == 0) {
            std::fill(vertex_mark.begin(), vertex_mark.end(), 0);
            std::fill(face_mark.begin(), face_mark.end(), 0);
            epoch = 1;
        }
        candidates.clear();
        auto add_vertex = [&](uint32_t v) {
            if (vertex_mark[v] == epoch) return;
            vertex_mark[v] = epoch;
            candidates.push_back(v);
        };
        const glm::uvec2 ends = table.edge_vertices[query.edge];
        add_vertex(ends.x);
        add_vertex(ends.y);
        // Face ids read from the map are exact only below kMaxFaceId.
        if (verdict == internal::DepthVerdict::kEdge && mesh.triangles.size() < internal::kMaxFaceId) {
            seen.clear();
            internal::faces_around(map, sample.p_window, kSeenRings, seen);
            for (uint32_t f : seen) {
                for (int c = 0; c < 3; ++c) add_vertex(mesh.triangles[f][c]);
            }
        }
        const glm::dvec2 size(map.width, map.height);
        for (size_t k = 0; k < candidates.size(); ++k) {
            for (uint32_t e : table.edges_around(candidates[k])) {
                const uint32_t v = table.other_vertex(e, candidates[k]);
                if (vertex_mark[v] == epoch) continue;
                const glm::dvec4 clip = projection->clip(glm::dvec3(mesh.positions[v]));
                if (clip.w <= 0.0) continue;
                const glm::dvec2 p_window = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * size;
                if (glm::length(p_window - sample.p_window) <= kNearTexels) add_vertex(v);
            }
        }
        for (uint32_t v : candidates) {
            for (uint32_t f : faces_at(v)) {
                if (face_mark[f] == epoch || !table.face_valid[f] || is_own(query, f)) continue;
                face_mark[f] = epoch;
                const glm::uvec3 t = mesh.triangles[f];
                if (segment_hits(from, query.p_object, glm::dvec3(mesh.positions[t.x]), glm::dvec3(mesh.positions[t.y]),
                                 glm::dvec3(mesh.positions[t.z]))) {
                    return true;
                }
            }
        }
        return false;
    }

    // A smooth contour point's own faces (the neighbourhood of the face it crosses) never cover
    // it; other points rely on the segment's end gap, as exact visibility does.
    static bool is_own(const core::OcclusionQuery& query, uint32_t face) {
        return !query.own_faces.empty() && std::binary_search(query.own_faces.begin(), query.own_faces.end(), face);
    }

    // True when a face seen at the four texels around the point crosses the segment from -> p.
    bool seen_faces_cover(const glm::dvec3& from, const core::OcclusionQuery& query,
                          const internal::DepthSample& sample) const {
        const core::Mesh& mesh = *frame_mesh;
        const glm::dvec3& p = query.p_object;
        seen.clear();
        internal::faces_around(map, sample.p_window, 0, seen);
        for (uint32_t f : seen) {
            if (is_own(query, f)) continue;
            const glm::uvec3 t = mesh.triangles[f];
            if (segment_hits(from, p, glm::dvec3(mesh.positions[t.x]), glm::dvec3(mesh.positions[t.y]),
                             glm::dvec3(mesh.positions[t.z]))) {
                return true;
            }
        }
        return false;
    }

    void build_vertex_faces(const core::Mesh& mesh) {
        vertex_face_offsets.assign(mesh.positions.size() + 1, 0);
        for (const glm::uvec3& t : mesh.triangles) {
            for (int c = 0; c < 3; ++c) ++vertex_face_offsets[t[c] + 1];
        }
        for (size_t v = 0; v < mesh.positions.size(); ++v) vertex_face_offsets[v + 1] += vertex_face_offsets[v];
        vertex_faces.resize(vertex_face_offsets.back());
        std::vector<uint32_t> fill(vertex_face_offsets.begin(), vertex_face_offsets.end() - 1);
        for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
            for (int c = 0; c < 3; ++c) vertex_faces[fill[mesh.triangles[f][c]]++] = f;
        }
    }

    std::span<const uint32_t> faces_at(uint32_t v) const {
        return {vertex_faces.data() + vertex_face_offsets[v], vertex_face_offsets[v + 1] - vertex_face_offsets[v]};
    }

    // (Re)allocates the framebuffer when the depth-map size changes.
    void resize(int width, int height) {
        if (width == map.width && height == map.height) return;
        fn.BindRenderbuffer(GL_RENDERBUFFER, color);
        fn.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, width, height);
        fn.BindRenderbuffer(GL_RENDERBUFFER, depth);
        fn.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
        fn.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        fn.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
        fn.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        check_gl(fn, "allocating the depth map");
        if (fn.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw ContextError("the GL context cannot render to an RGBA32F framebuffer of " +
                               std::to_string(width) + "x" + std::to_string(height));
        }
        map.width = width;
        map.height = height;
        map.texels.assign(size_t(width) * size_t(height), {});
    }

    void render(const core::Projection& proj) {
        // Clip-space matrix in float: the same one the CPU test applies in double.
        const glm::mat4 clip_from_object(clip_from_object_of(proj));
        fn.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        const GLenum draw_buffer = GL_COLOR_ATTACHMENT0;
        fn.DrawBuffers(1, &draw_buffer);
        fn.Viewport(0, 0, map.width, map.height);
        const GLfloat no_surface[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const GLfloat far_depth = 1.0f;
        fn.ClearBufferfv(GL_COLOR, 0, no_surface);
        fn.DepthMask(GL_TRUE);
        fn.ClearBufferfv(GL_DEPTH, 0, &far_depth);
        fn.Enable(GL_DEPTH_TEST);
        fn.DepthFunc(GL_LESS);
        // Occluders between the eye and the near plane count in the exact definition, and the
        // far plane must not cut the mesh: depth clamping turns off near and far clipping.
        fn.Enable(GL_DEPTH_CLAMP);
        fn.Disable(GL_CULL_FACE);  // back faces occlude too
        fn.UseProgram(program);
        fn.UniformMatrix4fv(clip_from_object_location, 1, GL_FALSE, &clip_from_object[0][0]);
        fn.Uniform1i(orthographic_location, proj.orthographic() ? 1 : 0);
        fn.BindVertexArray(vao);
        fn.DrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
        fn.Finish();
        check_gl(fn, "rendering the depth map");
    }

    void read_back() {
        fn.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
        fn.ReadBuffer(GL_COLOR_ATTACHMENT0);
        fn.PixelStorei(GL_PACK_ALIGNMENT, 4);
        fn.ReadPixels(0, 0, map.width, map.height, GL_RGBA, GL_FLOAT, map.texels.data());
        check_gl(fn, "reading back the depth map");
    }
};

DepthOcclusion::DepthOcclusion(const Context& context, const DepthVisibilityOptions& options)
    : impl_(std::make_unique<Impl>()) {
    if (options.supersampling < 1) {
        throw InputError("depth-map supersampling " + std::to_string(options.supersampling) +
                         ": expected 1 or more");
    }
    Impl& m = *impl_;
    m.options = options;
    m.fn = internal::load_functions(context);
    const internal::Functions& fn = m.fn;
    m.program = internal::link_program(fn, kVertexShader, kFragmentShader, "depth pass");
    m.clip_from_object_location = fn.GetUniformLocation(m.program, "clip_from_object");
    m.orthographic_location = fn.GetUniformLocation(m.program, "orthographic");
    fn.GenVertexArrays(1, &m.vao);
    fn.GenBuffers(1, &m.positions);
    fn.GenBuffers(1, &m.indices);
    fn.BindVertexArray(m.vao);
    fn.BindBuffer(GL_ARRAY_BUFFER, m.positions);
    fn.EnableVertexAttribArray(0);
    fn.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    fn.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.indices);
    fn.GenFramebuffers(1, &m.framebuffer);
    fn.GenRenderbuffers(1, &m.color);
    fn.GenRenderbuffers(1, &m.depth);
    GLint renderbuffer_size = 0, viewport_size[2] = {0, 0};
    fn.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer_size);
    fn.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport_size);
    m.max_size = std::min({renderbuffer_size, viewport_size[0], viewport_size[1]});
    check_gl(fn, "setting up the depth pass");
}

DepthOcclusion::~DepthOcclusion() = default;

void DepthOcclusion::prepare(const core::Mesh& mesh, const core::EdgeTable& table, const core::Projection& projection,
                             core::MeshChange change) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    Impl& m = *impl_;
    const core::ImageSize image = projection.image();
    const int side = std::max(image.width, image.height);
    if (side > m.max_size) {
        throw InputError("image " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " is larger than this GL's framebuffer limit of " + std::to_string(m.max_size) +
                         " px; use a smaller --size or --visibility exact");
    }
    // The factor asked for, lowered to fit GL's size limit and the texel budget (at least 1).
    const double pixels = double(image.width) * double(image.height);
    const int budget = std::max(1, int(std::sqrt(double(kMaxTexels) / pixels)));
    const int supersampling = std::min({m.options.supersampling, m.max_size / side, budget});

    auto start = std::chrono::steady_clock::now();
    m.upload(mesh, change);
    m.stats.upload_ms = ms_since(start);

    start = std::chrono::steady_clock::now();
    m.resize(image.width * supersampling, image.height * supersampling);
    m.render(projection);
    m.stats.render_ms = ms_since(start);

    start = std::chrono::steady_clock::now();
    m.read_back();
    m.stats.readback_ms = ms_since(start);

    m.stats.width = m.map.width;
    m.stats.height = m.map.height;
    m.stats.supersampling = supersampling;
    m.projection = projection;
    m.reach = projection.orthographic() ? core::occlusion_reach(mesh.positions) : 0.0;
    m.frame_mesh = &mesh;
    m.frame_table = &table;
}

void DepthOcclusion::occluded(const core::Viewpoint& eye_object, std::span<const core::OcclusionQuery> queries,
                              std::span<uint8_t> r_occluded) const {
    INKLINE_CHECK_EQ(queries.size(), r_occluded.size());
    const Impl& m = *impl_;
    INKLINE_CHECK(m.projection.has_value());  // prepare() comes first
    const core::Projection& projection = *m.projection;
    // The caller's eye must be the prepared one; a stale depth map would answer silently.
    const core::Viewpoint& prepared = projection.eye_object();
    INKLINE_CHECK(eye_object.w == prepared.w &&
                  glm::length(eye_object.xyz - prepared.xyz) <= 1e-9 * (1.0 + glm::length(eye_object.xyz)));
    const glm::dvec2 size(m.map.width, m.map.height);
    for (size_t i = 0; i < queries.size(); ++i) {
        const glm::dvec4 clip = projection.clip(queries[i].p_object);
        if (clip.w <= 0.0) {
            r_occluded[i] = 0;  // behind the eye: outside the view, not occluded
            continue;
        }
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        const internal::DepthSample sample{(ndc * 0.5 + 0.5) * size, depth_q(projection, clip)};
        // The segment towards the eye starts at the eye, or towards one at infinity where
        // exact visibility starts it.
        const glm::dvec3 from = eye_object.orthographic()
                                    ? core::occlusion_segment_end(queries[i].p_object, eye_object, m.reach)
                                    : eye_object.xyz;
        const internal::DepthVerdict verdict = internal::classify_in_depth_map(m.map, sample);
        bool hidden = verdict == internal::DepthVerdict::kHidden;
        if (m.options.local_ray_test) {
            if (!hidden) {
                hidden = m.covered_nearby(from, queries[i], sample, verdict);
            } else if (m.frame_mesh->triangles.size() < internal::kMaxFaceId) {
                // The planes seen around the point all pass in front of it, but a plane is not its
                // face: in a valley narrower than a texel, the neighbours' planes do and their
                // faces do not. The faces themselves confirm it, or the full local test decides.
                hidden = m.seen_faces_cover(from, queries[i], sample) ||
                         m.covered_nearby(from, queries[i], sample, internal::DepthVerdict::kEdge);
            }
        }
        r_occluded[i] = hidden ? 1 : 0;
    }
}

const DepthPassStats& DepthOcclusion::last_pass() const { return impl_->stats; }

DepthOcclusionSource::DepthOcclusionSource(const Context& context, const DepthVisibilityOptions& options)
    : context_(context), options_(options) {}

DepthOcclusionSource::~DepthOcclusionSource() = default;

const core::Occlusion& DepthOcclusionSource::prepare(const core::Mesh& mesh, const core::EdgeTable& table,
                                                     const core::Projection& projection, core::MeshChange change) {
    if (!depth_) depth_ = std::make_unique<DepthOcclusion>(context_, options_);
    depth_->prepare(mesh, table, projection, change);
    return *depth_;
}

std::string DepthOcclusionSource::device() const {
    return context_.backend_name() + std::string(": ") + context_.renderer();
}

}  // namespace inkline::gl
