// SPDX-License-Identifier: MIT
#include "core/tone/surface_samples.h"

#include "core/internal/key_table.h"
#include "core/internal/parallel.h"
#include "core/random.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace inkline::core {
namespace {

// Level 0 has about this many points; every later level about doubles the count.
constexpr double kFirstLevelSamples = 32.0;
// Candidates thrown per level, per square of its spacing: enough to fill the level's gaps
// almost to saturation.
constexpr double kCandidatesPerSquare = 3.0;
// A tile's side, in its level's spacings: at least one, so that tiles of one phase never meet.
constexpr double kTileSpacings = 8.0;
// Tile coordinates: 21 bits an axis.
constexpr int kTileBits = 21;
constexpr int kMostTiles = (1 << kTileBits) - 1;
constexpr int kMostLevels = 64;
// Points per unit area of levels 0..k, times r_k squared: measured on a wide plane
// (tests/core/surface_samples_test.cpp), the first levels apart and then one value.
constexpr std::array<double, 4> kFirstDensities{0.63, 0.54, 0.51, 0.50};
constexpr double kDensity = 0.515;
// Faces in a leaf of the faces' box tree.
constexpr uint32_t kLeafFaces = 4;

// The 2 x 2 x 2 cells nearest a point, cells being twice the spacing wide, hold every point
// within the spacing of it: its cell and those across the nearer side along each axis. `cell`
// is the point's cell and `within` its place in it, each coordinate in [0, 1).
template <typename Visit>
bool any_of_nearest_cells(const glm::ivec3& cell, const glm::vec3& within, Visit visit) {
    const glm::ivec3 step(within.x < 0.5f ? -1 : 1, within.y < 0.5f ? -1 : 1, within.z < 0.5f ? -1 : 1);
    for (int n = 0; n < 8; ++n) {
        if (visit(cell + glm::ivec3(n & 1 ? step.x : 0, n & 2 ? step.y : 0, n & 4 ? step.z : 0))) return true;
    }
    return false;
}

// A level's candidates in a part of area `area`: kCandidatesPerSquare per square of the spacing r,
// the fraction rounded at random.
size_t candidate_count(double area, double r, SplitMix64& r_rng) {
    const double wanted = kCandidatesPerSquare / (r * r) * area;
    auto count = size_t(wanted);
    if (r_rng.uniform(0.0, 1.0) < wanted - double(count)) ++count;
    return count;
}

// Points by cells of side 2r over all of space, to find those within r of a point (in the 2 x 2
// x 2 cells nearest it): cells in blocks of 8 x 8 x 8 behind a hash of the blocks, so that the
// cells around a point are mostly one block's, looked up once.
class BlockGrid {
  public:
    BlockGrid(const glm::dvec3& origin, double r, size_t expected)
        : origin_(origin), per_cell_(0.5 / r), blocks_(expected / 64 + 16) {}

    void add(const glm::vec3& p) {
        const glm::ivec3 c = cell_of(p);
        uint32_t& block = blocks_[block_key(c)];
        if (block == 0) {
            heads_.resize(heads_.size() + kCells, 0);
            block = uint32_t(heads_.size() / kCells);
        }
        uint32_t& head = heads_[(block - 1) * kCells + local(c)];
        points_.push_back({p, head});
        head = uint32_t(points_.size());
    }
    // The last block looked up (the cells around a point are mostly one block's); valid until a
    // point is added.
    struct Cache {
        uint64_t key = ~uint64_t(0);
        const uint32_t* block = nullptr;
    };
    bool near(const glm::vec3& p, float r2, Cache& r_cache) const {
        const glm::dvec3 scaled = (glm::dvec3(p) - origin_) * per_cell_;
        const glm::ivec3 c(glm::floor(scaled));
        return any_of_nearest_cells(c, glm::vec3(scaled - glm::dvec3(c)), [&](const glm::ivec3& at) {
            const uint64_t key = block_key(at);
            if (key != r_cache.key) {
                const uint32_t* block = blocks_.find(key);
                r_cache = {key, block ? heads_.data() + (*block - 1) * kCells : nullptr};
            }
            if (r_cache.block == nullptr) return false;
            for (uint32_t q = r_cache.block[local(at)]; q != 0; q = points_[q - 1].next) {
                const glm::vec3 d = points_[q - 1].p - p;
                if (glm::dot(d, d) < r2) return true;
            }
            return false;
        });
    }

  private:
    static constexpr size_t kCells = 512;
    struct Entry {
        glm::vec3 p;
        uint32_t next;  // 1 + the next point in its cell; 0: none
    };
    glm::ivec3 cell_of(const glm::vec3& p) const {
        return glm::ivec3(glm::floor((glm::dvec3(p) - origin_) * per_cell_));
    }
    static uint64_t block_key(const glm::ivec3& c) {
        const auto part = [](int v) { return uint64_t(uint32_t(v >> 3) & 0x1fffffu); };
        return part(c.x) | (part(c.y) << 21) | (part(c.z) << 42);
    }
    static size_t local(const glm::ivec3& c) { return size_t(((c.z & 7) << 6) | ((c.y & 7) << 3) | (c.x & 7)); }

    glm::dvec3 origin_;
    double per_cell_;
    internal::KeyTable<uint32_t> blocks_;  // block -> 1 + its index
    std::vector<uint32_t> heads_;          // per cell, 1 + its last point; 0: none
    std::vector<Entry> points_;
};

}  // namespace

struct SurfaceSamples::Candidate {
    uint64_t id;
    uint32_t face;
    float b1, b2;
    glm::vec3 p;
};

namespace {

// The key that stands for "the whole face" in the candidates' seeds (no tile has it: keys use 63 bits).
constexpr uint64_t kWholeFace = ~uint64_t(0);

int phase(const glm::ivec3& at) { return (at.x & 1) | ((at.y & 1) << 1) | ((at.z & 1) << 2); }

struct PartVertex {
    glm::dvec2 b;
    glm::dvec3 p;
};

uint64_t tile_seed(uint64_t seed, int level, uint64_t key, uint32_t face) {
    uint64_t h = SplitMix64::hash(seed ^ 0x243f6a8885a308d3ull);
    h = SplitMix64::hash(h ^ uint64_t(level));
    h = SplitMix64::hash(h ^ key);
    return SplitMix64::hash(h ^ uint64_t(face));
}

// Points by cells of side r over a box, one cell of margin around it, to find those within r of
// a point (in its cell or one next to it); points outside the box are left out.
class SpacingGrid {
  public:
    SpacingGrid(const glm::dvec3& lo, const glm::dvec3& hi, double r)
        : lo_(lo), hi_(hi), per_cell_(float(0.5 / r)), n_(int(std::ceil(0.5 * (hi.x - lo.x) / r)) + 2) {
        head_.assign(size_t(n_) * size_t(n_) * size_t(n_), kNone);
    }
    void add(const glm::vec3& p) {
        if (glm::any(glm::lessThan(p, lo_)) || glm::any(glm::greaterThan(p, hi_))) return;
        uint32_t& first = head_[index(cell(p))];
        points_.push_back({p, first});
        first = uint32_t(points_.size() - 1);
    }
    // Whether a point of the grid lies within sqrt(r2) of p (in the box): in the 2 x 2 x 2 cells
    // nearest it, cells being 2r wide.
    bool near(const glm::vec3& p, float r2) const {
        const glm::ivec3 c = cell(p);
        return any_of_nearest_cells(c, (p - lo_) * per_cell_ - (glm::vec3(c) - 1.0f), [&](const glm::ivec3& at) {
            for (uint32_t q = head_[index(at)]; q != kNone; q = points_[q].next) {
                const glm::vec3 d = points_[q].p - p;
                if (glm::dot(d, d) < r2) return true;
            }
            return false;
        });
    }

  private:
    static constexpr uint32_t kNone = ~0u;
    struct Entry {
        glm::vec3 p;
        uint32_t next;
    };
    // A point's cell, one cell of margin on each side.
    glm::ivec3 cell(const glm::vec3& p) const {
        return glm::clamp(glm::ivec3(glm::floor((p - lo_) * per_cell_)), glm::ivec3(0), glm::ivec3(n_ - 3)) + 1;
    }
    size_t index(const glm::ivec3& c) const { return size_t((c.z * n_ + c.y) * n_ + c.x); }

    glm::vec3 lo_, hi_;
    float per_cell_;
    int n_;
    std::vector<uint32_t> head_;
    std::vector<Entry> points_;
};

}  // namespace

struct SurfaceSamples::Level {
    internal::KeyTable<uint32_t> index;  // tile key -> 1 + its index in tiles
    std::vector<Tile> tiles;
    std::vector<glm::vec3> points;
    uint64_t last_key = ~uint64_t(0);  // the last tile looked up (lookups come in runs)
    uint32_t last_index = 0;
};

SurfaceSamples::SurfaceSamples(SurfaceSamples&&) noexcept = default;
SurfaceSamples& SurfaceSamples::operator=(SurfaceSamples&&) noexcept = default;
SurfaceSamples::~SurfaceSamples() = default;

SurfaceSamples::SurfaceSamples(const Mesh& mesh, uint64_t seed) : seed_(seed) {
    const size_t faces = mesh.triangles.size();
    corners_.reserve(faces * 3);
    face_area_.assign(faces, 0.0);
    face_extent_.assign(faces, 0.0f);
    offsets_.assign(faces + 1, 0);
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    std::vector<glm::vec3> centres(faces);
    for (size_t f = 0; f < faces; ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        corners_.push_back(a);
        corners_.push_back(b);
        corners_.push_back(c);
        const double area = 0.5 * glm::length(face_normal(mesh.positions, t));
        if (!(std::isfinite(area) && area > 0.0)) continue;
        face_area_[f] = area;
        area_ += area;
        const glm::vec3 extent = glm::max(a, glm::max(b, c)) - glm::min(a, glm::min(b, c));
        face_extent_[f] = std::max({extent.x, extent.y, extent.z});
        lo = glm::min(lo, glm::min(glm::dvec3(a), glm::min(glm::dvec3(b), glm::dvec3(c))));
        hi = glm::max(hi, glm::max(glm::dvec3(a), glm::max(glm::dvec3(b), glm::dvec3(c))));
        centres[box_faces_.size()] = (a + b + c) / 3.0f;
        box_faces_.push_back(uint32_t(f));
    }
    if (!(area_ > 0.0) || !std::isfinite(area_)) return;
    box_nodes_.reserve(2 * box_faces_.size() / kLeafFaces + 2);
    build_boxes(0, uint32_t(box_faces_.size()), centres);

    const double first = std::sqrt(area_ / kFirstLevelSamples);
    origin_ = lo - kTileSpacings * first;
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) + 2.0 * kTileSpacings * first;
    for (int k = 0; k < kMostLevels; ++k) {
        const double r = first / std::pow(std::numbers::sqrt2, k);
        if (!(extent / (kTileSpacings * r) + 2.0 < double(kMostTiles))) break;
        radius_.push_back(r);
    }
    levels_.resize(radius_.size());
}

double SurfaceSamples::density(int level, double first_radius) {
    if (level < 0) return 0.0;
    const double per_square = size_t(level) < kFirstDensities.size() ? kFirstDensities[size_t(level)] : kDensity;
    return std::ldexp(per_square / (first_radius * first_radius), level);
}

int SurfaceSamples::level_for(double wanted) const {
    if (!(wanted > 0.0)) return 0;
    // Near the level past the first ones' table (density kDensity 2^k / r0^2), then the exact one.
    const double x = wanted * radius_[0] * radius_[0] / kDensity;
    int k = x > 1.0 ? int(std::ceil(std::log2(std::min(x, 0x1p62)))) : 0;
    k = std::clamp(k, 0, levels() - 1);
    while (k > 0 && density(k - 1) >= wanted) --k;
    while (k + 1 < levels() && density(k) < wanted) ++k;
    return k;
}

glm::ivec3 SurfaceSamples::tile_of(int level, const glm::dvec3& p) const {
    const glm::dvec3 at = glm::floor((p - origin_) / (kTileSpacings * radius_[size_t(level)]));
    return glm::ivec3(glm::clamp(at, glm::dvec3(0.0), glm::dvec3(kMostTiles)));
}

uint64_t SurfaceSamples::tile_key(const glm::ivec3& at) {
    return uint64_t(at.x) | (uint64_t(at.y) << kTileBits) | (uint64_t(at.z) << (2 * kTileBits));
}

void SurfaceSamples::tile_box(int level, const glm::ivec3& at, glm::dvec3& r_lo, glm::dvec3& r_hi) const {
    const double side = kTileSpacings * radius_[size_t(level)];
    r_lo = origin_ + glm::dvec3(at) * side;
    r_hi = r_lo + side;
}

void SurfaceSamples::face_box(uint32_t face, glm::dvec3& r_lo, glm::dvec3& r_hi) const {
    const glm::vec3* c = &corners_[size_t(face) * 3];
    r_lo = glm::dvec3(glm::min(c[0], glm::min(c[1], c[2])));
    r_hi = glm::dvec3(glm::max(c[0], glm::max(c[1], c[2])));
}

int SurfaceSamples::tiles_across(uint32_t face, int level) const {
    glm::dvec3 lo, hi;
    face_box(face, lo, hi);
    const glm::ivec3 span = tile_of(level, hi) - tile_of(level, lo);
    return 1 + std::max({span.x, span.y, span.z});
}

bool SurfaceSamples::plane_meets(uint32_t face, const glm::dvec3& lo, const glm::dvec3& hi) const {
    const glm::vec3* c = &corners_[size_t(face) * 3];
    const glm::dvec3 p0(c[0]), n = glm::cross(glm::dvec3(c[1]) - p0, glm::dvec3(c[2]) - p0);
    return std::abs(glm::dot(n, 0.5 * (lo + hi) - p0)) <= glm::dot(0.5 * (hi - lo), glm::abs(n));
}

SurfaceSamples::Part SurfaceSamples::part_in_box(uint32_t face, const glm::dvec3& lo, const glm::dvec3& hi) const {
    if (!plane_meets(face, lo, hi)) return {};
    const glm::vec3* c = &corners_[size_t(face) * 3];
    glm::dvec3 face_lo, face_hi;
    face_box(face, face_lo, face_hi);
    if (glm::all(glm::greaterThanEqual(face_lo, lo)) && glm::all(glm::lessThanEqual(face_hi, hi))) {
        Part whole;
        whole.b[1] = {1.0, 0.0};
        whole.b[2] = {0.0, 1.0};
        whole.count = 3;
        return whole;
    }
    std::array<PartVertex, 9> polygon{PartVertex{{0.0, 0.0}, glm::dvec3(c[0])},
                                      PartVertex{{1.0, 0.0}, glm::dvec3(c[1])},
                                      PartVertex{{0.0, 1.0}, glm::dvec3(c[2])}};
    size_t count = 3;
    for (int plane = 0; plane < 6 && count > 0; ++plane) {
        const int axis = plane / 2;
        const auto inside = [&](const PartVertex& v) {
            return plane % 2 == 0 ? v.p[axis] - lo[axis] : hi[axis] - v.p[axis];
        };
        std::array<PartVertex, 9> clipped;
        size_t kept = 0;
        for (size_t i = 0; i < count; ++i) {
            const PartVertex& u = polygon[i];
            const PartVertex& v = polygon[(i + 1) % count];
            const double du = inside(u), dv = inside(v);
            // (A polygon made slightly concave by rounding could cross a plane more than twice:
            // the array bounds it.)
            if (du >= 0.0 && kept < clipped.size()) clipped[kept++] = u;
            if ((du >= 0.0) != (dv >= 0.0) && kept < clipped.size()) {
                const double s = du / (du - dv);
                clipped[kept++] = {u.b + s * (v.b - u.b), u.p + s * (v.p - u.p)};
            }
        }
        polygon = clipped;
        count = kept;
    }
    Part part;
    if (count < 3) return part;
    part.count = count;
    for (size_t i = 0; i < count; ++i) part.b[i] = polygon[i].b;
    return part;
}

uint32_t SurfaceSamples::build_boxes(uint32_t first, uint32_t count, std::vector<glm::vec3>& centres) {
    const auto node = uint32_t(box_nodes_.size());
    box_nodes_.emplace_back();
    glm::vec3 lo(INFINITY), hi(-INFINITY), centre_lo(INFINITY), centre_hi(-INFINITY);
    for (uint32_t i = first; i < first + count; ++i) {
        const glm::vec3* c = &corners_[size_t(box_faces_[i]) * 3];
        lo = glm::min(lo, glm::min(c[0], glm::min(c[1], c[2])));
        hi = glm::max(hi, glm::max(c[0], glm::max(c[1], c[2])));
        centre_lo = glm::min(centre_lo, centres[i]);
        centre_hi = glm::max(centre_hi, centres[i]);
    }
    box_nodes_[node].lo = lo;
    box_nodes_[node].hi = hi;
    box_nodes_[node].first = first;
    box_nodes_[node].count = count;
    if (count <= kLeafFaces) return node;
    const glm::vec3 extent = centre_hi - centre_lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    // Faces and centres sorted together by the centres' coordinate along the axis, split at the median.
    std::vector<uint32_t> order(count);
    for (uint32_t i = 0; i < count; ++i) order[i] = i;
    const uint32_t half = count / 2;
    std::nth_element(order.begin(), order.begin() + half, order.end(),
                     [&](uint32_t a, uint32_t b) { return centres[first + a][axis] < centres[first + b][axis]; });
    std::vector<uint32_t> faces(count);
    std::vector<glm::vec3> moved(count);
    for (uint32_t i = 0; i < count; ++i) faces[i] = box_faces_[first + order[i]], moved[i] = centres[first + order[i]];
    std::copy(faces.begin(), faces.end(), box_faces_.begin() + first);
    std::copy(moved.begin(), moved.end(), centres.begin() + first);
    build_boxes(first, half, centres);
    const uint32_t right = build_boxes(first + half, count - half, centres);
    box_nodes_[node].right = right;
    return node;
}

void SurfaceSamples::faces_meeting(const glm::dvec3& lo, const glm::dvec3& hi, std::vector<uint32_t>& r_faces) const {
    r_faces.clear();
    if (box_nodes_.empty()) return;
    const glm::vec3 flo(lo), fhi(hi);
    const auto meets = [&](const glm::vec3& a, const glm::vec3& b) {
        return a.x <= fhi.x && b.x >= flo.x && a.y <= fhi.y && b.y >= flo.y && a.z <= fhi.z && b.z >= flo.z;
    };
    const auto inside = [&](const glm::vec3& a, const glm::vec3& b) {
        return glm::all(glm::greaterThanEqual(a, flo)) && glm::all(glm::lessThanEqual(b, fhi));
    };
    uint32_t stack[64];
    size_t depth = 0;
    stack[depth++] = 0;
    while (depth > 0) {
        const uint32_t at = stack[--depth];
        const BoxNode& node = box_nodes_[at];
        if (!meets(node.lo, node.hi)) continue;
        if (inside(node.lo, node.hi)) {
            r_faces.insert(r_faces.end(), box_faces_.begin() + node.first,
                           box_faces_.begin() + node.first + node.count);
            continue;
        }
        if (node.right == 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const glm::vec3* c = &corners_[size_t(box_faces_[i]) * 3];
                if (meets(glm::min(c[0], glm::min(c[1], c[2])), glm::max(c[0], glm::max(c[1], c[2])))) {
                    r_faces.push_back(box_faces_[i]);
                }
            }
            continue;
        }
        stack[depth++] = node.right;
        stack[depth++] = at + 1;
    }
}

uint32_t SurfaceSamples::tile_index(int level, const glm::ivec3& at) {
    Level& l = levels_[size_t(level)];
    const uint64_t key = tile_key(at);
    if (key == l.last_key) return l.last_index;
    uint32_t& index = l.index[key];
    if (index == 0) {
        l.tiles.emplace_back();
        index = uint32_t(l.tiles.size());
    }
    l.last_key = key;
    l.last_index = index - 1;
    return index - 1;
}

void SurfaceSamples::build_face(uint32_t face, int level) {
    if (level >= levels() || face_area_[face] <= 0.0) return;
    glm::dvec3 lo, hi;
    face_box(face, lo, hi);
    // The tiles of its box that its plane passes through.
    tiles_over(level, lo, hi, [&](const glm::ivec3& at) {
        glm::dvec3 tile_lo, tile_hi;
        tile_box(level, at, tile_lo, tile_hi);
        if (plane_meets(face, tile_lo, tile_hi)) build(level, at);
    });
}

void SurfaceSamples::build_everywhere(int last) {
    last = std::min(last, levels() - 1);
    std::vector<Candidate> made;
    // The level's candidates with their tiles, without their points (computed again from the
    // face when tried): a level can have a few million.
    struct Placed {
        uint64_t id;
        uint32_t tile, face;
        float b1, b2;
    };
    std::vector<Placed> placed;
    std::vector<uint8_t> tile_phase;
    for (int k = 0; k <= last; ++k) {
        Level& l = levels_[size_t(k)];
        const bool fresh = std::none_of(l.tiles.begin(), l.tiles.end(), [](const Tile& t) { return t.built; });
        if (!fresh) {
            // Tiles built one by one before: the same points, tile by tile (a tile sees only the
            // neighbours of earlier phases, which a level built at once cannot tell apart).
            for (uint32_t f = 0; f < faces(); ++f) build_face(f, k);
            continue;
        }
        // Every face's candidates, by tile.
        const double side = kTileSpacings * radius_[size_t(k)];
        placed.clear();
        const auto place = [&](const glm::ivec3& at, const Candidate& c) {
            const uint32_t index = tile_index(k, at);
            if (tile_phase.size() <= index) tile_phase.resize(size_t(index) + 1);
            tile_phase[index] = uint8_t(phase(at));
            placed.push_back({c.id, index, c.face, c.b1, c.b2});
        };
        for (uint32_t f = 0; f < faces(); ++f) {
            if (face_area_[f] <= 0.0) continue;
            made.clear();
            if (face_extent_[f] <= side) {
                face_candidates(k, f, made);
                for (const Candidate& c : made) place(tile_of(k, glm::dvec3(c.p)), c);
                continue;
            }
            glm::dvec3 lo, hi;
            face_box(f, lo, hi);
            tiles_over(k, lo, hi, [&](const glm::ivec3& at) {
                glm::dvec3 tile_lo, tile_hi;
                tile_box(k, at, tile_lo, tile_hi);
                const Part part = part_in_box(f, tile_lo, tile_hi);
                if (part.count < 3) return;
                made.clear();
                part_candidates(k, tile_key(at), f, part, made);
                for (const Candidate& m : made) place(at, m);
            });
        }
        // Tile by tile, phase by phase (tiles of one phase never meet), each tile's candidates
        // by id, against every point of the levels before and of this level's tiles so far.
        std::vector<uint32_t> start(tile_phase.size() + 1, 0);  // per tile, its first candidate
        for (const Placed& c : placed) ++start[c.tile + 1];
        std::vector<uint32_t> tiles;
        for (uint32_t t = 0; t < tile_phase.size(); ++t) {
            if (start[t + 1] > 0) tiles.push_back(t);
            start[t + 1] += start[t];
        }
        std::vector<uint32_t> by_tile(placed.size());  // the candidates, tile after tile
        {
            std::vector<uint32_t> fill(start.begin(), start.end() - 1);
            for (uint32_t i = 0; i < placed.size(); ++i) by_tile[fill[placed[i].tile]++] = i;
        }
        std::stable_sort(tiles.begin(), tiles.end(),
                         [&](uint32_t a, uint32_t b) { return tile_phase[a] < tile_phase[b]; });
        size_t held = 0;
        for (int j = 0; j < k; ++j) held += levels_[size_t(j)].points.size();
        BlockGrid grid(origin_, radius_[size_t(k)], held + placed.size() / 4);
        for (int j = 0; j < k; ++j) {
            for (const glm::vec3& p : levels_[size_t(j)].points) grid.add(p);
        }
        // The tiles of a phase in parallel (each against the grid and its own points), then
        // filed in order.
        const auto r2 = float(radius_[size_t(k)] * radius_[size_t(k)]);
        std::vector<std::vector<Candidate>> kept;
        for (size_t first = 0; first < tiles.size();) {
            size_t end = first;
            while (end < tiles.size() && tile_phase[tiles[end]] == tile_phase[tiles[first]]) ++end;
            const size_t count = end - first;
            kept.assign(count, {});
            const size_t slices = std::min<size_t>(internal::hardware_threads(), std::max<size_t>(1, count / 64));
            internal::run_tasks(slices, [&](size_t slice) {
                std::vector<Candidate> mine;
                BlockGrid::Cache cache;
                for (size_t n = count * slice / slices; n < count * (slice + 1) / slices; ++n) {
                    const uint32_t t = tiles[first + n];
                    mine.clear();
                    for (uint32_t i = start[t]; i < start[t + 1]; ++i) {
                        const Placed& c = placed[by_tile[i]];
                        const glm::vec3* corner = &corners_[size_t(c.face) * 3];
                        mine.push_back({c.id, c.face, c.b1, c.b2,
                                        (1.0f - c.b1 - c.b2) * corner[0] + c.b1 * corner[1] + c.b2 * corner[2]});
                    }
                    std::sort(mine.begin(), mine.end(),
                              [](const Candidate& a, const Candidate& b) { return a.id < b.id; });
                    std::vector<Candidate>& out = kept[n];
                    for (const Candidate& c : mine) {
                        // The tile's own points first: fewer, and the nearest.
                        const bool close = std::any_of(out.begin(), out.end(), [&](const Candidate& q) {
                            const glm::vec3 d = q.p - c.p;
                            return glm::dot(d, d) < r2;
                        });
                        if (!close && !grid.near(c.p, r2, cache)) out.push_back(c);
                    }
                }
            });
            for (size_t n = 0; n < count; ++n) {
                for (const Candidate& c : kept[n]) grid.add(c.p);
                file(k, tiles[first + n], kept[n]);
            }
            first = end;
        }
        tile_phase.clear();
    }
    finish();
}

void SurfaceSamples::build_tile(int level, const glm::ivec3& at) {
    if (level >= 0 && level < levels()) build(level, at);
}

uint32_t SurfaceSamples::build(int level, const glm::ivec3& at) {
    const uint32_t index = tile_index(level, at);
    if (levels_[size_t(level)].tiles[index].built) return index;

    glm::dvec3 lo, hi;
    tile_box(level, at, lo, hi);
    std::vector<uint32_t> faces;
    faces_meeting(lo, hi, faces);
    // Faces no wider than a tile throw their candidates over the whole face, the same for every
    // tile they meet, and each tile takes those inside it; wider ones over their part in the tile.
    const double side = kTileSpacings * radius_[size_t(level)];
    std::vector<uint32_t> small;
    std::vector<std::pair<uint32_t, Part>> parts;
    for (uint32_t f : faces) {
        if (face_extent_[f] <= side) {
            small.push_back(f);
            continue;
        }
        const Part part = part_in_box(f, lo, hi);
        if (part.count >= 3) parts.emplace_back(f, part);
    }
    if (small.empty() && parts.empty()) {
        levels_[size_t(level)].tiles[index].built = true;
        return index;  // no surface here: no point, whatever is around
    }

    // What its points are tested against, built first: the neighbours of its level in earlier
    // phases, and the lower levels within r of it.
    const double r = radius_[size_t(level)];
    const int own_phase = phase(at);
    std::vector<glm::ivec3> before;
    for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const glm::ivec3 n = at + glm::ivec3(dx, dy, dz);
                if (glm::any(glm::lessThan(n, glm::ivec3(0))) ||
                    glm::any(glm::greaterThan(n, glm::ivec3(kMostTiles)))) {
                    continue;
                }
                if (phase(n) < own_phase) before.push_back(n);
            }
        }
    }
    std::vector<std::pair<int, uint32_t>> built;  // level, index
    for (const glm::ivec3& n : before) built.emplace_back(level, build(level, n));
    const glm::dvec3 near_lo = lo - r, near_hi = hi + r;
    for (int j = 0; j < level; ++j) {
        tiles_over(j, near_lo, near_hi, [&](const glm::ivec3& u) { built.emplace_back(j, build(j, u)); });
    }

    // Those points in a grid of cells of side r over the box widened by r.
    SpacingGrid grid(near_lo, near_hi, r);
    for (const auto& [j, i] : built) {
        const Level& l = levels_[size_t(j)];
        const Tile& tile = l.tiles[i];
        for (uint32_t k = tile.begin; k < tile.begin + tile.count; ++k) grid.add(l.points[k]);
    }

    // Candidates on each face's part, as many as its area asks for (rounded at random), tried in
    // the order of their ids.
    std::vector<Candidate> candidates;
    const uint64_t key = tile_key(at);
    for (const auto& [f, part] : parts) part_candidates(level, key, f, part, candidates);
    std::vector<Candidate> whole;
    for (uint32_t f : small) {
        whole.clear();
        face_candidates(level, f, whole);
        for (const Candidate& c : whole) {
            if (tile_of(level, glm::dvec3(c.p)) == at) candidates.push_back(c);
        }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.id < b.id; });

    // Tried by id, each kept at least r from the points around and from those kept before it.
    const auto r2 = float(r * r);
    std::vector<Candidate> kept;
    for (const Candidate& candidate : candidates) {
        if (grid.near(candidate.p, r2)) continue;
        grid.add(candidate.p);
        kept.push_back(candidate);
    }
    file(level, index, kept);
    return index;
}

void SurfaceSamples::file(int level, uint32_t index, std::span<const Candidate> kept) {
    const double below = density(level - 1), share = density(level) - below;
    Level& l = levels_[size_t(level)];
    Tile& tile = l.tiles[index];
    tile.begin = uint32_t(l.points.size());
    tile.count = uint32_t(kept.size());
    tile.built = true;
    for (const Candidate& c : kept) {
        l.points.push_back(c.p);
        const double u = SplitMix64::unit(SplitMix64::hash(c.id ^ 0x9e3779b97f4a7c15ull));
        fresh_.push_back({c.face, {c.id, below + (1.0 - u) * share, c.b1, c.b2}});
    }
    size_ += kept.size();
}

void SurfaceSamples::part_candidates(int level, uint64_t key, uint32_t face, const Part& part,
                                     std::vector<Candidate>& r_out) const {
    std::array<double, 9> fan{};  // cumulative areas of the triangles (b0, b_i, b_i+1)
    double total = 0.0;
    for (size_t i = 1; i + 1 < part.count; ++i) {
        const glm::dvec2 u = part.b[i] - part.b[0], v = part.b[i + 1] - part.b[0];
        total += 0.5 * std::abs(u.x * v.y - u.y * v.x);
        fan[i] = total;
    }
    SplitMix64 rng(tile_seed(seed_, level, key, face));
    const size_t count = candidate_count(part_area(face, part), radius_[size_t(level)], rng);
    const glm::vec3* c = &corners_[size_t(face) * 3];
    for (size_t n = 0; n < count; ++n) {
        const double pick = rng.uniform(0.0, total);
        size_t i = 1;
        while (i + 2 < part.count && fan[i] <= pick) ++i;
        const double s = std::sqrt(rng.uniform(0.0, 1.0)), t = rng.uniform(0.0, 1.0);
        const glm::dvec2 b = part.b[0] + s * (1.0 - t) * (part.b[i] - part.b[0]) + s * t * (part.b[i + 1] - part.b[0]);
        const auto b1 = float(b.x), b2 = float(b.y);
        r_out.push_back({rng.next() >> 1, face, b1, b2, (1.0f - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2]});
    }
}

void SurfaceSamples::face_candidates(int level, uint32_t face, std::vector<Candidate>& r_out) const {
    SplitMix64 rng(tile_seed(seed_, level, kWholeFace, face));
    const size_t count = candidate_count(face_area_[face], radius_[size_t(level)], rng);
    const glm::vec3* c = &corners_[size_t(face) * 3];
    for (size_t n = 0; n < count; ++n) {
        const double s = std::sqrt(rng.uniform(0.0, 1.0)), t = rng.uniform(0.0, 1.0);
        const auto b1 = float(s * (1.0 - t)), b2 = float(s * t);
        const uint64_t id = rng.next() >> 1;
        r_out.push_back({id, face, b1, b2, (1.0f - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2]});
    }
}

double SurfaceSamples::part_area(uint32_t face, const Part& part) const {
    double twice = 0.0;  // of the part in the (b1, b2) plane, where the face is the half square
    for (size_t i = 0; i < part.count; ++i) {
        const glm::dvec2& u = part.b[i];
        const glm::dvec2& v = part.b[(i + 1) % part.count];
        twice += u.x * v.y - u.y * v.x;
    }
    return std::abs(twice) * face_area_[face];
}

void SurfaceSamples::clear() {
    for (Level& level : levels_) level = Level();
    std::vector<Sample>().swap(samples_);
    std::fill(offsets_.begin(), offsets_.end(), 0);
    std::vector<std::pair<uint32_t, Sample>>().swap(fresh_);
    size_ = 0;
}

void SurfaceSamples::finish() {
    if (fresh_.empty()) return;
    const auto by_rank = [](const Sample& a, const Sample& b) {
        return a.rank != b.rank ? a.rank < b.rank : a.id < b.id;
    };
    std::sort(fresh_.begin(), fresh_.end(), [&](const auto& a, const auto& b) {
        return a.first != b.first ? a.first < b.first : by_rank(a.second, b.second);
    });
    // Each face's samples merged with its new ones, face after face.
    std::vector<Sample> merged;
    merged.reserve(samples_.size() + fresh_.size());
    std::vector<size_t> offsets(offsets_.size(), 0);
    size_t next = 0;
    for (size_t f = 0; f + 1 < offsets_.size(); ++f) {
        offsets[f] = merged.size();
        const Sample* old = samples_.data() + offsets_[f];
        const Sample* old_end = samples_.data() + offsets_[f + 1];
        while (next < fresh_.size() && fresh_[next].first == f) {
            const Sample& s = fresh_[next].second;
            while (old != old_end && by_rank(*old, s)) merged.push_back(*old++);
            merged.push_back(s);
            ++next;
        }
        merged.insert(merged.end(), old, old_end);
    }
    offsets.back() = merged.size();
    samples_.swap(merged);
    offsets_.swap(offsets);
    fresh_.clear();
}

}  // namespace inkline::core
