// SPDX-License-Identifier: MIT
#include "gl/preview.h"

#include "core/error.h"
#include "core/lines/smooth_pieces.h"
#include "core/scene/camera.h"
#include "gl/internal/functions.h"
#include "gl/internal/quad_strip.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <new>
#include <span>
#include <string>
#include <vector>

namespace inkline::gl {
namespace {

// Image pixels (origin top-left, y down) to clip space with y kept downward, so that GL's
// window row 0 is the image's top row and glReadPixels returns rows from the top.
constexpr const char* kStrokeVertexShader = R"(#version 330 core
layout(location = 0) in vec2 p_px;
layout(location = 1) in vec2 across_in;
layout(location = 2) in float s_in;
layout(location = 3) in float u_in;
layout(location = 4) in float width_in;
uniform vec2 image_size;
out vec2 across;
out float s;
out float u;
out float width;
void main() {
    gl_Position = vec4(p_px / image_size * 2.0 - 1.0, 0.0, 1.0);
    across = across_in;
    s = s_in;
    u = u_in;
    width = width_in;
}
)";

// Tone: triangles in pixels, one flat ink.
constexpr const char* kToneVertexShader = R"(#version 330 core
layout(location = 0) in vec2 p_px;
uniform vec2 image_size;
void main() {
    gl_Position = vec4(p_px / image_size * 2.0 - 1.0, 0.0, 1.0);
}
)";
constexpr const char* kToneFragmentShader = R"(#version 330 core
uniform vec3 ink;  // sRGB
uniform float opacity;
layout(location = 0) out vec4 colour;
void main() {
    colour = vec4(ink * opacity, opacity);  // premultiplied
}
)";

// Sides of the polygon a dot is drawn as.
constexpr int kDotSides = 16;

// The triangles of a frame's tone, one list per ink (one list with fewer than two inks): each dot
// a polygon round its centre, each hatch a quad per segment, its corners offset across the line
// by half its width at each end.
std::vector<std::vector<glm::vec2>> tone_triangles(const core::FrameTone& tone) {
    std::vector<std::vector<glm::vec2>> by_ink(std::max<size_t>(1, tone.inks.size()));
    const auto list = [&](uint16_t ink) -> std::vector<glm::vec2>& {
        return by_ink[std::min<size_t>(ink, by_ink.size() - 1)];
    };
    for (const core::Dot& dot : tone.dots) {
        std::vector<glm::vec2>& out = list(dot.ink);
        const glm::dvec2 c = dot.point_px;
        for (int k = 0; k < kDotSides; ++k) {
            const double a0 = 2.0 * glm::pi<double>() * k / kDotSides;
            const double a1 = 2.0 * glm::pi<double>() * (k + 1) / kDotSides;
            out.emplace_back(c);
            out.emplace_back(c + dot.radius_px * glm::dvec2(std::cos(a0), std::sin(a0)));
            out.emplace_back(c + dot.radius_px * glm::dvec2(std::cos(a1), std::sin(a1)));
        }
    }
    for (const core::Hatch& hatch : tone.hatches) {
        std::vector<glm::vec2>& out = list(hatch.ink);
        const std::vector<glm::dvec2>& p = hatch.points_px;
        for (size_t i = 0; i + 1 < p.size(); ++i) {
            const glm::dvec2 d = p[i + 1] - p[i];
            const double length = glm::length(d);
            if (!(length > 0.0)) continue;
            const glm::dvec2 across = glm::dvec2(-d.y, d.x) / length;
            const glm::dvec2 a0 = p[i] + 0.5 * hatch.width_px[i] * across, a1 = p[i] - 0.5 * hatch.width_px[i] * across;
            const glm::dvec2 b0 = p[i + 1] + 0.5 * hatch.width_px[i + 1] * across;
            const glm::dvec2 b1 = p[i + 1] - 0.5 * hatch.width_px[i + 1] * across;
            for (const glm::dvec2& v : {a0, a1, b0, b0, a1, b1}) out.emplace_back(v);
        }
    }
    return by_ink;
}

// The tip image as alpha. Along the stroke: its head over the first head_px and its tail over
// the last tail_px where those ends are free (S: the brush is set down and lifted there; a
// blunt A or C end runs into another stroke, so the line carries on through it), its middle
// repeated by u elsewhere (u is carried from frame to frame, so the texture stays on the paper
// as the stroke moves); across: v from one edge to the other, and on a cap the distance from
// its centre, so the edge's profile runs round the cap.
constexpr const char* kStrokeFragmentShader = R"(#version 330 core
in vec2 across;
in float s;
in float u;
in float width;
uniform sampler2D tip;
uniform float tip_length;     // px along the stroke of the whole image
uniform vec3 zones;           // head, middle and tail fractions of the image width
uniform float stroke_length;  // px
uniform float period;         // px of one repeat of the middle
uniform vec2 free_ends;       // 1 where the start, the end is free: it shows the head, the tail
uniform vec3 ink;             // sRGB
uniform float opacity;
uniform vec3 pressure;        // width_min_px, 1 / (width_max_px - width_min_px) or 0, darkening
uniform float dash[32];       // the style's dash pattern along u, px: on, off, on, ... (even count)
uniform int dash_count;       // 0: solid
uniform float dash_period;    // the pattern's length, px
uniform int cap;              // the dashes' ends: 0 round, 1 butt, 2 square
uniform vec2 u_range;         // where the line begins and ends along u: its ends end a dash too
uniform float widen;          // strip half-widths per brush half-width
uniform int plain;            // 1: a plain line in the ink (hidden lines), no tip texture
layout(location = 0) out vec4 colour;

// Along-coordinates of the middle (by u) and of the head and tail (by s, clamped to their zones),
// and how much of the head and of the tail shows at s: each fades into the middle over the
// last part of its zone next to the middle, so no seam shows where the zones meet.
struct Along {
    float middle, head, tail, head_weight, tail_weight;
};
const float kZoneBlend = 0.4;  // fraction of a zone, next to the middle, over which it fades

Along along() {
    Along a;
    a.middle = zones.x + zones.y * fract(u / period);
    a.head_weight = 0.0;
    a.tail_weight = 0.0;
    a.head = 0.0;
    a.tail = 1.0;
    float head_px = free_ends.x * zones.x * tip_length;
    float tail_px = free_ends.y * zones.z * tip_length;
    if (head_px + tail_px == 0.0) return a;
    // A stroke shorter than head and tail together shows both, shortened alike.
    float k = min(1.0, stroke_length / max(head_px + tail_px, 1e-6));
    head_px = max(head_px * k, 1e-6);
    tail_px = max(tail_px * k, 1e-6);
    float sc = clamp(s, 0.0, stroke_length);
    float to_end = stroke_length - sc;
    a.head = zones.x * min(sc / head_px, 1.0);
    a.tail = 1.0 - zones.z * min(to_end / tail_px, 1.0);
    a.head_weight = free_ends.x * (1.0 - smoothstep((1.0 - kZoneBlend) * head_px, head_px, sc));
    a.tail_weight = free_ends.y * (1.0 - smoothstep((1.0 - kZoneBlend) * tail_px, tail_px, to_end));
    return a;
}

// Whether a sample at u, `side` brush half-widths off the centerline, is in a dash with its caps
// (docs/styles.md): round caps reach half a width past a dash's ends as a disc does, square caps
// as a square does, butt caps not at all; a dash of length 0 is a dot. A dash the line's end
// cuts ends there, with its cap, as SVG's dashes do.
bool in_dash(float side) {
    float m = mod(u, dash_period);
    float base = u - m;  // where the pattern's repeat holding u begins
    float half_width = max(0.5 * width, 1e-6);
    for (int shift = -1; shift <= 1; ++shift) {
        float at = float(shift) * dash_period;
        for (int i = 0; i < dash_count; i += 2) {
            float a = max(at, u_range.x - base), b = min(at + dash[i], u_range.y - base);
            at += dash[i] + dash[i + 1];
            if (a > b) continue;
            float past = max(max(a - m, m - b), 0.0) / half_width;
            if (cap == 0 && past * past + side * side <= 1.0) return true;
            if (cap == 1 && past == 0.0 && b > a) return true;
            if (cap == 2 && past <= 1.0) return true;
        }
    }
    return false;
}

void main() {
    if (dash_count > 0 && !in_dash(across.x * widen)) discard;
    if (plain != 0) {
        colour = vec4(ink * opacity, opacity);  // premultiplied
        return;
    }
    float r = length(across);
    float v = 0.5 + 0.5 * (across.x < 0.0 ? -r : r);
    // Mip level from the continuous coordinates: the middle's wrap-around would otherwise pick
    // the smallest level along every seam.
    vec2 dx = vec2(dFdx(s) / tip_length, 0.5 * dFdx(r));
    vec2 dy = vec2(dFdy(s) / tip_length, 0.5 * dFdy(r));
    float y = clamp(v, 0.0, 1.0);
    Along x = along();
    float a = textureGrad(tip, vec2(x.middle, y), dx, dy).r;
    if (x.tail_weight > 0.0) a = mix(a, textureGrad(tip, vec2(x.tail, y), dx, dy).r, x.tail_weight);
    if (x.head_weight > 0.0) a = mix(a, textureGrad(tip, vec2(x.head, y), dx, dy).r, x.head_weight);
    a *= opacity;
    float p = clamp((width - pressure.x) * pressure.y, 0.0, 1.0);
    colour = vec4(ink * (1.0 - pressure.z * p) * a, a);  // premultiplied
}
)";

constexpr const char* kSurfaceVertexShader = R"(#version 330 core
layout(location = 0) in vec3 p_object;
layout(location = 1) in vec3 n_object;
uniform mat4 clip_from_object;
uniform mat4 world_from_object;
uniform mat4 normal_world_from_object;
out vec3 p_world;
out vec3 n_world;
void main() {
    gl_Position = clip_from_object * vec4(p_object, 1.0);
    p_world = (world_from_object * vec4(p_object, 1.0)).xyz;
    n_world = mat3(normal_world_from_object) * n_object;
}
)";

// Lambert with the frame's light, both sides lit as the side facing the eye; toon shading
// quantises it into three bands of paper tones.
constexpr const char* kSurfaceFragmentShader = R"(#version 330 core
in vec3 p_world;
in vec3 n_world;
uniform vec4 eye_world;  // w = 0: towards an orthographic camera's viewer
uniform vec3 light;  // direction from the light, or a point light's position
uniform int point_light;
uniform int toon;
layout(location = 0) out vec4 colour;
const vec3 kLit = vec3(0.97, 0.96, 0.93);
const vec3 kMid = vec3(0.85, 0.84, 0.81);
const vec3 kShadow = vec3(0.68, 0.68, 0.68);
void main() {
    vec3 n = toon != 0 ? normalize(n_world) : normalize(cross(dFdx(p_world), dFdy(p_world)));
    if (dot(n, eye_world.xyz - eye_world.w * p_world) < 0.0) n = -n;
    vec3 to_light = point_light != 0 ? normalize(light - p_world) : -normalize(light);
    float i = max(dot(n, to_light), 0.0);
    vec3 c = toon != 0 ? (i > 0.6 ? kLit : i > 0.25 ? kMid : kShadow) : mix(kShadow, kLit, i);
    colour = vec4(c, 1.0);
}
)";

// Stencil values tell strokes apart so that none blends over itself (one stroke per value,
// cleared when they run out).
constexpr int kStencilValues = 255;

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Throws for a GL error recorded since the last check: std::bad_alloc for GL_OUT_OF_MEMORY, a
// ContextError otherwise; a preview that failed is never read back or written.
void check_gl(const internal::Functions& fn, const char* step) {
    const GLenum error = fn.GetError();
    if (error == GL_OUT_OF_MEMORY) throw std::bad_alloc();
    if (error != GL_NO_ERROR) {
        throw ContextError(std::string("GL error ") + std::to_string(error) + " while " + step +
                           " (out of memory for the preview? try fewer samples or a smaller image)");
    }
}

// One stroke's range in the frame's index buffer and what its shader needs.
struct StrokeDraw {
    const core::BrushStyle* brush = nullptr;  // its style's: ink, pressure and dashes
    // A hidden line: a plain dashed line of this width at half the ink's opacity, dashed from
    // u = dash_offset, as the vector outputs stroke it; 0: a brush stroke.
    float hidden_width_px = 0.0f;
    float dash_offset_px = 0.0f;
    size_t first_index = 0;
    GLsizei index_count = 0;
    float length_px = 0.0f;
    float period_px = 0.0f;
    bool free_start = false;  // an S end: shows the tip's head
    bool free_end = false;    // an S end: shows the tip's tail
    bool closed = false;
};

// Unit normals in float, for the GL buffers; a zero normal (no faces, or faces that cancel)
// faces +z.
std::vector<glm::vec3> float_normals(const std::vector<glm::dvec3>& normals) {
    std::vector<glm::vec3> out(normals.size(), glm::vec3(0.0f, 0.0f, 1.0f));
    for (size_t v = 0; v < normals.size(); ++v) {
        if (normals[v] != glm::dvec3(0.0)) out[v] = glm::vec3(normals[v]);
    }
    return out;
}

}  // namespace

struct PreviewRenderer::Impl {
    internal::Functions fn;
    core::BrushStyle style;
    PreviewOptions options;
    BrushTip tip_layout;  // fractions and margin; pixels live in the texture
    double tip_length_px = 0.0;
    int samples = 1;
    GLint max_size = 0;

    GLuint stroke_program = 0, surface_program = 0, tone_program = 0;
    GLuint tone_vao = 0, tone_vertices = 0;
    GLuint stroke_vao = 0, stroke_vertices = 0, stroke_indices = 0;
    GLuint surface_vao = 0, surface_positions = 0, surface_normals = 0, surface_indices = 0;
    // The toon underlay split at creases: the sides' edges of the table's faces (constant with
    // the table), and the smooth pieces, their buffers kept from frame to frame.
    const core::EdgeTable* split_table = nullptr;
    std::vector<glm::uvec3> split_face_edges;
    core::SmoothPieces split_pieces;
    std::vector<glm::vec3> split_positions;
    GLuint tip_texture = 0;
    GLuint msaa_fbo = 0, msaa_color = 0, msaa_depth_stencil = 0;
    GLuint resolve_fbo = 0, resolve_color = 0;
    int fb_width = 0, fb_height = 0;
    PreviewStats stats;

    struct StrokeUniforms {
        GLint image_size, tip, tip_length, zones, stroke_length, period, free_ends, ink, opacity, pressure, dash,
            dash_count, dash_period, cap, u_range, widen, plain;
    } su{};
    struct ToneUniforms {
        GLint image_size, ink, opacity;
    } tu{};
    struct SurfaceUniforms {
        GLint clip_from_object, world_from_object, normal_world_from_object, eye_world, light, point_light, toon;
    } fu{};

    ~Impl() {
        if (!fn.DeleteProgram) return;  // loading failed: nothing was created
        fn.DeleteFramebuffers(1, &msaa_fbo);
        fn.DeleteFramebuffers(1, &resolve_fbo);
        const GLuint renderbuffers[] = {msaa_color, msaa_depth_stencil, resolve_color};
        fn.DeleteRenderbuffers(3, renderbuffers);
        fn.DeleteTextures(1, &tip_texture);
        const GLuint buffers[] = {stroke_vertices, stroke_indices, surface_positions,
                                  surface_normals, surface_indices, tone_vertices};
        fn.DeleteBuffers(6, buffers);
        const GLuint arrays[] = {stroke_vao, surface_vao, tone_vao};
        fn.DeleteVertexArrays(3, arrays);
        fn.DeleteProgram(stroke_program);
        fn.DeleteProgram(surface_program);
        fn.DeleteProgram(tone_program);
    }

    void setup(const BrushTip& tip) {
        stroke_program = internal::link_program(fn, kStrokeVertexShader, kStrokeFragmentShader, "preview");
        surface_program = internal::link_program(fn, kSurfaceVertexShader, kSurfaceFragmentShader, "preview");
        tone_program = internal::link_program(fn, kToneVertexShader, kToneFragmentShader, "preview");
        tu = {fn.GetUniformLocation(tone_program, "image_size"), fn.GetUniformLocation(tone_program, "ink"),
              fn.GetUniformLocation(tone_program, "opacity")};
        auto stroke_uniform = [&](const char* name) { return fn.GetUniformLocation(stroke_program, name); };
        su = {stroke_uniform("image_size"), stroke_uniform("tip"),           stroke_uniform("tip_length"),
              stroke_uniform("zones"),      stroke_uniform("stroke_length"), stroke_uniform("period"),
              stroke_uniform("free_ends"),  stroke_uniform("ink"),           stroke_uniform("opacity"),
              stroke_uniform("pressure"),   stroke_uniform("dash"),          stroke_uniform("dash_count"),
              stroke_uniform("dash_period"), stroke_uniform("cap"),          stroke_uniform("u_range"),
              stroke_uniform("widen"),      stroke_uniform("plain")};
        auto surface_uniform = [&](const char* name) { return fn.GetUniformLocation(surface_program, name); };
        fu = {surface_uniform("clip_from_object"),
              surface_uniform("world_from_object"),
              surface_uniform("normal_world_from_object"),
              surface_uniform("eye_world"),
              surface_uniform("light"),
              surface_uniform("point_light"),
              surface_uniform("toon")};

        // Stroke vertices: internal::StripVertex, 7 floats.
        fn.GenVertexArrays(1, &stroke_vao);
        fn.GenBuffers(1, &stroke_vertices);
        fn.GenBuffers(1, &stroke_indices);
        fn.BindVertexArray(stroke_vao);
        fn.BindBuffer(GL_ARRAY_BUFFER, stroke_vertices);
        const auto stride = GLsizei(sizeof(internal::StripVertex));
        const struct {
            GLint size;
            size_t offset;
        } attributes[] = {{2, offsetof(internal::StripVertex, p_px)},
                          {2, offsetof(internal::StripVertex, across)},
                          {1, offsetof(internal::StripVertex, s_px)},
                          {1, offsetof(internal::StripVertex, u_px)},
                          {1, offsetof(internal::StripVertex, width_px)}};
        for (GLuint i = 0; i < 5; ++i) {
            fn.EnableVertexAttribArray(i);
            fn.VertexAttribPointer(i, attributes[i].size, GL_FLOAT, GL_FALSE, stride,
                                   reinterpret_cast<const void*>(attributes[i].offset));
        }
        fn.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, stroke_indices);

        // Surface: positions and normals, one vec3 each.
        fn.GenVertexArrays(1, &surface_vao);
        fn.GenBuffers(1, &surface_positions);
        fn.GenBuffers(1, &surface_normals);
        fn.GenBuffers(1, &surface_indices);
        fn.BindVertexArray(surface_vao);
        fn.BindBuffer(GL_ARRAY_BUFFER, surface_positions);
        fn.EnableVertexAttribArray(0);
        fn.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
        fn.BindBuffer(GL_ARRAY_BUFFER, surface_normals);
        fn.EnableVertexAttribArray(1);
        fn.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
        fn.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, surface_indices);

        // Tone: one vec2 per vertex, triangles in order.
        fn.GenVertexArrays(1, &tone_vao);
        fn.GenBuffers(1, &tone_vertices);
        fn.BindVertexArray(tone_vao);
        fn.BindBuffer(GL_ARRAY_BUFFER, tone_vertices);
        fn.EnableVertexAttribArray(0);
        fn.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(glm::vec2), nullptr);
        fn.BindVertexArray(0);

        // The tip: one channel, mipmapped, so thin strokes average its streaks instead of
        // aliasing them.
        GLint max_texture = 0;
        fn.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
        if (tip.width > max_texture || tip.height > max_texture) {
            throw InputError("brush tip of " + std::to_string(tip.width) + "x" + std::to_string(tip.height) +
                             " px exceeds this GL's texture limit of " + std::to_string(max_texture) + " px");
        }
        fn.GenTextures(1, &tip_texture);
        fn.ActiveTexture(GL_TEXTURE0);
        fn.BindTexture(GL_TEXTURE_2D, tip_texture);
        fn.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        fn.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, tip.width, tip.height, 0, GL_RED, GL_UNSIGNED_BYTE, tip.alpha.data());
        fn.GenerateMipmap(GL_TEXTURE_2D);
        fn.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        fn.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        fn.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        fn.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

        fn.GenFramebuffers(1, &msaa_fbo);
        fn.GenFramebuffers(1, &resolve_fbo);
        fn.GenRenderbuffers(1, &msaa_color);
        fn.GenRenderbuffers(1, &msaa_depth_stencil);
        fn.GenRenderbuffers(1, &resolve_color);
        GLint max_samples = 1, renderbuffer_size = 0, viewport_size[2] = {0, 0};
        fn.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
        fn.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer_size);
        fn.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport_size);
        samples = std::clamp(options.samples, 1, std::max(max_samples, 1));
        max_size = std::min({renderbuffer_size, viewport_size[0], viewport_size[1]});
        check_gl(fn, "setting up the preview");
    }

    // (Re)allocates the multisampled and the resolve framebuffers for an image size.
    void resize(int width, int height) {
        if (width == fb_width && height == fb_height) return;
        fn.BindRenderbuffer(GL_RENDERBUFFER, msaa_color);
        fn.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
        fn.BindRenderbuffer(GL_RENDERBUFFER, msaa_depth_stencil);
        fn.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width, height);
        fn.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo);
        fn.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color);
        fn.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, msaa_depth_stencil);
        const GLenum msaa_status = fn.CheckFramebufferStatus(GL_FRAMEBUFFER);
        fn.BindRenderbuffer(GL_RENDERBUFFER, resolve_color);
        fn.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        fn.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
        fn.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_color);
        check_gl(fn, "allocating the preview framebuffers");
        if (msaa_status != GL_FRAMEBUFFER_COMPLETE ||
            fn.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw ContextError("the GL context cannot render a " + std::to_string(width) + "x" +
                               std::to_string(height) + " RGBA8 framebuffer with " + std::to_string(samples) +
                               " samples");
        }
        fb_width = width;
        fb_height = height;
    }

    // Every drawn visible stroke's strip, then every hidden line's, in one vertex and one index
    // buffer.
    std::vector<StrokeDraw> upload_strokes(const core::FrameStrokes& strokes) {
        const internal::QuadStripOptions strip_options{.widen = 1.0 / (1.0 - 2.0 * tip_layout.edge_margin)};
        const double middle_px = (1.0 - tip_layout.head_fraction - tip_layout.tail_fraction) * tip_length_px;
        std::vector<internal::StripVertex> vertices;
        std::vector<uint32_t> indices;
        std::vector<StrokeDraw> draws;
        // A styled stroke in its style's brush; the others in the renderer's.
        const auto brush_of = [&](const core::Stroke& stroke) -> const core::BrushStyle& {
            const bool styled = stroke.style != 0 && stroke.style < strokes.styles.size();
            return styled ? strokes.styles[stroke.style].brush : style;
        };
        // The strip's triangles into the buffers, as `r_draw`'s range.
        const auto append = [&](const internal::QuadStrip& strip, StrokeDraw& r_draw) {
            r_draw.first_index = indices.size();
            r_draw.index_count = GLsizei(strip.indices.size());
            r_draw.length_px = float(strip.length_px);
            r_draw.closed = strip.closed;
            const auto base = uint32_t(vertices.size());
            for (const uint32_t i : strip.indices) indices.push_back(base + i);
            vertices.insert(vertices.end(), strip.vertices.begin(), strip.vertices.end());
        };
        for (const core::Stroke& stroke : strokes.strokes) {
            if (!stroke.geometry.visible || !stroke.drawn) continue;
            internal::QuadStrip strip = internal::quad_strip(stroke, strip_options);
            if (strip.indices.empty()) continue;
            StrokeDraw draw;
            draw.brush = &brush_of(stroke);
            append(strip, draw);
            draw.free_start = !strip.closed && stroke.geometry.ends[0] == core::StrokeEnd::kFree;
            draw.free_end = !strip.closed && stroke.geometry.ends[1] == core::StrokeEnd::kFree;
            // A loop repeats the middle a whole number of times, so it has no seam.
            const double period = std::max(middle_px, 1e-3);
            draw.period_px =
                float(strip.closed ? strip.length_px / std::max(1.0, std::round(strip.length_px / period)) : period);
            draws.push_back(draw);
        }
        // Hidden lines above them, as the vector outputs layer them: along the drawn centerline
        // where there is one.
        for (const core::Stroke& stroke : strokes.strokes) {
            const core::StrokeGeometry& g = stroke.geometry;
            if (g.visible) continue;
            const core::BrushStyle& brush = brush_of(stroke);
            const bool on_centerline = stroke.centerline_px.size() >= 2;
            const std::vector<double>& u = on_centerline ? stroke.centerline_u : stroke.u;
            StrokeDraw draw;
            draw.brush = &brush;
            draw.hidden_width_px = float(brush.line_width_px.value_or(options.centerline_width_px));
            draw.dash_offset_px = brush.dash_px.empty() || u.empty() ? 0.0f : float(u.front());
            const internal::QuadStrip strip =
                internal::centerline_strip(on_centerline ? stroke.centerline_px : g.points_px, g.closed,
                                           draw.hidden_width_px, draw.dash_offset_px, brush.cap, {});
            if (strip.indices.empty()) continue;
            append(strip, draw);
            draws.push_back(draw);
        }
        fn.BindVertexArray(stroke_vao);
        fn.BindBuffer(GL_ARRAY_BUFFER, stroke_vertices);
        fn.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(internal::StripVertex)), vertices.data(),
                      GL_STREAM_DRAW);
        fn.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(),
                      GL_STREAM_DRAW);
        check_gl(fn, "uploading the strokes");
        stats.strokes = draws.size();
        stats.triangles = indices.size() / 3;
        return draws;
    }

    void draw_surface(const core::FrameLines& frame, const PreviewSurface& surface) {
        const core::Mesh& mesh = *surface.mesh;
        // A vertex per position with vertex normals (flat shading takes its normals from screen
        // derivatives), or for toon with the edge table a vertex per smooth piece around one.
        std::span<const glm::vec3> positions = mesh.positions;
        std::span<const glm::uvec3> triangles = mesh.triangles;
        std::vector<glm::vec3> normals;
        if (options.underlay == Underlay::kToon && surface.table) {
            if (split_table != surface.table || split_face_edges.size() != mesh.triangles.size()) {
                split_table = surface.table;
                split_face_edges = core::face_edges(mesh, *surface.table);
            }
            core::smooth_pieces(mesh, *surface.table, split_face_edges, surface.crease_angle_deg, split_pieces);
            split_positions.clear();
            for (const uint32_t v : split_pieces.group_vertex) split_positions.push_back(mesh.positions[v]);
            positions = split_positions;
            triangles = split_pieces.face_groups;
            normals = float_normals(split_pieces.normals);
        } else {
            normals = float_normals(core::vertex_normals(mesh));
        }
        fn.BindVertexArray(surface_vao);
        fn.BindBuffer(GL_ARRAY_BUFFER, surface_positions);
        fn.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions.size() * sizeof(glm::vec3)), positions.data(),
                      GL_STREAM_DRAW);
        fn.BindBuffer(GL_ARRAY_BUFFER, surface_normals);
        fn.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(normals.size() * sizeof(glm::vec3)), normals.data(), GL_STREAM_DRAW);
        fn.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(triangles.size() * sizeof(glm::uvec3)), triangles.data(),
                      GL_STREAM_DRAW);
        // The camera's clip space with y flipped: the framebuffer's rows run down the image.
        const glm::dmat4 flip_y = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, -1.0, 1.0));
        const glm::mat4 clip_from_object(flip_y * core::clip_from_view(frame.camera, frame.image) *
                                         core::view_from_world(frame.camera) * surface.world_from_object);
        const glm::mat4 world_from_object(surface.world_from_object);
        const glm::mat4 normal_world_from_object(glm::inverseTranspose(glm::dmat3(surface.world_from_object)));
        const core::Light& light = frame.light;
        const glm::vec3 light_vector(light.is_point ? light.position : light.direction);
        fn.UseProgram(surface_program);
        fn.UniformMatrix4fv(fu.clip_from_object, 1, GL_FALSE, &clip_from_object[0][0]);
        fn.UniformMatrix4fv(fu.world_from_object, 1, GL_FALSE, &world_from_object[0][0]);
        fn.UniformMatrix4fv(fu.normal_world_from_object, 1, GL_FALSE, &normal_world_from_object[0][0]);
        const core::Viewpoint eye = core::viewpoint_of(frame.camera);
        fn.Uniform4f(fu.eye_world, float(eye.xyz.x), float(eye.xyz.y), float(eye.xyz.z), float(eye.w));
        fn.Uniform3f(fu.light, light_vector.x, light_vector.y, light_vector.z);
        fn.Uniform1i(fu.point_light, light.is_point ? 1 : 0);
        fn.Uniform1i(fu.toon, options.underlay == Underlay::kToon ? 1 : 0);
        fn.Enable(GL_DEPTH_TEST);
        fn.DepthFunc(GL_LESS);
        fn.DepthMask(GL_TRUE);
        fn.DrawElements(GL_TRIANGLES, GLsizei(3 * triangles.size()), GL_UNSIGNED_INT, nullptr);
        fn.Disable(GL_DEPTH_TEST);
    }

    // The tone's triangles, each sample inked once per ink: the stencil marks what is inked.
    void draw_tone(const PreviewTone& tone, core::ImageSize image) {
        const std::vector<core::ToneInk>& inks = tone.tone->inks;
        stats.tone_triangles = 0;
        const std::vector<std::vector<glm::vec2>> triangles = tone_triangles(*tone.tone);
        if (inks.empty()) {
            draw_tone_ink(triangles.front(), tone.color, tone.opacity, image);
            return;
        }
        for (size_t ink = 0; ink < inks.size(); ++ink) {
            draw_tone_ink(triangles[ink], inks[ink].color, inks[ink].opacity, image);
        }
    }

    void draw_tone_ink(const std::vector<glm::vec2>& triangles, const glm::dvec3& color, double opacity,
                       core::ImageSize image) {
        stats.tone_triangles += triangles.size() / 3;
        if (triangles.empty()) return;
        fn.UseProgram(tone_program);
        fn.BindVertexArray(tone_vao);
        fn.BindBuffer(GL_ARRAY_BUFFER, tone_vertices);
        fn.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(triangles.size() * sizeof(glm::vec2)), triangles.data(),
                      GL_STREAM_DRAW);
        fn.Uniform2f(tu.image_size, float(image.width), float(image.height));
        fn.Uniform3f(tu.ink, float(color.r), float(color.g), float(color.b));
        fn.Uniform1f(tu.opacity, float(opacity));
        fn.Enable(GL_BLEND);
        fn.BlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        fn.Enable(GL_STENCIL_TEST);
        fn.StencilMask(0xff);
        fn.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        fn.StencilFunc(GL_GREATER, 1, 0xff);
        fn.DrawArrays(GL_TRIANGLES, 0, GLsizei(triangles.size()));
        fn.Disable(GL_STENCIL_TEST);
        fn.Disable(GL_BLEND);
        // The next ink, and the strokes, count their own stencil values from a clean slate.
        fn.ClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
        check_gl(fn, "drawing the tone");
    }

    void draw_strokes(const std::vector<StrokeDraw>& draws, core::ImageSize image) {
        fn.UseProgram(stroke_program);
        fn.BindVertexArray(stroke_vao);
        fn.ActiveTexture(GL_TEXTURE0);
        fn.BindTexture(GL_TEXTURE_2D, tip_texture);
        fn.Uniform1i(su.tip, 0);
        fn.Uniform2f(su.image_size, float(image.width), float(image.height));
        fn.Uniform1f(su.tip_length, float(tip_length_px));
        const double middle = 1.0 - tip_layout.head_fraction - tip_layout.tail_fraction;
        fn.Uniform3f(su.zones, float(tip_layout.head_fraction), float(middle), float(tip_layout.tail_fraction));
        const float widen = float(1.0 / (1.0 - 2.0 * tip_layout.edge_margin));
        // Premultiplied "over": strokes layer like ink.
        fn.Enable(GL_BLEND);
        fn.BlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        // A sample takes each stroke once: where a strip folds over itself (tight bends, caps
        // over the strip) the second layer fails the stencil test.
        fn.Enable(GL_STENCIL_TEST);
        fn.StencilMask(0xff);
        fn.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        int value = 0;
        const core::BrushStyle* brush = nullptr;
        bool hidden = false;
        for (const StrokeDraw& d : draws) {
            if (d.brush != brush || (d.hidden_width_px > 0.0f) != hidden) {
                brush = d.brush;
                hidden = d.hidden_width_px > 0.0f;
                fn.Uniform1i(su.plain, hidden ? 1 : 0);
                fn.Uniform1f(su.widen, hidden ? 1.0f : widen);
                set_brush(*brush, hidden ? d.hidden_width_px : 0.0f);
            }
            // Where a hidden line begins and ends along u; a brush stroke's dashes run on past its
            // ends into its caps.
            constexpr float kNoEnd = 1e30f;
            if (hidden && !d.closed) {
                fn.Uniform2f(su.u_range, d.dash_offset_px, d.dash_offset_px + d.length_px);
            } else {
                fn.Uniform2f(su.u_range, -kNoEnd, kNoEnd);
            }
            if (++value > kStencilValues) {
                fn.ClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
                value = 1;
            }
            fn.StencilFunc(GL_GREATER, value, 0xff);
            fn.Uniform1f(su.stroke_length, d.length_px);
            fn.Uniform1f(su.period, d.period_px);
            fn.Uniform2f(su.free_ends, d.free_start ? 1.0f : 0.0f, d.free_end ? 1.0f : 0.0f);
            fn.DrawElements(GL_TRIANGLES, d.index_count, GL_UNSIGNED_INT,
                            reinterpret_cast<const void*>(d.first_index * sizeof(uint32_t)));
        }
        fn.Disable(GL_STENCIL_TEST);
        fn.Disable(GL_BLEND);
    }

    // The uniforms of a stroke's brush: ink, opacity, pressure and dashes. For a hidden line
    // (hidden_width_px > 0): half the opacity, no pressure, and without dashes of the style's own
    // the hidden lines' (3 and 2 widths), as export/drawing.h's dashes_of gives them.
    void set_brush(const core::BrushStyle& brush, float hidden_width_px) {
        const bool hidden = hidden_width_px > 0.0f;
        fn.Uniform3f(su.ink, float(brush.color.r), float(brush.color.g), float(brush.color.b));
        fn.Uniform1f(su.opacity, float(brush.opacity * (hidden ? 0.5 : 1.0)));
        const double range = brush.width_max_px - brush.width_min_px;
        fn.Uniform3f(su.pressure, float(brush.width_min_px), range > 0.0 ? float(1.0 / range) : 0.0f,
                     hidden ? 0.0f : float(options.pressure_darkening));
        // An odd pattern repeats once more, as SVG's stroke-dasharray does: on and off swap.
        std::vector<float> dash(brush.dash_px.begin(), brush.dash_px.end());
        if (hidden && dash.empty()) dash = {3.0f * hidden_width_px, 2.0f * hidden_width_px};
        if (dash.size() % 2 == 1) dash.insert(dash.end(), brush.dash_px.begin(), brush.dash_px.end());
        double period = 0.0;
        for (const float d : dash) period += d;
        const bool dashed = !dash.empty() && period > 0.0;
        fn.Uniform1i(su.dash_count, dashed ? GLint(dash.size()) : 0);
        if (dashed) fn.Uniform1fv(su.dash, GLsizei(dash.size()), dash.data());
        fn.Uniform1f(su.dash_period, float(period));
        fn.Uniform1i(su.cap, brush.cap == core::LineCap::kButt ? 1 : brush.cap == core::LineCap::kSquare ? 2 : 0);
    }

    PreviewImage read_back() {
        PreviewImage out;
        out.width = fb_width;
        out.height = fb_height;
        out.rgba.resize(size_t(fb_width) * size_t(fb_height) * 4);
        fn.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo);
        if (fn.CheckFramebufferStatus(GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            check_gl(fn, "reading back the preview");
            throw ContextError("the preview framebuffer is incomplete; nothing to read back");
        }
        fn.ReadBuffer(GL_COLOR_ATTACHMENT0);
        fn.PixelStorei(GL_PACK_ALIGNMENT, 4);
        fn.ReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
        check_gl(fn, "reading back the preview");
        // Premultiplied to straight alpha.
        for (size_t k = 0; k < out.rgba.size(); k += 4) {
            const unsigned a = out.rgba[k + 3];
            if (a == 0 || a == 255) continue;
            for (size_t c = 0; c < 3; ++c)
                out.rgba[k + c] = uint8_t(std::min(255u, (out.rgba[k + c] * 255u + a / 2) / a));
        }
        return out;
    }
};

PreviewRenderer::PreviewRenderer(const Context& context, const core::BrushStyle& style, const BrushTip& tip,
                                 const PreviewOptions& options)
    : impl_(std::make_unique<Impl>()) {
    INKLINE_CHECK(tip.width >= 2 && tip.height >= 2);
    INKLINE_CHECK_EQ(tip.alpha.size(), size_t(tip.width) * size_t(tip.height));
    INKLINE_CHECK(tip.head_fraction >= 0.0 && tip.tail_fraction >= 0.0 && tip.head_fraction + tip.tail_fraction < 1.0);
    INKLINE_CHECK(tip.edge_margin >= 0.0 && tip.edge_margin < 0.5);
    if (!(options.tip_length_px >= 0.0 && options.pressure_darkening >= 0.0 && options.pressure_darkening <= 1.0)) {
        throw InputError("preview: tip length must not be negative and pressure darkening must be in 0..1");
    }
    Impl& m = *impl_;
    m.style = style;
    m.options = options;
    m.tip_layout = tip;
    m.tip_layout.alpha.clear();
    // Widths below a pixel would lay the tip out shorter than its streaks are wide.
    m.tip_length_px =
        options.tip_length_px > 0.0 ? options.tip_length_px : tip.aspect() * std::max(style.width_max_px, 1.0);
    m.fn = internal::load_functions(context);
    m.setup(tip);
}

PreviewRenderer::~PreviewRenderer() = default;

void PreviewRenderer::prepare(core::ImageSize image) {
    Impl& m = *impl_;
    INKLINE_CHECK(image.width > 0 && image.height > 0);
    if (image.width > m.max_size || image.height > m.max_size) {
        throw InputError("preview of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " px is larger than this GL's framebuffer limit of " + std::to_string(m.max_size) + " px");
    }
    m.resize(image.width, image.height);
}

PreviewImage PreviewRenderer::render(const core::FrameLines& frame, const core::FrameStrokes& strokes,
                                     const PreviewSurface& surface, const PreviewTone& tone) {
    Impl& m = *impl_;
    const internal::Functions& fn = m.fn;
    const core::ImageSize image = frame.image;
    const bool underlay = m.options.underlay != Underlay::kNone;
    INKLINE_CHECK(!underlay || surface.mesh != nullptr);
    prepare(image);

    auto start = std::chrono::steady_clock::now();
    const std::vector<StrokeDraw> draws = m.upload_strokes(strokes);
    m.stats.geometry_ms = ms_since(start);

    start = std::chrono::steady_clock::now();
    fn.BindFramebuffer(GL_FRAMEBUFFER, m.msaa_fbo);
    if (fn.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        check_gl(fn, "binding the preview framebuffer");
        throw ContextError("the preview framebuffer is incomplete");
    }
    const GLenum draw_buffer = GL_COLOR_ATTACHMENT0;
    fn.DrawBuffers(1, &draw_buffer);
    fn.Viewport(0, 0, image.width, image.height);
    // The depth pass may share the context: set every switch this pass relies on.
    for (const GLenum capability : {GL_CULL_FACE, GL_DEPTH_CLAMP, GL_DEPTH_TEST, GL_STENCIL_TEST, GL_BLEND}) {
        fn.Disable(capability);
    }
    const glm::vec3 background(m.options.background.value_or(glm::dvec3(0.0)));
    const GLfloat clear[4] = {background.r, background.g, background.b, m.options.background ? 1.0f : 0.0f};
    fn.ClearBufferfv(GL_COLOR, 0, clear);
    fn.DepthMask(GL_TRUE);
    fn.StencilMask(0xff);
    fn.ClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    if (underlay) m.draw_surface(frame, surface);
    m.stats.tone_triangles = 0;
    if (tone.tone) m.draw_tone(tone, image);
    m.draw_strokes(draws, image);
    // Resolve the samples into the single-sampled buffer that is read back.
    fn.BindFramebuffer(GL_READ_FRAMEBUFFER, m.msaa_fbo);
    fn.BindFramebuffer(GL_DRAW_FRAMEBUFFER, m.resolve_fbo);
    fn.BlitFramebuffer(0, 0, image.width, image.height, 0, 0, image.width, image.height, GL_COLOR_BUFFER_BIT,
                       GL_NEAREST);
    fn.Finish();
    check_gl(fn, "rendering the preview");
    m.stats.render_ms = ms_since(start);
    m.stats.samples = m.samples;

    start = std::chrono::steady_clock::now();
    PreviewImage out = m.read_back();
    m.stats.readback_ms = ms_since(start);
    return out;
}

const PreviewStats& PreviewRenderer::last_render() const { return impl_->stats; }

}  // namespace inkline::gl
