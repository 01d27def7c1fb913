// SPDX-License-Identifier: MIT
#include "core/tone/hatch.h"

#include "core/internal/parallel.h"
#include "core/internal/view_clip.h"
#include "core/strokes/strokes.h"
#include "core/tone/internal/ink_grid.h"
#include "core/tone/internal/tone_light.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

namespace inkline::core {
namespace {

// Levels of planes: level k has 2^k + 1 planes across the rest shape's extent. Plane numbers
// count the finest level's spacing.
constexpr int kFinest = 24;
constexpr double kFinestSteps = double(1u << kFinest);
// The most lines traced across one face in one family (a face that would need more is drawn at
// a coarser level: a closer camera stops adding lines there). A ground plane filling a 4K image
// in perspective needs about a thousand near the camera.
constexpr uint64_t kMaxLinesPerFace = 4096;
// A point whose line has faded in less than this share of its width is not drawn: hairlines
// across the lit side read as noise, not tone.
constexpr double kMinWeight = 0.1;
// Where a line crosses a face farther than kLongCrossingPx on the image, points inside the face
// are added along it every kPointSpacingPx, each tested and sized on its own: a large face (a
// ground plane of two triangles) is clipped by the image, hidden by what stands before it and
// spaced under perspective point by point, not only where its line meets its edges. Shorter
// crossings, most of a detailed mesh's, keep their two points.
constexpr double kLongCrossingPx = 24.0;
constexpr double kPointSpacingPx = 4.0;
// The most points added across one face by one line.
constexpr int kMaxPointsAcrossFace = 4096;
// Where a drawn run of a line meets a point that is not drawn, the line runs on towards it to
// where it stops being drawable (fades out, meets a stroke's ink or the image's edge, goes
// behind something), found by halving the segment until it is shorter than kEndPrecisionPx on
// the image, at most kEndSteps times (0.4 px on the longest segments, kLongCrossingPx). Without
// it a line would stop at its last drawable point, short of a stroke by up to a whole segment.
constexpr double kEndPrecisionPx = 0.4;
constexpr int kEndSteps = 6;

uint32_t level_of(uint64_t plane) {
    if (plane == 0) return 0;
    const int zeros = std::countr_zero(plane);
    return zeros >= kFinest ? 0u : uint32_t(kFinest - zeros);
}

// The share of the tone each family draws: all of it with plain hatching; with crosshatch the
// first family up to cross_from, the second the rest, so that the two together cover
// 1 - (1 - t1)(1 - t2) = tone.
double family_tone(double tone, uint32_t family, const ToneOptions& options) {
    if (options.mode != ToneMode::kCrosshatch) return family == 0 ? tone : 0.0;
    const double first = std::min(tone, options.cross_from);
    if (family == 0) return first;
    return tone > first ? 1.0 - (1.0 - tone) / (1.0 - first) : 0.0;
}

// How much of a line of `level` is drawn where the tone asks for coverage `tone` and the planes
// of level 0, step0 apart along h, lie step0 / gradient_px pixels apart: the levels below the one
// the spacing needs are drawn in full, that one faded so that the lines cover `tone` of the
// surface (widths over spacings).
double line_weight(uint32_t level, double tone, double step0, double gradient_px, double width_px) {
    if (tone <= 0.0 || gradient_px <= 0.0) return 0.0;
    // 2^need: how many times denser than level 0 the lines must be.
    const double need = step0 * tone / (gradient_px * width_px);
    if (level == 0) return std::min(need, 1.0);
    return std::clamp(2.0 * need / std::ldexp(1.0, int(level)) - 1.0, 0.0, 1.0);
}

// The finest level whose lines are drawn at all at that need.
int finest_level(double tone, double step0, double gradient_px, double width_px) {
    if (tone <= 0.0 || gradient_px <= 0.0) return -1;
    const double need = step0 * tone / (gradient_px * width_px);
    if (!(need > 0.0)) return -1;
    return int(std::clamp(std::floor(std::log2(need)) + 1.0, 0.0, double(kFinest)));
}

// The ink of a thin line: each point offset across it by half its width, along the normal of
// its neighbours' chord, out on one side and back on the other, ends cut square. Folds at sharp
// turns overlap themselves, which the nonzero rule fills.
Ring ribbon(std::span<const glm::dvec2> points, std::span<const double> width) {
    const size_t n = points.size();
    Ring out(2 * n);
    for (size_t i = 0; i < n; ++i) {
        glm::dvec2 chord = points[std::min(i + 1, n - 1)] - points[i > 0 ? i - 1 : 0];
        const double length = glm::length(chord);
        chord = length > 0.0 ? chord / length : glm::dvec2(1.0, 0.0);
        const glm::dvec2 across = 0.5 * width[i] * glm::dvec2(-chord.y, chord.x);
        out[i] = points[i] + across;
        out[2 * n - 1 - i] = points[i] - across;
    }
    return out;
}

// A hatch line's segment across one face.
struct FaceLine {
    uint32_t face = 0;
    uint64_t plane = 0;
    uint32_t sides[2] = {0, 0};  // the mesh edges it crosses
    glm::dvec3 points[2];        // where, object space
    double width[2] = {0.0, 0.0};  // its width there, px, by this face's gradient
};

// A face as it is now, with h's gradient along it: h lies on the rest shape (or, in screen space,
// on the image), so the face may have turned, stretched or bent since.
struct FaceFrame {
    glm::dvec3 p0{0.0}, u1{0.0}, u2{0.0};  // a corner and the two sides from it
    double g11 = 0.0, g12 = 0.0, g22 = 0.0, gram = 0.0;  // the sides' Gram matrix and its determinant
    glm::dvec3 unit_n{0.0};
    glm::dvec3 t1{0.0}, t2{0.0};  // an orthonormal basis of the face's plane
    glm::dvec2 h_in_plane{0.0};   // h's gradient along the face, in that basis

    FaceFrame(const Mesh& mesh, const glm::uvec3& t, std::span<const float> h)
        : p0(mesh.positions[t.x]), u1(glm::dvec3(mesh.positions[t.y]) - p0), u2(glm::dvec3(mesh.positions[t.z]) - p0) {
        g11 = glm::dot(u1, u1), g12 = glm::dot(u1, u2), g22 = glm::dot(u2, u2);
        gram = g11 * g22 - g12 * g12;
        if (!valid()) return;
        unit_n = glm::normalize(glm::cross(u1, u2));
        const double dh1 = double(h[t.y]) - double(h[t.x]), dh2 = double(h[t.z]) - double(h[t.x]);
        const glm::dvec3 h_along = ((g22 * dh1 - g12 * dh2) * u1 + (g11 * dh2 - g12 * dh1) * u2) / gram;
        t1 = glm::normalize(std::abs(unit_n.x) < 0.9 ? glm::cross(unit_n, glm::dvec3(1.0, 0.0, 0.0))
                                                     : glm::cross(unit_n, glm::dvec3(0.0, 1.0, 0.0)));
        t2 = glm::cross(unit_n, t1);
        h_in_plane = {glm::dot(h_along, t1), glm::dot(h_along, t2)};
    }
    bool valid() const { return gram > 0.0; }
    // The barycentric coordinates of corners 1 and 2 at a point of the face's plane.
    glm::dvec2 barycentric(const glm::dvec3& p) const {
        const glm::dvec3 d = p - p0;
        const double d1 = glm::dot(d, u1), d2 = glm::dot(d, u2);
        return glm::dvec2(g22 * d1 - g12 * d2, g11 * d2 - g12 * d1) / gram;
    }
};

}  // namespace

std::vector<Hatch> Hatcher::hatch(const Mesh& mesh, const EdgeTable& table, const ToneNormals& normals,
                                  const Projection& projection, const Light& light, const Occlusion& occlusion,
                                  std::span<const Stroke> strokes, bool topology_changed,
                                  FaceTones face_tones) {
    stats_ = {};
    std::vector<Hatch> out;
    if ((options_.mode != ToneMode::kHatch && options_.mode != ToneMode::kCrosshatch) || mesh.triangles.empty()) {
        return out;
    }

    // Each family's planes on the rest shape: the mesh as first seen.
    if (families_.empty() || topology_changed || faces_ != mesh.triangles.size()) {
        families_.clear();
        faces_ = mesh.triangles.size();
        face_edges_ = face_edges(mesh, table);
        const size_t count = options_.mode == ToneMode::kCrosshatch ? 2 : 1;
        for (size_t f = 0; f < count; ++f) {
            Family family;
            family.h.resize(mesh.positions.size());
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            if (options_.space == HatchSpace::kScreen) {
                // Lines along the angle on the page (y down): planes across it, spanning the image.
                const double angle = glm::radians(f == 0 ? options_.angle_deg : options_.cross_angle_deg);
                family.across = {std::sin(angle), std::cos(angle)};
                const ImageSize image = projection.image();
                for (const glm::dvec2 corner : {glm::dvec2(0.0), glm::dvec2(image.width, 0.0),
                                                glm::dvec2(0.0, image.height), glm::dvec2(image.width, image.height)}) {
                    lo = std::min(lo, glm::dot(family.across, corner));
                    hi = std::max(hi, glm::dot(family.across, corner));
                }
            }
            const glm::dvec3 d = glm::normalize(f == 0 ? options_.direction : options_.cross_direction);
            for (size_t v = 0; v < mesh.positions.size() && options_.space == HatchSpace::kObject; ++v) {
                const double h = glm::dot(d, glm::dvec3(mesh.positions[v]));
                family.h[v] = float(h);
                lo = std::min(lo, double(family.h[v]));
                hi = std::max(hi, double(family.h[v]));
            }
            family.step0 = hi > lo ? 0.5 * (hi - lo) : 1.0;
            // Half a finest step below the lowest point: no plane passes exactly through it.
            family.first = lo - 0.5 * family.step0 / kFinestSteps;
            families_.push_back(std::move(family));
        }
    }

    const Viewpoint& eye = projection.eye_object();
    const glm::dmat4& world_from_object = projection.world_from_object();
    const ImageSize image = projection.image();
    const double width = options_.line_width_px;

    // Each face's curve: its own, or the options' (nullptr: the face is left unshaded).
    const ToneCurve& scene_curve = options_.curve;
    const auto curve_of = [&](size_t f) -> const ToneCurve* {
        if (face_tones.empty()) return &scene_curve;
        const uint16_t c = face_tones.curve_of_face[f];
        return c == 0 ? nullptr : &face_tones.curves[c - 1];
    };
    // Tone at a point of the mesh with the (object-space) normal given, on a curve; 0 without a
    // normal.
    const internal::ToneLight lit(world_from_object, light);
    const auto tone_at = [&](const glm::dvec3& p, const glm::dvec3& normal, const ToneCurve& curve) {
        return glm::dot(normal, normal) == 0.0 ? 0.0 : tone_of(lit.intensity(p, normal), curve);
    };

    // Once a frame, per normal: the tone on the options' curve (0 without a normal) and the
    // light's intensity for faces on other curves (NaN without a normal); per vertex: the clip
    // coordinates.
    std::vector<double>& normal_tone = normal_tone_;
    std::vector<double>& normal_intensity = normal_intensity_;
    std::vector<glm::dvec4>& vertex_clip = vertex_clip_;
    normal_tone.resize(normals.size());
    normal_intensity.resize(normals.size());
    vertex_clip.resize(mesh.positions.size());
    internal::parallel_for(normals.size(), 8192, [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) {
            const glm::dvec3& normal = normals.normals[k];
            const glm::dvec3 p(mesh.positions[normals.vertex(k)]);
            normal_intensity[k] = glm::dot(normal, normal) == 0.0 ? NAN : lit.intensity(p, normal);
            normal_tone[k] = std::isnan(normal_intensity[k]) ? 0.0 : tone_of(normal_intensity[k], scene_curve);
        }
    });
    internal::parallel_for(mesh.positions.size(), 8192, [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) vertex_clip[v] = projection.clip(glm::dvec3(mesh.positions[v]));
    });

    // h's gradient on the image (h per px) at a point of a face (clip: its clip coordinates):
    // h's gradient along the face carried through the pixel Jacobian there, so that under
    // perspective the lines' spacing is known point by point. 1 in screen space, where h is the
    // image position.
    const glm::dmat4& m = projection.clip_from_object();
    const glm::dvec3 mx(m[0][0], m[1][0], m[2][0]), my(m[0][1], m[1][1], m[2][1]), mw(m[0][3], m[1][3], m[2][3]);
    const double half_w = 0.5 * image.width, half_h = 0.5 * image.height;
    const auto gradient_at = [&](const FaceFrame& frame, const glm::dvec4& clip) {
        if (options_.space == HatchSpace::kScreen) return 1.0;
        const glm::dvec3 jx = (mx - clip.x / clip.w * mw) * (half_w / clip.w);
        const glm::dvec3 jy = (my - clip.y / clip.w * mw) * (half_h / clip.w);
        // The pixel Jacobian in the face's plane.
        const double a = glm::dot(jx, frame.t1), b = glm::dot(jx, frame.t2);
        const double c = glm::dot(jy, frame.t1), e = glm::dot(jy, frame.t2);
        const double det = a * e - b * c;
        if (!(std::abs(det) > 0.0)) return 0.0;
        const double q1 = frame.h_in_plane.x, q2 = frame.h_in_plane.y;
        return glm::length(glm::dvec2(q1 * e - q2 * c, a * q2 - b * q1)) / std::abs(det);
    };

    // In screen space each vertex's place across the lines is this frame's.
    const bool screen = options_.space == HatchSpace::kScreen;
    // In screen space, w (h - c) at a point of clip coordinates `clip`, where h is its image
    // position across the family's lines: linear in clip coordinates, so a line h = c is a plane
    // through the eye, which also meets sides reaching behind the camera (where h is undefined).
    const auto screen_level = [&](const glm::dvec2& across, const glm::dvec4& clip, double c) {
        return across.x * half_w * (clip.x + clip.w) + across.y * half_h * (clip.w - clip.y) - c * clip.w;
    };
    for (Family& family : families_) {
        if (!screen) break;
        internal::parallel_for(mesh.positions.size(), 8192, [&](size_t begin, size_t end) {
            for (size_t v = begin; v < end; ++v) {
                const bool seen = projection.in_front(vertex_clip[v]);
                family.h[v] = seen ? float(glm::dot(family.across, projection.pixel_from_clip(vertex_clip[v]))) : 0.0f;
            }
        });
    }

    const internal::InkGrid ink(strokes, image, width);
    const size_t faces = mesh.triangles.size();
    for (uint32_t f = 0; f < families_.size(); ++f) {
        const Family& family = families_[f];
        const double finest_step = family.step0 / kFinestSteps;

        // The lines across one face, appended to r_lines in plane order.
        const auto trace_face = [&](uint32_t face, std::vector<FaceLine>& r_lines) {
            const ToneCurve& curve = *curve_of(face);
            const glm::uvec3 t = mesh.triangles[face], corners = normals.corners(face, t);
            const glm::dvec3 p[3] = {glm::dvec3(mesh.positions[t.x]), glm::dvec3(mesh.positions[t.y]),
                                     glm::dvec3(mesh.positions[t.z])};
            if (glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), eye.toward(p[0])) <= 0.0) return;  // back-facing
            const double h[3] = {family.h[t.x], family.h[t.y], family.h[t.z]};
            double h_lo = std::min({h[0], h[1], h[2]}), h_hi = std::max({h[0], h[1], h[2]});
            const bool in_front = projection.in_front(vertex_clip[t.x]) && projection.in_front(vertex_clip[t.y]) &&
                                  projection.in_front(vertex_clip[t.z]);
            // A face reaching behind the camera or out of the image is traced on its part in view:
            // that part's range of h gives its planes, and its least gradient its finest level.
            // In screen space a corner behind the camera has no h: its side of a line is read from
            // screen_level.
            const bool unplaced = screen && !in_front;
            if (!unplaced && !(h_hi > h_lo)) return;
            internal::ViewPolygon part;
            bool clipped = !in_front;
            if (in_front) {
                glm::dvec2 q[3];
                for (int c = 0; c < 3; ++c) q[c] = projection.pixel_from_clip(vertex_clip[t[c]]);
                const glm::dvec2 box_lo = glm::min(q[0], glm::min(q[1], q[2]));
                const glm::dvec2 box_hi = glm::max(q[0], glm::max(q[1], q[2]));
                if (box_hi.x < 0.0 || box_hi.y < 0.0 || box_lo.x > image.width || box_lo.y > image.height) return;
                const glm::dvec2 a = q[1] - q[0], b = q[2] - q[0];
                if (std::abs(a.x * b.y - a.y * b.x) < 1e-12) return;  // edge-on
                clipped = box_lo.x < 0.0 || box_lo.y < 0.0 || box_hi.x > image.width || box_hi.y > image.height;
            }
            if (clipped) {
                part = internal::part_in_view(projection, p[0], p[1], p[2]);
                if (part.count < 3) return;
            }
            const FaceFrame frame(mesh, t, family.h);
            if (!frame.valid()) return;
            if (clipped) {
                h_lo = INFINITY, h_hi = -INFINITY;
                for (size_t k = 0; k < part.count; ++k) {
                    const internal::ViewVertex& v = part.vertices[k];
                    const glm::dvec2 b12 = frame.barycentric(v.p);
                    const double hv = screen ? glm::dot(family.across, projection.pixel_from_clip(v.clip))
                                             : h[0] + b12.x * (h[1] - h[0]) + b12.y * (h[2] - h[0]);
                    h_lo = std::min(h_lo, hv), h_hi = std::max(h_hi, hv);
                }
                if (!(h_hi > h_lo)) return;
            }

            // The finest level any point of the face asks for: at its darkest corner, where h's
            // gradient on the image is least (the lines of level 0 lie step0 / |g| px apart); for
            // a face reaching behind the camera or out of the image, its darkest corner's tone with
            // the least gradient of its part in view.
            int finest = -1;
            double darkest = 0.0;
            for (int c = 0; c < 3; ++c) {
                const double intensity = normal_intensity[corners[c]];
                const double tone = curve == scene_curve   ? normal_tone[corners[c]]
                                    : std::isnan(intensity) ? 0.0
                                                            : tone_of(intensity, curve);
                darkest = std::max(darkest, tone);
                if (clipped) continue;
                const double gradient = gradient_at(frame, vertex_clip[t[c]]);
                finest = std::max(finest, finest_level(family_tone(tone, f, options_), family.step0, gradient, width));
            }
            for (size_t k = 0; k < part.count; ++k) {
                const double gradient = gradient_at(frame, part.vertices[k].clip);
                finest = std::max(finest, finest_level(family_tone(darkest, f, options_), family.step0, gradient, width));
            }
            if (finest < 0) return;
            // Planes of levels up to `finest` with h_lo < c <= h_hi (a corner on a plane counts
            // as above it, so each line crosses exactly two sides).
            uint64_t step = uint64_t(1) << (kFinest - finest);
            const auto plane_above = [&](double v) {
                return uint64_t(std::max(0.0, std::floor((v - family.first) / finest_step)));
            };
            uint64_t first_plane = (plane_above(h_lo) / step + 1) * step;
            const uint64_t last_plane = plane_above(h_hi);
            while (last_plane >= first_plane && (last_plane - first_plane) / step >= kMaxLinesPerFace) {
                step *= 2;
                first_plane = (plane_above(h_lo) / step + 1) * step;
            }
            for (uint64_t plane = first_plane; plane <= last_plane; plane += step) {
                const double c = family.first + double(plane) * finest_step;
                FaceLine line;
                line.face = face;
                line.plane = plane;
                int found = 0;
                // Which side of the line a corner lies on (a corner on it counts as above).
                const auto above = [&](int k) {
                    const glm::dvec4& clip = vertex_clip[t[k]];
                    return unplaced && !projection.in_front(clip) ? screen_level(family.across, clip, c) >= 0.0
                                                                  : h[k] >= c;
                };
                for (int k = 0; k < 3 && found < 2; ++k) {
                    const int l = (k + 1) % 3;
                    if (above(k) == above(l)) continue;
                    const uint32_t edge = face_edges_[face][k];  // the side (t[k], t[l])
                    // From the side's own first vertex: both of its faces compute the same point.
                    const glm::uvec2 ends = table.edge_vertices[edge];
                    const double h0 = family.h[ends.x], h1 = family.h[ends.y];
                    double along = (c - h0) / (h1 - h0);
                    const glm::dvec4 &clip0 = vertex_clip[ends.x], &clip1 = vertex_clip[ends.y];
                    if (screen && !(projection.in_front(clip0) && projection.in_front(clip1))) {
                        // A side reaching behind the camera: where it meets the line's plane.
                        const double l0 = screen_level(family.across, clip0, c),
                                     l1 = screen_level(family.across, clip1, c);
                        along = l0 / (l0 - l1);
                    } else if (screen) {
                        // h runs evenly on the image, not along the edge in space: the point of
                        // the edge whose image lies on the line.
                        const double w0 = clip0.w, w1 = clip1.w;
                        along = along * w0 / (along * w0 + (1.0 - along) * w1);
                    }
                    const glm::dvec3 e0(mesh.positions[ends.x]), e1(mesh.positions[ends.y]);
                    line.sides[found] = edge;
                    line.points[found] = e0 + along * (e1 - e0);
                    const glm::dvec3& n0 = normals.normals[normals.at_vertex(face, t, ends.x)];
                    const glm::dvec3& n1 = normals.normals[normals.at_vertex(face, t, ends.y)];
                    const glm::dvec3 normal = n0 + along * (n1 - n0);
                    const double tone = family_tone(tone_at(line.points[found], normal, curve), f, options_);
                    const glm::dvec4 point_clip = projection.clip(line.points[found]);
                    // (A point behind the camera has no width: it is never drawn.)
                    line.width[found] =
                        projection.in_front(point_clip)
                            ? width * line_weight(level_of(plane), tone, family.step0, gradient_at(frame, point_clip), width)
                            : NAN;
                    ++found;
                }
                if (found == 2) r_lines.push_back(line);
            }
        };

        // Every face's lines, in parallel slices of faces joined in face order: per line its
        // plane and the two sides it crosses, where (the same point from both faces of a side:
        // computed from the side's own vertex order) and how wide (this face's gradient).
        std::vector<FaceLine> lines;
        std::vector<uint32_t> line_offsets(faces + 1, 0);
        {
            const size_t slices = faces >= 4096 ? std::min<size_t>(internal::hardware_threads(), 8) : 1;
            std::vector<std::vector<FaceLine>> found(slices);
            std::vector<HatchStats> slice_stats(slices);
            internal::run_tasks(slices, [&](size_t s) {
                for (size_t face = faces * s / slices; face < faces * (s + 1) / slices; ++face) {
                    if (!table.face_valid[face] || curve_of(face) == nullptr) continue;
                    const size_t before = found[s].size();
                    trace_face(uint32_t(face), found[s]);
                    line_offsets[face + 1] = uint32_t(found[s].size() - before);
                    if (found[s].size() > before) ++slice_stats[s].faces;
                }
            });
            for (const HatchStats& st : slice_stats) stats_.faces += st.faces;
            for (size_t face = 0; face < faces; ++face) line_offsets[face + 1] += line_offsets[face];
            lines.reserve(line_offsets[faces]);
            for (std::vector<FaceLine>& part : found) lines.insert(lines.end(), part.begin(), part.end());
        }
        stats_.segments += lines.size();

        // The line on the other face of `side` of line l, on the same plane; -1 where there is
        // none (a boundary, a non-manifold side, a face with no line there).
        const auto across = [&](uint32_t l, int side) -> int64_t {
            const FaceLine& line = lines[l];
            const std::span<const uint32_t> around = table.faces_of(line.sides[side]);
            if (around.size() != 2) return -1;
            const uint32_t other = around[0] == line.face ? around[1] : around[0];
            for (uint32_t k = line_offsets[other]; k < line_offsets[other + 1]; ++k) {
                if (lines[k].plane == line.plane) return k;
            }
            return -1;
        };

        // Chains of lines through their shared sides, then cut where points are not drawn.
        std::vector<uint8_t> used(lines.size(), 0);
        struct ChainPoint {
            uint32_t edge;  // the edge it lies on; inside a face, the face's first edge
            glm::dvec3 p_object;
            double width;
            uint32_t face;  // the face of the line's segment up to it
            bool on_edge = true;
        };
        struct Run {  // a chain: its plane, whether it closes, its points
            uint64_t plane;
            bool loop;
            uint32_t first, count;  // its points in `points`
        };
        // Points across face b.face between a and b (a line's segment there), where it is longer on
        // the image than kLongCrossingPx: evenly on the image, each with its width from the tone
        // and h's gradient there. Each names the face's first edge.
        const auto inside_face = [&](const ChainPoint& a, const ChainPoint& b, uint64_t plane,
                                     std::vector<ChainPoint>& r_points) {
            // None where the line has faded out at both ends (its width follows the tone and the
            // spacing, which change evenly along it).
            if (a.width < kMinWeight * width && b.width < kMinWeight * width) return;
            glm::dvec3 from = a.p_object, to = b.p_object;
            glm::dvec4 clip_a = projection.clip(from), clip_b = projection.clip(to);
            const auto in_view = [&](const glm::dvec4& clip) {
                return projection.in_front(clip) && projection.inside_image(projection.pixel_from_clip(clip));
            };
            if (!in_view(clip_a) || !in_view(clip_b)) {
                // A segment reaching behind the camera or out of the image: its points go on its
                // stretch in view.
                double s0 = 0.0, s1 = 1.0;
                if (!internal::segment_in_view(projection, a.p_object, b.p_object, s0, s1)) return;
                from = a.p_object + s0 * (b.p_object - a.p_object);
                to = a.p_object + s1 * (b.p_object - a.p_object);
                clip_a = projection.clip(from);
                clip_b = projection.clip(to);
            }
            const double length_px =
                glm::distance(projection.pixel_from_clip(clip_a), projection.pixel_from_clip(clip_b));
            if (!(length_px > kLongCrossingPx)) return;
            const int n = int(std::min(std::ceil(length_px / kPointSpacingPx), double(kMaxPointsAcrossFace)));
            const uint32_t face = b.face;
            const ToneCurve* curve = curve_of(face);
            const glm::uvec3 t = mesh.triangles[face], g = normals.corners(face, t);
            const FaceFrame frame(mesh, t, family.h);
            if (curve == nullptr || !frame.valid()) return;
            for (int i = 1; i < n; ++i) {
                // Evenly on the image: the point of the segment at share s of its image.
                const double s = double(i) / n;
                const double along = s * clip_a.w / (s * clip_a.w + (1.0 - s) * clip_b.w);
                const glm::dvec3 p = from + along * (to - from);
                const glm::dvec2 b12 = frame.barycentric(p);
                const std::span<const glm::dvec3> at = normals.normals;
                const glm::dvec3 normal = (1.0 - b12.x - b12.y) * at[g.x] + b12.x * at[g.y] + b12.y * at[g.z];
                const double tone = family_tone(tone_at(p, normal, *curve), f, options_);
                const double gradient = gradient_at(frame, projection.clip(p));
                r_points.push_back({face_edges_[face].x, p,
                                    width * line_weight(level_of(plane), tone, family.step0, gradient, width), face,
                                    false});
            }
        };

        std::vector<Run> chains;
        std::vector<ChainPoint> points, chain;
        std::vector<OcclusionQuery> queries;
        for (uint32_t start = 0; start < lines.size(); ++start) {
            if (used[start]) continue;
            used[start] = 1;
            // Back through side 0 as far as it goes (or round to the start: a loop).
            std::vector<std::pair<uint32_t, int>> back;  // line, the side it was entered by
            bool loop = false;
            for (int64_t l = start, side = 0;;) {
                const int64_t next = across(uint32_t(l), int(side));
                if (next < 0) break;
                if (next == start) {
                    loop = true;
                    break;
                }
                if (used[next]) break;
                used[next] = 1;
                const int entered = lines[next].sides[0] == lines[l].sides[side] ? 0 : 1;
                back.emplace_back(uint32_t(next), entered);
                l = next;
                side = 1 - entered;
            }
            // The chain's lines in order, each with the side it leaves by.
            std::vector<std::pair<uint32_t, int>> order;
            for (auto it = back.rbegin(); it != back.rend(); ++it) order.emplace_back(it->first, it->second);
            order.emplace_back(start, 1);
            if (!loop) {
                for (int64_t l = start, side = 1;;) {
                    const int64_t next = across(uint32_t(l), int(side));
                    if (next < 0 || used[next]) break;
                    used[next] = 1;
                    const int entered = lines[next].sides[0] == lines[l].sides[side] ? 0 : 1;
                    order.emplace_back(uint32_t(next), 1 - entered);
                    l = next;
                    side = 1 - entered;
                }
            }
            // Its points: the first line's far side, then each side it crosses (the thinner
            // width of its two faces).
            chain.clear();
            const auto point_of = [&](uint32_t l, int side) {
                const FaceLine& line = lines[l];
                return ChainPoint{line.sides[side], line.points[side], line.width[side], line.face, true};
            };
            if (!loop) chain.push_back(point_of(order.front().first, 1 - order.front().second));
            for (size_t k = 0; k < order.size(); ++k) {
                ChainPoint p = point_of(order[k].first, order[k].second);
                const size_t next = k + 1 < order.size() ? k + 1 : (loop ? 0 : order.size());
                if (next < order.size()) {
                    const FaceLine& n = lines[order[next].first];
                    p.width = std::min(p.width, n.width[n.sides[0] == p.edge ? 0 : 1]);
                }
                if (next < order.size() || !loop) chain.push_back(p);
            }

            // The segments across faces that are long on the image get points inside them too.
            // Segment k runs from chain[k] to the next point, across that point's face (the
            // first point of an open chain lies on the first line's far side: its own face is
            // the second point's).
            const uint64_t plane = lines[start].plane;
            const size_t before = points.size();
            for (size_t k = 0; k < chain.size(); ++k) {
                points.push_back(chain[k]);
                if (loop || k + 1 < chain.size()) inside_face(chain[k], chain[(k + 1) % chain.size()], plane, points);
            }
            chains.push_back({plane, loop, uint32_t(before), uint32_t(points.size() - before)});
        }

        // Which points are drawn: in the image, faded in, off the strokes' ink, not hidden (one
        // batch of occlusion queries for the whole family).
        // What a point's own tests say, before the occlusion test: left out behind the camera,
        // faded below a tenth of the width or outside the image (kOff), or on a stroke's ink
        // (kInked); r_px: where it lies on the image (NaN behind the camera).
        enum class Tested : uint8_t { kOff, kInked, kMaybe };
        const auto test_point = [&](const ChainPoint& cp, glm::dvec2& r_px) {
            const glm::dvec4 clip = projection.clip(cp.p_object);
            if (!projection.in_front(clip)) {
                r_px = glm::dvec2(NAN);
                return Tested::kOff;
            }
            r_px = projection.pixel_from_clip(clip);
            if (cp.width < kMinWeight * width || !projection.inside_image(r_px)) return Tested::kOff;
            return ink.touches(r_px, 0.5 * cp.width) ? Tested::kInked : Tested::kMaybe;
        };
        std::vector<glm::dvec2> px(points.size());
        std::vector<uint8_t> drawn(points.size(), 0), hidden(points.size(), 0);
        queries.clear();
        std::vector<uint32_t> queried;
        for (uint32_t i = 0; i < points.size(); ++i) {
            const ChainPoint& cp = points[i];
            const Tested tested = test_point(cp, px[i]);
            if (tested == Tested::kInked) ++stats_.inked;
            if (tested != Tested::kMaybe) continue;
            // A point inside a face: that face alone never hides it.
            const std::span<const uint32_t> own = cp.on_edge ? std::span<const uint32_t>() : std::span(&cp.face, 1);
            queries.push_back({.p_object = cp.p_object, .edge = cp.edge, .own_faces = own});
            queried.push_back(i);
        }
        std::vector<uint8_t> occluded(queries.size(), 0);
        if (!queries.empty()) occlusion.occluded(eye, queries, occluded);
        stats_.points += queries.size();
        for (size_t k = 0; k < queried.size(); ++k) {
            if (occluded[k]) {
                ++stats_.occluded;
                hidden[queried[k]] = 1;
            } else {
                drawn[queried[k]] = 1;
            }
        }

        // Each chain's drawn runs. A loop drawn all round is closed where it began; else it
        // starts at a point not drawn, so that its drawn runs are whole.
        struct DrawnRun {
            uint32_t chain;
            uint32_t begin, count;            // its points (indices in `points`) in run_points
            int32_t before = -1, after = -1;  // its ends' extensions in `ends`, -1: none
        };
        // A run's end runs on from its last drawn point `from` towards the next point `to`
        // (not drawn) across `face`, as far as t = lo of the way (hi: the least t known not to
        // be drawable). `behind`: `to` is hidden, so the way there asks the occlusion test.
        struct RunEnd {
            uint32_t from, to, face;
            bool behind = false;
            int steps = 0;  // halvings to go
            double lo = 0.0, hi = 1.0;
        };
        std::vector<DrawnRun> runs;
        std::vector<uint32_t> run_points, at;
        std::vector<RunEnd> ends;
        for (uint32_t r = 0; r < chains.size(); ++r) {
            const Run& c = chains[r];
            at.resize(c.count);
            std::iota(at.begin(), at.end(), c.first);
            bool closed = false;
            if (c.loop) {
                const auto gap = std::find_if(at.begin(), at.end(), [&](uint32_t i) { return !drawn[i]; });
                if (gap == at.end()) {
                    at.push_back(c.first);
                    closed = true;
                } else {
                    std::rotate(at.begin(), gap, at.end());
                }
            }
            for (size_t i = 0; i < at.size();) {
                while (i < at.size() && !drawn[at[i]]) ++i;
                size_t j = i;
                while (j < at.size() && drawn[at[j]]) ++j;
                if (j > i) {
                    DrawnRun run{r, uint32_t(run_points.size()), uint32_t(j - i)};
                    run_points.insert(run_points.end(), at.begin() + i, at.begin() + j);
                    // The segment between two points lies on the face of the later one's (in
                    // chain order). A loop's last point is followed by its first (not drawn).
                    if (i > 0) {
                        run.before = int32_t(ends.size());
                        ends.push_back({at[i], at[i - 1], points[at[i]].face, hidden[at[i - 1]] != 0});
                    }
                    const bool wraps = c.loop && !closed && j == at.size();
                    if (j < at.size() || wraps) {
                        const uint32_t next = j < at.size() ? at[j] : at[0];
                        run.after = int32_t(ends.size());
                        ends.push_back({at[j - 1], next, points[next].face, hidden[next] != 0});
                    }
                    runs.push_back(std::move(run));
                }
                i = j;
            }
        }
        for (RunEnd& e : ends) {
            const double length_px = glm::distance(px[e.from], px[e.to]);  // NaN towards a point behind the camera
            e.steps = !std::isfinite(length_px) ? kEndSteps
                      : length_px > kEndPrecisionPx
                          ? std::min(kEndSteps, int(std::ceil(std::log2(length_px / kEndPrecisionPx))))
                          : 0;
        }
        // The point t of the way from a run end's drawn point to the next, inside its face.
        const auto end_point = [&](const RunEnd& e, double t) {
            const ChainPoint& a = points[e.from];
            const ChainPoint& b = points[e.to];
            const double b_width = std::isfinite(b.width) ? b.width : a.width;  // (behind the camera: none)
            return ChainPoint{face_edges_[e.face].x, a.p_object + t * (b.p_object - a.p_object),
                              a.width + t * (b_width - a.width), e.face, false};
        };
        // Halving: towards a point that fades, leaves the image or meets the ink, by those
        // tests alone; towards a hidden one, with the occlusion test too (a batch a step).
        const auto occlusion_query = [&](const RunEnd& e, const ChainPoint& cp) {
            return OcclusionQuery{.p_object = cp.p_object, .edge = cp.edge, .own_faces = std::span(&e.face, 1)};
        };
        for (int step = 0; step < kEndSteps && !ends.empty(); ++step) {
            queries.clear();
            queried.clear();
            for (uint32_t k = 0; k < ends.size(); ++k) {
                RunEnd& e = ends[k];
                if (step >= e.steps) continue;
                const double t = 0.5 * (e.lo + e.hi);
                const ChainPoint cp = end_point(e, t);
                glm::dvec2 at_px;
                if (test_point(cp, at_px) != Tested::kMaybe) {
                    e.hi = t;
                } else if (!e.behind) {
                    e.lo = t;
                } else {
                    queries.push_back(occlusion_query(e, cp));
                    queried.push_back(k);
                }
            }
            occluded.assign(queries.size(), 0);
            if (!queries.empty()) occlusion.occluded(eye, queries, occluded);
            for (size_t q = 0; q < queried.size(); ++q) {
                RunEnd& e = ends[queried[q]];
                (occluded[q] ? e.hi : e.lo) = 0.5 * (e.lo + e.hi);
            }
        }
        // The ends found without the occlusion test are tested once: one that something hides
        // (it stood in front of the way to a point left out for the ink) is not run on.
        queries.clear();
        queried.clear();
        for (uint32_t k = 0; k < ends.size(); ++k) {
            if (ends[k].behind || !(ends[k].lo > 0.0)) continue;
            queries.push_back(occlusion_query(ends[k], end_point(ends[k], ends[k].lo)));
            queried.push_back(k);
        }
        occluded.assign(queries.size(), 0);
        if (!queries.empty()) occlusion.occluded(eye, queries, occluded);
        for (size_t q = 0; q < queried.size(); ++q) {
            if (occluded[q]) ends[queried[q]].lo = 0.0;
        }

        // The runs of two points and more, their ends run on.
        for (const DrawnRun& run : runs) {
            const bool before = run.before >= 0 && ends[size_t(run.before)].lo > 0.0;
            const bool after = run.after >= 0 && ends[size_t(run.after)].lo > 0.0;
            if (run.count + (before ? 1 : 0) + (after ? 1 : 0) < 2) continue;
            Hatch hatch;
            hatch.family = f;
            hatch.plane = chains[run.chain].plane;
            hatch.level = level_of(hatch.plane);
            const auto add = [&](const ChainPoint& cp, const glm::dvec2& at_px) {
                hatch.points_px.push_back(at_px);
                hatch.points_world.emplace_back(world_from_object * glm::dvec4(cp.p_object, 1.0));
                hatch.edges.push_back(cp.edge);
                hatch.faces.push_back(cp.face);
                hatch.width_px.push_back(cp.width);
            };
            const auto add_end = [&](int32_t end) {
                const ChainPoint cp = end_point(ends[size_t(end)], ends[size_t(end)].lo);
                add(cp, projection.pixel(cp.p_object));
            };
            if (before) add_end(run.before);
            for (uint32_t k = run.begin; k < run.begin + run.count; ++k) add(points[run_points[k]], px[run_points[k]]);
            if (after) add_end(run.after);
            hatch.outline = {ribbon(hatch.points_px, hatch.width_px)};
            out.push_back(std::move(hatch));
        }
    }
    return out;
}

}  // namespace inkline::core
