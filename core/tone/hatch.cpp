// SPDX-License-Identifier: MIT
#include "core/tone/hatch.h"

#include "core/strokes/strokes.h"
#include "core/tone/internal/ink_grid.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace inkline::core {
namespace {

// Levels of planes: level k has 2^k + 1 planes across the rest shape's extent. Plane numbers
// count the finest level's spacing.
constexpr int kFinest = 24;
constexpr double kFinestSteps = double(1u << kFinest);
// The most lines traced across one face in one family (a face that would need more is drawn at
// a coarser level: a closer camera stops adding lines there).
constexpr uint64_t kMaxLinesPerFace = 256;
// A point whose line has faded in less than this share of its width is not drawn: hairlines
// across the lit side read as noise, not tone.
constexpr double kMinWeight = 0.1;

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

uint32_t edge_between(const EdgeTable& table, uint32_t a, uint32_t b) {
    for (uint32_t e : table.edges_around(a)) {
        if (table.other_vertex(e, a) == b) return e;
    }
    return std::numeric_limits<uint32_t>::max();
}

struct LinePoint {
    uint32_t edge = 0;
    uint64_t plane = 0;
    glm::dvec3 p_object{0.0};
    double width = 0.0;
    uint32_t segments[2] = {kNone, kNone};
    uint32_t degree = 0;
    static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
};

}  // namespace

std::vector<Hatch> Hatcher::hatch(const Mesh& mesh, const EdgeTable& table, std::span<const glm::dvec3> normals,
                                  const Projection& projection, const Light& light, const Occlusion& occlusion,
                                  std::span<const Stroke> strokes, bool topology_changed,
                                  std::span<const uint8_t> shaded_faces) {
    stats_ = {};
    std::vector<Hatch> out;
    if ((options_.mode != ToneMode::kHatch && options_.mode != ToneMode::kCrosshatch) || mesh.triangles.empty()) {
        return out;
    }

    // Each family's planes on the rest shape: the mesh as first seen.
    if (families_.empty() || topology_changed || faces_ != mesh.triangles.size()) {
        families_.clear();
        faces_ = mesh.triangles.size();
        const size_t count = options_.mode == ToneMode::kCrosshatch ? 2 : 1;
        for (size_t f = 0; f < count; ++f) {
            const glm::dvec3 d = glm::normalize(f == 0 ? options_.direction : options_.cross_direction);
            Family family;
            family.h.resize(mesh.positions.size());
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (size_t v = 0; v < mesh.positions.size(); ++v) {
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

    const glm::dvec3 eye = projection.eye_object();
    const glm::dmat4& world_from_object = projection.world_from_object();
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world_from_object)));
    const ImageSize image = projection.image();
    const double width = options_.line_width_px;

    // Tone at a point of the mesh with the (object-space) normal given.
    const auto tone_at = [&](const glm::dvec3& p, glm::dvec3 normal) {
        if (glm::dot(normal, normal) == 0.0) return 0.0;
        normal = glm::normalize(normal_matrix * normal);
        const glm::dvec3 p_world(world_from_object * glm::dvec4(p, 1.0));
        const glm::dvec3 to_light = light.is_point ? light.position - p_world : -light.direction;
        return tone_of(glm::dot(normal, glm::normalize(to_light)), options_);
    };

    const internal::InkGrid ink(strokes, image, width);
    for (uint32_t f = 0; f < families_.size(); ++f) {
        const Family& family = families_[f];
        const double finest_step = family.step0 / kFinestSteps;
        std::vector<LinePoint> points;
        std::unordered_map<uint64_t, uint32_t> point_at;  // plane << 32 | edge -> index in points
        struct Segment {
            uint32_t a, b;
        };
        std::vector<Segment> segments;

        for (uint32_t face = 0; face < mesh.triangles.size(); ++face) {
            if (!table.face_valid[face] || (!shaded_faces.empty() && !shaded_faces[face])) continue;
            const glm::uvec3 t = mesh.triangles[face];
            const glm::dvec3 p[3] = {glm::dvec3(mesh.positions[t.x]), glm::dvec3(mesh.positions[t.y]),
                                     glm::dvec3(mesh.positions[t.z])};
            if (glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), eye - p[0]) <= 0.0) continue;  // back-facing
            const double h[3] = {family.h[t.x], family.h[t.y], family.h[t.z]};
            const double h_lo = std::min({h[0], h[1], h[2]}), h_hi = std::max({h[0], h[1], h[2]});
            if (!(h_hi > h_lo)) continue;
            glm::dvec2 q[3];
            bool in_front = true;
            for (int c = 0; c < 3; ++c) {
                const glm::dvec4 clip = projection.clip(p[c]);
                in_front = in_front && projection.in_front(clip);
                if (in_front) q[c] = projection.pixel_from_clip(clip);
            }
            if (!in_front) continue;
            const glm::dvec2 box_lo = glm::min(q[0], glm::min(q[1], q[2]));
            const glm::dvec2 box_hi = glm::max(q[0], glm::max(q[1], q[2]));
            if (box_hi.x < 0.0 || box_hi.y < 0.0 || box_lo.x > image.width || box_lo.y > image.height) continue;

            // h's gradient on screen, in h per pixel: the lines of level 0 lie step0 / |g| px apart.
            const glm::dvec2 a = q[1] - q[0], b = q[2] - q[0];
            const double det = a.x * b.y - a.y * b.x;
            if (std::abs(det) < 1e-12) continue;
            const glm::dvec2 g = ((h[1] - h[0]) * glm::dvec2(b.y, -b.x) - (h[2] - h[0]) * glm::dvec2(a.y, -a.x)) / det;
            const double gradient = glm::length(g);

            int finest = -1;
            for (int c = 0; c < 3; ++c) {
                const double tone = family_tone(tone_at(p[c], normals[t[c]]), f, options_);
                finest = std::max(finest, finest_level(tone, family.step0, gradient, width));
            }
            if (finest < 0) continue;
            ++stats_.faces;
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
                uint32_t ends[2];
                int found = 0;
                for (int k = 0; k < 3 && found < 2; ++k) {
                    const int l = (k + 1) % 3;
                    if ((h[k] >= c) == (h[l] >= c)) continue;
                    const uint32_t edge = edge_between(table, t[k], t[l]);
                    if (edge == std::numeric_limits<uint32_t>::max()) break;
                    const uint64_t key = (plane << 32) | edge;
                    auto [it, inserted] = point_at.try_emplace(key, uint32_t(points.size()));
                    if (inserted) {
                        const double s = (c - h[k]) / (h[l] - h[k]);
                        LinePoint point;
                        point.edge = edge;
                        point.plane = plane;
                        point.p_object = p[k] + s * (p[l] - p[k]);
                        const glm::dvec3 normal = normals[t[k]] + s * (normals[t[l]] - normals[t[k]]);
                        const double tone = family_tone(tone_at(point.p_object, normal), f, options_);
                        point.width = width * line_weight(level_of(plane), tone, family.step0, gradient, width);
                        points.push_back(point);
                    }
                    ends[found++] = it->second;
                }
                if (found != 2) continue;
                const auto seg = uint32_t(segments.size());
                segments.push_back({ends[0], ends[1]});
                for (uint32_t e : ends) {
                    LinePoint& lp = points[e];
                    if (lp.degree < 2) lp.segments[lp.degree] = seg;
                    ++lp.degree;
                }
            }
        }
        stats_.segments += segments.size();

        // Which points are drawn: in the image, faded in, off the strokes' ink, not hidden.
        std::vector<uint8_t> drawn(points.size(), 0);
        std::vector<glm::dvec2> px(points.size());
        std::vector<OcclusionQuery> queries;
        std::vector<uint32_t> queried;
        for (uint32_t i = 0; i < points.size(); ++i) {
            const LinePoint& lp = points[i];
            px[i] = projection.pixel(lp.p_object);
            if (lp.width < kMinWeight * width || !projection.inside_image(px[i])) continue;
            if (ink.touches(px[i], 0.5 * lp.width)) {
                ++stats_.inked;
                continue;
            }
            queries.push_back({.p_object = lp.p_object, .edge = lp.edge});
            queried.push_back(i);
        }
        std::vector<uint8_t> occluded(queries.size(), 0);
        if (!queries.empty()) occlusion.occluded(eye, queries, occluded);
        stats_.points += queries.size();
        for (size_t k = 0; k < queried.size(); ++k) {
            if (occluded[k]) {
                ++stats_.occluded;
            } else {
                drawn[queried[k]] = 1;
            }
        }

        // Chain the segments through their shared points, then cut the chains where points are
        // not drawn. A point on three or more faces' lines (a non-manifold edge) ends a chain.
        std::vector<uint8_t> used(segments.size(), 0);
        const auto walk = [&](uint32_t start_point, uint32_t start_segment) {
            std::vector<uint32_t> chain{start_point};
            uint32_t point = start_point, seg = start_segment;
            while (seg != LinePoint::kNone && !used[seg]) {
                used[seg] = 1;
                const uint32_t next = segments[seg].a == point ? segments[seg].b : segments[seg].a;
                chain.push_back(next);
                point = next;
                const LinePoint& lp = points[point];
                if (lp.degree != 2) break;
                seg = lp.segments[0] == seg ? lp.segments[1] : lp.segments[0];
            }
            return chain;
        };
        const auto emit = [&](const std::vector<uint32_t>& chain) {
            size_t i = 0;
            while (i < chain.size()) {
                while (i < chain.size() && !drawn[chain[i]]) ++i;
                size_t j = i;
                while (j < chain.size() && drawn[chain[j]]) ++j;
                if (j - i >= 2) {
                    Hatch hatch;
                    hatch.family = f;
                    hatch.plane = points[chain[i]].plane;
                    hatch.level = level_of(hatch.plane);
                    for (size_t k = i; k < j; ++k) {
                        const LinePoint& lp = points[chain[k]];
                        hatch.points_px.push_back(px[chain[k]]);
                        hatch.points_world.emplace_back(world_from_object * glm::dvec4(lp.p_object, 1.0));
                        hatch.edges.push_back(lp.edge);
                        hatch.width_px.push_back(lp.width);
                    }
                    hatch.outline = build_outline(hatch.points_px, hatch.width_px, false,
                                                  {.simplify_px = 0.05, .cap = LineCap::kButt});
                    out.push_back(std::move(hatch));
                }
                i = j;
            }
        };
        // Open chains from their ends first, then the loops that remain.
        for (uint32_t i = 0; i < points.size(); ++i) {
            if (points[i].degree == 1 && !used[points[i].segments[0]]) emit(walk(i, points[i].segments[0]));
        }
        for (uint32_t i = 0; i < points.size(); ++i) {
            for (int k = 0; k < 2 && k < int(points[i].degree); ++k) {
                const uint32_t seg = points[i].segments[k];
                if (used[seg]) continue;
                std::vector<uint32_t> chain = walk(i, seg);
                // A loop: start it at a point that is not drawn, so that its drawn runs are whole.
                if (chain.size() > 2 && chain.front() == chain.back()) {
                    chain.pop_back();
                    const auto gap = std::find_if(chain.begin(), chain.end(), [&](uint32_t q) { return !drawn[q]; });
                    if (gap == chain.end()) {
                        chain.push_back(chain.front());  // drawn all round: closed where it began
                    } else {
                        std::rotate(chain.begin(), gap, chain.end());
                    }
                }
                emit(chain);
            }
        }
        // Segments at points shared by three or more (not listed there): each on its own.
        for (uint32_t seg = 0; seg < segments.size(); ++seg) {
            if (!used[seg]) emit({segments[seg].a, segments[seg].b});
        }
    }
    return out;
}

}  // namespace inkline::core
