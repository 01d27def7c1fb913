// SPDX-License-Identifier: MIT
#include "core/tone/stipple.h"

#include "core/internal/key_table.h"
#include "core/internal/parallel.h"
#include "core/internal/view_clip.h"
#include "core/random.h"
#include "core/strokes/strokes.h"
#include "core/tone/internal/ink_grid.h"
#include "core/tone/internal/tone_light.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace inkline::core {
namespace {

// Level 0 keeps about this many samples; every later level roughly doubles the count.
constexpr double kFirstLevelSamples = 32.0;
// Candidates thrown per level, per square of its spacing: enough to fill the level's gaps
// almost to saturation.
constexpr double kCandidatesPerSquare = 3.0;
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

// A grid cell, 21 bits an axis.
uint64_t pack_cell(const glm::ivec3& c) {
    const auto part = [](int v) { return uint64_t(uint32_t(v) & 0x1fffffu); };
    return part(c.x) | (part(c.y) << 21) | (part(c.z) << 42);
}
glm::ivec3 cell_of(const glm::vec3& p, double cell) { return glm::ivec3(glm::floor(glm::dvec3(p) / cell)); }

// Grid cells in blocks of 8 x 8 x 8: a hash of the blocks (a surface meets few, so it stays in
// cache) and each block's cells side by side, so that a cell's neighbours are near in memory
// too, and the 2 x 2 x 2 cells around a point are mostly one block's. A cell's value is Value{}
// until set.
template <typename Value>
class BlockedCells {
  public:
    static constexpr size_t kCells = 512;

    explicit BlockedCells(size_t expected_cells) : blocks_(expected_cells / 32 + 16) {}

    Value& operator[](const glm::ivec3& c) {
        uint32_t& block = blocks_[block_key(c)];
        if (block == 0) {
            values_.resize(values_.size() + kCells);
            block = uint32_t(values_.size() / kCells);
        }
        return values_[(block - 1) * kCells + local(c)];
    }
    // A block's kCells values, in local() order; nullptr for a block with none set. Valid until
    // a cell of a new block is set.
    const Value* block(uint64_t key) const {
        const uint32_t* block = blocks_.find(key);
        return block ? &values_[(*block - 1) * kCells] : nullptr;
    }
    // How many values the blocks hold: it grows when a block is added.
    size_t size() const { return values_.size(); }

    static uint64_t block_key(const glm::ivec3& c) { return pack_cell(c >> kShift); }
    static size_t local(const glm::ivec3& c) { return size_t(((c.z & 7) << 6) | ((c.y & 7) << 3) | (c.x & 7)); }
    // Orders cells block by block, then within a block (the order of the values).
    static std::pair<uint64_t, uint32_t> order(const glm::ivec3& c) { return {block_key(c), uint32_t(local(c))}; }

  private:
    static constexpr int kShift = 3;

    internal::KeyTable<uint32_t> blocks_;  // block -> 1 + its index
    std::vector<Value> values_;
};

constexpr uint32_t kNoPoint = 0xffffffffu;

// The points a level's spacing test looks at, by grid cell: the earlier levels' points sorted by
// cell (a cell's points side by side, and a block's cells too), and the level's own as they are
// kept (each cell's last, the others linked through `next`), in one record a cell so that a cell
// costs one lookup.
class LevelCells {
  public:
    struct Cell {
        uint32_t begin = 0, count = 0;  // the earlier points in it: earlier_[begin, begin + count)
        uint32_t head = kNoPoint;       // this level's last point in it
    };

    LevelCells(std::span<const glm::vec3> earlier, double cell, size_t expected)
        : cell_(cell), cells_(earlier.size() + expected) {
        std::vector<std::pair<std::pair<uint64_t, uint32_t>, uint32_t>> keyed(earlier.size());
        std::vector<glm::ivec3> cells(earlier.size());
        for (uint32_t i = 0; i < earlier.size(); ++i) {
            cells[i] = cell_of(earlier[i], cell);
            keyed[i] = {BlockedCells<Cell>::order(cells[i]), i};
        }
        std::sort(keyed.begin(), keyed.end());
        earlier_.reserve(earlier.size());
        for (size_t i = 0; i < keyed.size();) {
            size_t j = i;
            while (j < keyed.size() && keyed[j].first == keyed[i].first) earlier_.push_back(earlier[keyed[j++].second]);
            Cell& c = cells_[cells[keyed[i].second]];
            c.begin = uint32_t(i), c.count = uint32_t(j - i);
            i = j;
        }
    }
    double cell() const { return cell_; }

    // The cell record of c, or nullptr where no point lies in c's block. `cache` keeps the last
    // block looked up (the 2 x 2 x 2 cells around a point are mostly one block's).
    struct Cache {
        uint64_t key = ~uint64_t(0);
        size_t size = 0;
        const Cell* block = nullptr;
    };
    const Cell* find(const glm::ivec3& c, Cache& r_cache) const {
        const uint64_t key = BlockedCells<Cell>::block_key(c);
        if (key != r_cache.key || r_cache.size != cells_.size()) r_cache = {key, cells_.size(), cells_.block(key)};
        return r_cache.block ? r_cache.block + BlockedCells<Cell>::local(c) : nullptr;
    }
    std::span<const glm::vec3> earlier(const Cell& c) const { return {earlier_.data() + c.begin, c.count}; }

    // Files this level's point `point` in cell c.
    void insert(const glm::ivec3& c, uint32_t point, std::vector<uint32_t>& r_next) {
        uint32_t& head = cells_[c].head;
        r_next[point] = head;
        head = point;
    }

  private:
    double cell_;
    std::vector<glm::vec3> earlier_;
    BlockedCells<Cell> cells_;
};

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

SurfaceSamples::SurfaceSamples(const Mesh& mesh, uint64_t seed) : seed_(seed) {
    corners_.reserve(mesh.triangles.size() * 3);
    cdf_.reserve(mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        corners_.push_back(a);
        corners_.push_back(b);
        corners_.push_back(c);
        const double area = 0.5 * glm::length(face_normal(mesh.positions, t));
        area_ += std::isfinite(area) ? area : 0.0;
        cdf_.push_back(area_);
    }
    face_offsets_.assign(cdf_.size() + 1, 0);
}

void SurfaceSamples::extend_to(size_t count, size_t max_count) {
    count = std::min(count, max_count);
    // Each level is at most about twice the last, and a level is never cut short: a full level
    // keeps the prefix even.
    while (samples_.size() < count && area_ > 0.0 && samples_.size() * 2 + 64 <= std::max<size_t>(max_count, 64) &&
           level_ < 64) {
        add_level();
    }
}

void SurfaceSamples::add_level() {
    radius_ = level_ == 0 ? std::sqrt(area_ / kFirstLevelSamples) : radius_ / std::numbers::sqrt2;
    SplitMix64 rng(seed_ ^ SplitMix64::hash(uint64_t(level_) + 1));
    ++level_;
    const double r = radius_;
    const double per_area = kCandidatesPerSquare / (r * r);
    const size_t expected = size_t(std::ceil(per_area * area_ * 0.5)) + 16;
    // Cells twice the spacing: a ball of the spacing's radius meets at most two cells per axis.
    // Earlier levels' points sorted by cell; this level's filed in the same cells as they come.
    const size_t level_start = samples_.size();
    LevelCells grid(points_, 2.0 * r, expected);
    LevelCells::Cache cache;
    std::vector<uint32_t> next(expected, kNoPoint);

    // Candidates face by face (nearby faces are near in memory too), as many per face as its
    // area asks for, rounded at random.
    const float r2 = float(r * r);
    double below = 0.0;
    for (uint32_t face = 0; face < cdf_.size(); ++face) {
        const double area = cdf_[face] - below;
        below = cdf_[face];
        const double wanted = per_area * area;
        auto count = size_t(wanted);
        if (rng.uniform(0.0, 1.0) < wanted - double(count)) ++count;
        const glm::vec3* c = &corners_[size_t(face) * 3];
        for (size_t k = 0; k < count; ++k) {
            const double s = std::sqrt(rng.uniform(0.0, 1.0));
            const double v = rng.uniform(0.0, 1.0);
            const auto b1 = float(s * (1.0 - v)), b2 = float(s * v);
            const glm::vec3 p = (1.0f - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2];

            const glm::dvec3 scaled = glm::dvec3(p) / grid.cell();
            const glm::ivec3 cell(glm::floor(scaled));
            const glm::ivec3 step(scaled.x - cell.x < 0.5 ? -1 : 1, scaled.y - cell.y < 0.5 ? -1 : 1,
                                  scaled.z - cell.z < 0.5 ? -1 : 1);
            bool near = false;
            for (int n = 0; n < 8 && !near; ++n) {
                const glm::ivec3 at = cell + glm::ivec3(n & 1 ? step.x : 0, n & 2 ? step.y : 0, n & 4 ? step.z : 0);
                const LevelCells::Cell* near_cell = grid.find(at, cache);
                if (!near_cell) continue;
                for (const glm::vec3& q : grid.earlier(*near_cell)) {
                    const glm::vec3 d = q - p;
                    if (glm::dot(d, d) < r2) {
                        near = true;
                        break;
                    }
                }
                for (uint32_t q = near_cell->head; q != kNoPoint && !near; q = next[q]) {
                    const glm::vec3 d = points_[level_start + q] - p;
                    if (glm::dot(d, d) < r2) near = true;
                }
            }
            if (near) continue;
            const auto index = uint32_t(points_.size() - level_start);
            points_.push_back(p);
            samples_.push_back({face, b1, b2});
            if (next.size() <= index) next.resize(next.size() * 2, kNoPoint);
            grid.insert(cell, index, next);
        }
    }
    // The level's samples in random order: any prefix of it is spread over the whole surface.
    for (size_t i = samples_.size(); i > level_start + 1; --i) {
        const size_t j = level_start + size_t(rng.next() % uint64_t(i - level_start));
        std::swap(samples_[i - 1], samples_[j]);
        std::swap(points_[i - 1], points_[j]);
    }

    // Each face's samples, ascending.
    face_offsets_.assign(cdf_.size() + 1, 0);
    for (const Sample& sample : samples_) ++face_offsets_[sample.face + 1];
    for (size_t f = 0; f < cdf_.size(); ++f) face_offsets_[f + 1] += face_offsets_[f];
    face_samples_.resize(samples_.size());
    std::vector<uint32_t> fill(face_offsets_.begin(), face_offsets_.end() - 1);
    for (uint32_t i = 0; i < samples_.size(); ++i) face_samples_[fill[samples_[i].face]++] = i;
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
    // The largest area scale over foreshortening at the vertices of the part of a face a dot can
    // be drawn on (internal::part_in_view), as the faces' limits below take it at their corners;
    // 0 where nothing of it is in view.
    const auto visible_part_scale = [&](const glm::uvec3& t, const glm::dvec3& unit_n) {
        const internal::ViewPolygon part = internal::part_in_view(
            projection, glm::dvec3(mesh.positions[t.x]), glm::dvec3(mesh.positions[t.y]), glm::dvec3(mesh.positions[t.z]));
        double most = 0.0;
        for (size_t i = 0; i < part.count; ++i) {
            const internal::ViewVertex& v = part.vertices[i];
            const double cos_theta = std::abs(glm::dot(unit_n, glm::normalize(eye.toward(v.p))));
            most = std::max(most, std::abs(glm::dot(jacobian(v.clip), unit_n)) / shrink(cos_theta));
        }
        return most;
    };
    // Per face, the most samples any point of it can ask for: the darkest tone of its corners
    // (the interpolated normal's light is never below its corners' least) at the largest area
    // scale of its corners (with a margin for the variation across a face under perspective), or
    // where a corner is behind the camera or outside the image, of its part inside them. Zero
    // for faces turned away and faces of which nothing is in view.
    constexpr double kScaleMargin = 1.1;
    std::vector<double>& face_limit = face_limit_;
    face_limit.assign(mesh.triangles.size(), 0.0);
    const double area = samples_->area();
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
            if (!in_view) scale = visible_part_scale(t, unit_n);
            if (!(scale > 0.0)) continue;
            face_limit[f] = dot_density(tone, radius) * kScaleMargin * scale * area / kappa;
        }
    });
    double most = 0.0;
    for (double limit : face_limit) most = std::max(most, limit);
    stats_.asked = size_t(std::min(most + 1.0, 1e15));
    samples_->extend_to(stats_.asked, options_.max_samples);
    const std::span<const SurfaceSamples::Sample> samples = samples_->samples();
    stats_.samples = samples.size();

    // Dots asked for: faces in parallel slices, joined in order, then sorted by sample.
    const size_t faces = mesh.triangles.size();
    const size_t slices = faces >= 4096 ? std::min<size_t>(internal::hardware_threads(), 8) : 1;
    std::vector<std::vector<Dot>> found(slices);
    std::vector<size_t> considered(slices, 0);
    internal::run_tasks(slices, [&](size_t s) {
        std::vector<Dot>& dots = found[s];
        for (size_t f = faces * s / slices; f < faces * (s + 1) / slices; ++f) {
            const double limit = face_limit[f];
            if (limit <= 0.0) continue;  // also where the face is left unshaded
            const ToneCurve& curve = *curve_of(f);
            const glm::uvec3 t = mesh.triangles[f], g = normals.corners(uint32_t(f), t);
            const glm::dvec3 p0(mesh.positions[t.x]), p1(mesh.positions[t.y]), p2(mesh.positions[t.z]);
            const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
            const glm::dvec3 unit_n = glm::normalize(n);
            for (uint32_t i : samples_->on_face(uint32_t(f))) {
                if (double(i) >= limit) break;
                ++considered[s];
                const SurfaceSamples::Sample& sample = samples[i];
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
                const double threshold = dot_density(tone, radius) * scale * area / kappa;
                const double rank = double(i);
                double weight = 0.0;
                if (fade > 0.0) {
                    weight = std::clamp((threshold - rank) / (fade * (rank + 1.0)), 0.0, 1.0);
                } else {
                    weight = threshold > rank ? 1.0 : 0.0;
                }
                if (weight < kMinWeight) continue;
                dots.push_back({.sample = i,
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
    std::vector<std::pair<uint32_t, const Dot*>> order;
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
