// SPDX-License-Identifier: MIT
#include "core/tone/stipple.h"

#include "core/internal/parallel.h"
#include "core/internal/view_clip.h"
#include "core/strokes/strokes.h"
#include "core/tone/internal/ink_grid.h"
#include "core/tone/internal/tone_light.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

namespace inkline::core {
namespace {

// The first frame builds the levels everywhere whose points on the whole surface are at most
// this many times those the frame asks for.
constexpr double kEagerShare = 8.0;
// A dot smaller than this share of a full dot's area is not drawn.
constexpr double kMinWeight = 0.01;
// Dots foreshorten: where the surface turns from the camera by theta, a dot's area shrinks by
// cos(theta)^k and there are 1 / cos(theta)^k as many per square pixel (the same ink). Fewer
// dots come and go as a surface turns than with k = 0 (every dot full size, their number per
// square pixel fixed), which would change the count by the whole change of cos(theta).
constexpr double kForeshortening = 0.5;
// Dots keep this far (px) off a stroke's ink, besides their full radius: the outline strays a
// little from the centerline's half width at joins and where it is simplified.
constexpr double kInkClearancePx = 0.25;
constexpr double kLeastInkRadius = 0.35;

// Mean weight of the dots asked for when each fades in over `fade` of its threshold: the
// thresholds are divided by it so that the dots' areas add up to the density asked for.
double fade_weight(double fade) {
    if (fade <= 0.0) return 1.0;
    return 1.0 / (1.0 + fade) + (std::log1p(fade) - fade / (1.0 + fade)) / fade;
}

// An edge of a valid face (its first side), for the occlusion tests that seed their search there.
uint32_t edge_of(const EdgeTable& table, const glm::uvec3& tri) {
    const uint32_t edge = find_edge(table, tri.x, tri.y);
    return edge == kNoIndex ? 0 : edge;
}

}  // namespace

double dot_density(double tone, double radius_px) {
    // Dots thrown at random cover 1 - exp(-f) of the paper at fill f (their areas over the
    // paper's). The nested set's dots keep apart, so they overlap less: measured on a lit sphere
    // (tests/core/tone_test.cpp), they cover 1 - exp(-(f + kSpacedOverlap f^2)). Inverted here.
    constexpr double kSpacedOverlap = 0.69;
    const double t = std::clamp(tone, 0.0, 0.95);
    const double x = -std::log1p(-t);
    const double fill = (std::sqrt(1.0 + 4.0 * kSpacedOverlap * x) - 1.0) / (2.0 * kSpacedOverlap);
    return fill / (std::numbers::pi * radius_px * radius_px);
}

double Stippler::build_samples(const Mesh& mesh,
                               const std::function<double(uint32_t, const SurfaceSamples::Part&)>& need) {
    SurfaceSamples& s = *samples_;
    if (s.levels() == 0) return 0.0;
    const size_t faces = mesh.triangles.size();
    const size_t held = s.size();
    face_built_.resize(faces, -1);

    // The faces asking for a level not yet built over their whole box. A face wider than a few
    // tiles of a level (a ground, a wall) is built from then on tile by tile, where its part in
    // the tile asks for the level; the next level's tiles are looked for in those.
    constexpr int kNarrowTiles = 16;
    struct Pending {
        uint32_t face = 0;
        int level = 0;
        bool wide = false;
        std::vector<glm::ivec3> tiles;  // a wide face's tiles at the level being built
    };
    std::vector<Pending> pending;
    int deepest = -1;
    // The first time, the levels whose points on the whole surface are at most kEagerShare times
    // those asked for are built everywhere at once (a point costs a fraction of one built tile by
    // tile, and an object turning or a camera moving then seldom builds more).
    if (!eager_built_) {
        double asked = 0.0;  // samples the faces ask for, about
        for (uint32_t f = 0; f < faces; ++f) {
            if (s.face_area(f) <= 0.0 || !(face_limit_[f] > 0.0)) continue;
            // (A wide face asks for its finest level only where it is seen closest: left out.)
            const int level = s.level_for(face_limit_[f]);
            if (s.tiles_across(f, level) <= kNarrowTiles) asked += s.face_area(f) * s.density(level);
        }
        eager_built_ = asked > 0.0;  // (a frame that asks for none leaves it to the next)
        const double most = std::min(kEagerShare * asked, 0.25 * double(options_.max_samples));
        int eager = -1;
        while (eager + 1 < s.levels() && s.density(eager + 1) * s.area() <= most) ++eager;
        if (eager >= 0) {
            s.build_everywhere(eager);
            for (uint32_t f = 0; f < faces; ++f) face_built_[f] = int8_t(s.face_area(f) > 0.0 ? eager : -1);
        }
    }
    for (uint32_t f = 0; f < faces; ++f) {
        const double limit = face_limit_[f];
        if (!(limit > 0.0) || s.face_area(f) <= 0.0) continue;
        if (face_built_[f] >= 0 && limit <= s.density(face_built_[f])) continue;
        const int level = s.level_for(limit);
        if (level <= face_built_[f]) continue;
        pending.push_back({.face = f, .level = level, .wide = false, .tiles = {}});
        deepest = std::max(deepest, level);
    }

    const auto tile_order = [](const glm::ivec3& a, const glm::ivec3& b) {
        return std::tie(a.z, a.y, a.x) < std::tie(b.z, b.y, b.x);
    };
    int built = deepest;
    double held_back = 0.0;  // samples the levels not built would have added, about
    std::vector<uint32_t> narrow;
    std::vector<glm::ivec3> candidates;
    for (int j = 0; j <= deepest; ++j) {
        const double below = s.density(j - 1), share = s.density(j) - below;
        narrow.clear();
        double adds = 0.0;
        for (Pending& p : pending) {
            if (p.level < j) continue;
            if (!p.wide && s.tiles_across(p.face, j) <= kNarrowTiles) {
                if (face_built_[p.face] < j) {
                    narrow.push_back(p.face);
                    adds += s.face_area(p.face) * share;
                }
                continue;
            }
            candidates.clear();
            glm::dvec3 lo, hi;
            const auto add = [&](const glm::ivec3& at) { candidates.push_back(at); };
            if (!p.wide) {
                s.face_box(p.face, lo, hi);
                s.tiles_over(j, lo, hi, add);
            } else {
                for (const glm::ivec3& at : p.tiles) {
                    s.tile_box(j - 1, at, lo, hi);
                    s.tiles_over(j, lo, hi, add);
                }
                std::sort(candidates.begin(), candidates.end(), tile_order);
                candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
            }
            p.wide = true;
            p.tiles.clear();
            for (const glm::ivec3& at : candidates) {
                s.tile_box(j, at, lo, hi);
                const SurfaceSamples::Part part = s.part_in_box(p.face, lo, hi);
                if (part.count < 3 || !(need(p.face, part) > below)) continue;
                p.tiles.push_back(at);
                adds += s.part_area(p.face, part) * share;
            }
        }
        if (double(s.size()) + adds > double(options_.max_samples)) {
            built = j - 1;
            for (const Pending& p : pending) {
                if (p.level >= j) held_back += s.face_area(p.face) * (s.density(p.level) - below);
            }
            break;
        }
        for (uint32_t f : narrow) {
            s.build_face(f, j);
            face_built_[f] = int8_t(j);
        }
        for (const Pending& p : pending) {
            if (p.level < j || !p.wide) continue;
            for (const glm::ivec3& at : p.tiles) s.build_tile(j, at);
        }
    }
    s.finish();
    if (built < deepest && held > 0) {
        // Held back while holding samples of earlier frames: start again from none, which gives
        // the samples this frame needs (the same points whatever was built before).
        s.clear();
        face_built_.assign(faces, -1);
        eager_built_ = false;
        return build_samples(mesh, need);
    }
    stats_.asked = size_t(std::min(double(s.size()) + held_back, 1e15));
    return built < deepest ? s.density(built) : INFINITY;
}

std::vector<Dot> Stippler::stipple(const Mesh& mesh, const EdgeTable& table, const ToneNormals& normals,
                                   const Projection& projection, const Light& light, const Occlusion& occlusion,
                                   std::span<const Stroke> strokes, bool topology_changed,
                                   FaceTones face_tones) {
    stats_ = {};
    if (options_.mode != ToneMode::kStipple || mesh.triangles.empty()) return {};
    if (!samples_ || topology_changed || samples_->faces() != mesh.triangles.size()) {
        samples_.emplace(mesh, options_.seed);
        face_edge_.clear();
        face_built_.clear();
        eager_built_ = false;
    }

    const glm::dmat4& m = projection.clip_from_object();
    const glm::dvec3 mx(m[0][0], m[1][0], m[2][0]), my(m[0][1], m[1][1], m[2][1]), mw(m[0][3], m[1][3], m[2][3]);
    const ImageSize image = projection.image();
    const double half_w = 0.5 * image.width, half_h = 0.5 * image.height;
    const glm::dmat4& world_from_object = projection.world_from_object();
    const Viewpoint& eye = projection.eye_object();
    const double radius = options_.dot_radius_px;
    const double kappa = fade_weight(options_.fade);
    const double fade = options_.fade;

    // The pixel Jacobian's rows, crossed, at p (clip: its clip coordinates); along a unit normal
    // n, the square pixels per unit of area of the plane with that normal there.
    const auto jacobian = [&](const glm::dvec4& clip) {
        const double ndc_x = clip.x / clip.w, ndc_y = clip.y / clip.w;
        const glm::dvec3 jx = (mx - ndc_x * mw) * (half_w / clip.w);
        const glm::dvec3 jy = (my - ndc_y * mw) * (half_h / clip.w);
        return glm::cross(jx, jy);
    };
    const auto area_scale = [&](const glm::dvec4& clip, const glm::dvec3& n) {
        return std::abs(glm::dot(jacobian(clip), n));
    };
    // cos(theta)^kForeshortening, and that at p on a face of unit normal n.
    const auto shrink = [](double cos_theta) {
        if constexpr (kForeshortening == 0.5) return std::max(std::sqrt(cos_theta), 1e-6);
        return std::max(std::pow(cos_theta, kForeshortening), 1e-6);
    };
    const auto foreshortening = [&](const glm::dvec3& p, const glm::dvec3& n) {
        return shrink(std::abs(glm::dot(n, glm::normalize(eye.toward(p)))));
    };
    const internal::ToneLight lit(world_from_object, light);
    // Each face's curve: its own, or the options' (nullptr: the face is left unshaded).
    const ToneCurve& scene_curve = options_.curve;
    const auto curve_of = [&](size_t f) -> const ToneCurve* {
        if (face_tones.empty()) return &scene_curve;
        const uint16_t c = face_tones.curve_of_face[f];
        return c == 0 ? nullptr : &face_tones.curves[c - 1];
    };
    const auto tone_at = [&](const glm::dvec3& p, const glm::dvec3& normal, const glm::dvec3& face_n, const ToneCurve& curve) {
        return tone_of(lit.intensity(p, glm::dot(normal, normal) == 0.0 ? face_n : normal), curve);
    };

    // Per vertex, once each: what its faces' limits below read of it, as area_scale and
    // foreshortening would compute them at the vertex. Per normal: its tone on the options' curve
    // (the darkest without a normal) and the light's intensity for faces on other curves.
    const double darkest = std::max(scene_curve.min, scene_curve.max);
    // (Kept from frame to frame: a new buffer's pages cost more than filling it.)
    std::vector<VertexView>& vertex_view = vertex_view_;
    vertex_view.resize(mesh.positions.size());
    internal::parallel_for(mesh.positions.size(), 8192, [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) {
            const glm::dvec3 p(mesh.positions[v]);
            VertexView& view = vertex_view[v];
            const glm::dvec4 clip = m * glm::dvec4(p, 1.0);
            view.in_front = projection.in_front(clip);
            if (!view.in_front) continue;
            view.px = projection.pixel_from_clip(clip);
            view.jacobian = jacobian(clip);
            view.to_eye = glm::normalize(eye.toward(p));
        }
    });
    std::vector<NormalTone>& normal_tone = normal_tone_;
    normal_tone.resize(normals.size());
    internal::parallel_for(normals.size(), 8192, [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) {
            const glm::dvec3& normal = normals.normals[k];
            NormalTone& lit_tone = normal_tone[k];
            const glm::dvec3 p(mesh.positions[normals.vertex(k)]);
            lit_tone.intensity = glm::dot(normal, normal) == 0.0 ? NAN : lit.intensity(p, normal);
            lit_tone.tone = std::isnan(lit_tone.intensity) ? darkest : tone_of(lit_tone.intensity, scene_curve);
        }
    });
    // The largest area scale over foreshortening at the vertices of the part of a polygon on a
    // face (unit normal unit_n) that a dot can be drawn on (internal::part_in_view), as the faces'
    // limits below take it at their corners; 0 where nothing of it is in view.
    const auto visible_part_scale = [&](std::span<const glm::dvec3> polygon, const glm::dvec3& unit_n) {
        const internal::ViewPolygon part = internal::part_in_view(projection, polygon);
        double most = 0.0;
        for (size_t i = 0; i < part.count; ++i) {
            const internal::ViewVertex& v = part.vertices[i];
            const double cos_theta = std::abs(glm::dot(unit_n, glm::normalize(eye.toward(v.p))));
            most = std::max(most, std::abs(glm::dot(jacobian(v.clip), unit_n)) / shrink(cos_theta));
        }
        return most;
    };
    // Per face, the most density (samples per unit area) any point of it can ask for: the darkest tone of its corners
    // (the interpolated normal's light is never below its corners' least) at the largest area
    // scale of its corners (with a margin for the variation across a face under perspective), or
    // where a corner is behind the camera or outside the image, of its part inside them. Zero
    // for faces turned away and faces of which nothing is in view.
    constexpr double kScaleMargin = 1.1;
    std::vector<double>& face_limit = face_limit_;
    face_limit.assign(mesh.triangles.size(), 0.0);
    std::vector<double>& face_ink = face_ink_;
    face_ink.assign(mesh.triangles.size(), 0.0);
    internal::parallel_for(mesh.triangles.size(), 8192, [&](size_t begin, size_t end) {
        for (size_t f = begin; f < end; ++f) {
            const ToneCurve* curve = curve_of(f);
            if (!table.face_valid[f] || curve == nullptr) continue;
            const glm::uvec3 t = mesh.triangles[f], corners = normals.corners(uint32_t(f), t);
            const glm::dvec3 p0(mesh.positions[t.x]), p1(mesh.positions[t.y]), p2(mesh.positions[t.z]);
            const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
            const double n_len = glm::length(n);
            if (!(n_len > 0.0) || glm::dot(n, eye.toward(p0)) <= 0.0) continue;
            const glm::dvec3 unit_n = n / n_len;
            double scale = 0.0, tone = 0.0;
            bool in_view = true;  // every corner in front of the camera and inside the image
            for (int c = 0; c < 3; ++c) {
                const VertexView& view = vertex_view[t[c]];
                const NormalTone& lit_tone = normal_tone[corners[c]];
                in_view = in_view && view.in_front && projection.inside_image(view.px);
                if (in_view) {
                    scale = std::max(scale, std::abs(glm::dot(view.jacobian, unit_n)) /
                                                shrink(std::abs(glm::dot(unit_n, view.to_eye))));
                }
                tone = std::max(tone, *curve == scene_curve              ? lit_tone.tone
                                      : std::isnan(lit_tone.intensity) ? std::max(curve->min, curve->max)
                                                                       : tone_of(lit_tone.intensity, *curve));
            }
            if (!in_view) {
                const glm::dvec3 polygon[3] = {p0, p1, p2};
                scale = visible_part_scale(polygon, unit_n);
            }
            if (!(scale > 0.0)) continue;
            face_ink[f] = dot_density(tone, radius) * kScaleMargin / kappa;
            face_limit[f] = face_ink[f] * scale;
        }
    });
    const double most_density = build_samples(mesh, [&](uint32_t f, const SurfaceSamples::Part& part) {
        const glm::uvec3 t = mesh.triangles[f];
        const glm::dvec3 p0(mesh.positions[t.x]), p1(mesh.positions[t.y]), p2(mesh.positions[t.z]);
        std::array<glm::dvec3, 9> polygon;
        for (size_t i = 0; i < part.count; ++i) {
            polygon[i] = (1.0 - part.b[i].x - part.b[i].y) * p0 + part.b[i].x * p1 + part.b[i].y * p2;
        }
        const glm::dvec3 unit_n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
        return face_ink[f] * visible_part_scale(std::span(polygon.data(), part.count), unit_n);
    });
    const SurfaceSamples& samples = *samples_;
    stats_.samples = samples.size();

    // Dots asked for: faces in parallel slices, joined in order, then sorted by sample.
    const size_t faces = mesh.triangles.size();
    const size_t slices = faces >= 4096 ? std::min<size_t>(internal::hardware_threads(), 8) : 1;
    std::vector<std::vector<Dot>> found(slices);
    std::vector<size_t> considered(slices, 0);
    internal::run_tasks(slices, [&](size_t s) {
        std::vector<Dot>& dots = found[s];
        for (size_t f = faces * s / slices; f < faces * (s + 1) / slices; ++f) {
            const double limit = std::min(face_limit[f], most_density);
            if (limit <= 0.0) continue;  // also where the face is left unshaded
            const ToneCurve& curve = *curve_of(f);
            const glm::uvec3 t = mesh.triangles[f], g = normals.corners(uint32_t(f), t);
            const glm::dvec3 p0(mesh.positions[t.x]), p1(mesh.positions[t.y]), p2(mesh.positions[t.z]);
            const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
            const glm::dvec3 unit_n = glm::normalize(n);
            for (const SurfaceSamples::Sample& sample : samples.on_face(uint32_t(f))) {
                if (sample.rank >= limit) break;
                ++considered[s];
                const double b1 = sample.b1, b2 = sample.b2, b0 = 1.0 - b1 - b2;
                const glm::dvec3 p = b0 * p0 + b1 * p1 + b2 * p2;
                const glm::dvec4 clip = m * glm::dvec4(p, 1.0);
                if (!projection.in_front(clip)) continue;
                const glm::dvec2 px = projection.pixel_from_clip(clip);
                if (!projection.inside_image(px)) continue;
                const double shrunk = foreshortening(p, unit_n);
                const double scale = area_scale(clip, unit_n) / shrunk;
                const std::span<const glm::dvec3> at = normals.normals;
                const double tone = tone_at(p, b0 * at[g.x] + b1 * at[g.y] + b2 * at[g.z], n, curve);
                const double threshold = dot_density(tone, radius) * scale / kappa;
                const double rank = sample.rank;
                double weight = 0.0;
                if (fade > 0.0) {
                    weight = std::clamp((threshold - rank) / (fade * rank), 0.0, 1.0);
                } else {
                    weight = threshold > rank ? 1.0 : 0.0;
                }
                if (weight < kMinWeight) continue;
                dots.push_back({.sample = sample.id,
                                .face = uint32_t(f),
                                .barycentric = {b0, b1, b2},
                                .point_px = px,
                                .point_world = glm::dvec3(world_from_object * glm::dvec4(p, 1.0)),
                                .radius_px = radius * std::sqrt(weight * shrunk),
                                .tone = tone});
            }
        }
    });
    for (size_t c : considered) stats_.considered += c;
    std::vector<std::pair<uint64_t, const Dot*>> order;
    for (const std::vector<Dot>& part : found) {
        for (const Dot& d : part) order.emplace_back(d.sample, &d);
    }
    std::sort(order.begin(), order.end());
    std::vector<Dot> dots;
    dots.reserve(order.size());
    for (const auto& [sample, d] : order) dots.push_back(*d);
    stats_.wanted = dots.size();

    // None on a visible line's ink. Next to the ink a dot shrinks to keep clear of it; one that would shrink below
    // kLeastInkRadius of a full dot is left out. Both follow the full radius, whatever the dot
    // has grown to: a darker tone then draws every dot a lighter one draws.
    const internal::InkGrid ink(strokes, image, radius + kInkClearancePx);
    std::erase_if(dots, [&](Dot& d) {
        const double room = ink.clearance(d.point_px) - kInkClearancePx;
        if (room < kLeastInkRadius * radius) return true;
        d.radius_px = std::min(d.radius_px, room);
        return false;
    });
    stats_.inked = stats_.wanted - dots.size();

    // None on hidden surface: the same occlusion test as the lines, a dot's own face never
    // hiding it.
    std::vector<uint32_t> own(dots.size());
    std::vector<OcclusionQuery> queries(dots.size());
    face_edge_.resize(mesh.triangles.size(), kNoIndex);
    for (size_t k = 0; k < dots.size(); ++k) {
        own[k] = dots[k].face;
        const glm::uvec3 t = mesh.triangles[dots[k].face];
        const glm::dvec3& b = dots[k].barycentric;
        uint32_t& edge = face_edge_[dots[k].face];
        if (edge == kNoIndex) edge = edge_of(table, t);
        queries[k] = {.p_object = b.x * glm::dvec3(mesh.positions[t.x]) + b.y * glm::dvec3(mesh.positions[t.y]) +
                                  b.z * glm::dvec3(mesh.positions[t.z]),
                      .edge = edge,
                      .own_faces = std::span<const uint32_t>(&own[k], 1)};
    }
    std::vector<uint8_t> occluded(dots.size(), 0);
    if (!queries.empty()) occlusion.occluded(eye, queries, occluded);
    size_t kept = 0;
    for (size_t k = 0; k < dots.size(); ++k) {
        if (!occluded[k]) dots[kept++] = dots[k];
    }
    stats_.occluded = dots.size() - kept;
    dots.resize(kept);
    return dots;
}

}  // namespace inkline::core
