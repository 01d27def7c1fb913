// SPDX-License-Identifier: MIT
#include "core/lines/intersections.h"

#include "core/internal/parallel.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <optional>

namespace inkline::core {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using FaceBox = CGAL::Box_intersection_d::Box_with_info_d<double, 3, uint32_t>;

// The ties of the exact predicates are broken as if every vertex were moved by
//   eps * object * kNudge + eps^2 * jitter(vertex)
// for an infinitesimal eps: each object steps along a fixed direction by its index (so of two
// objects that touch, the one with the higher index lies on the kNudge side), and within one
// object each vertex by a small amount of its own. A predicate that is zero takes the sign of the
// first term that is not. kNudge is generic, so that no face of an ordinary model (axis-aligned,
// or at a simple angle) lies parallel to it.
constexpr glm::dvec3 kNudge(0.3713906763541037, 0.5570860145311556, 0.7417813527082074);

// A fixed pseudo-random vector in [-1, 1]^3 for a vertex (a hash of its index).
glm::dvec3 jitter(uint32_t vertex) {
    uint64_t x = vertex + 0x9e3779b97f4a7c15ull;
    glm::dvec3 out;
    for (int i = 0; i < 3; ++i) {
        x ^= x >> 30;
        x *= 0xbf58476d1ce4e5b9ull;
        x ^= x >> 27;
        x *= 0x94d049bb133111ebull;
        x ^= x >> 31;
        out[i] = double(x >> 11) * 0x1.0p-52 - 1.0;
    }
    return out;
}

constexpr uint32_t kNone = 0xffffffffu;

// Candidate face boxes up to this many are paired by a sweep along one axis; more by CGAL's
// segment tree, whose setup costs more than the sweep on a few thousand boxes (1,844 boxes of a
// shot's ground plane and objects: 1.4 ms a frame) but which stays n log^2 n however the boxes
// crowd along every axis.
constexpr size_t kMaxSweptBoxes = 4096;

// Where an edge of one surface pierces a face of the other.
struct Pierce {
    uint32_t edge = kNone;
    uint32_t face = kNone;
    glm::dvec3 point{0.0};

    uint64_t key() const { return (uint64_t(edge) << 32) | face; }
};

// The crossing of a face of the first surface and one of the other.
struct Segment {
    uint32_t first = kNone, other = kNone;
    std::array<Pierce, 2> ends;
};

int sign_of(CGAL::Orientation o) { return o == CGAL::POSITIVE ? 1 : o == CGAL::NEGATIVE ? -1 : 0; }
int sign_of(double x) { return x > 0.0 ? 1 : x < 0.0 ? -1 : 0; }

class Crossings {
  public:
    Crossings(const Mesh& mesh, const EdgeTable& table, std::span<const glm::uvec3> face_edges,
              std::span<const uint32_t> face_objects)
        : mesh_(mesh), table_(table), face_edges_(face_edges), face_objects_(face_objects),
          vertex_objects_(mesh.positions.size(), 0) {
        // A vertex's object is that of the last face using it (objects that share a vertex
        // touch there anyway).
        for (size_t f = 0; f < face_objects.size(); ++f) {
            for (int c = 0; c < 3; ++c) vertex_objects_[mesh.triangles[f][c]] = face_objects[f];
        }
    }

    uint32_t object_of(uint32_t face) const { return face_objects_.empty() ? 0 : face_objects_[face]; }
    uint32_t object_of_vertex(uint32_t vertex) const { return vertex_objects_[vertex]; }

    // The crossing of faces f (first surface) and g, if they cross in a segment.
    std::optional<Segment> cross(uint32_t f, uint32_t g) const {
        const glm::uvec3 tf = mesh_.triangles[f], tg = mesh_.triangles[g];
        std::array<int, 3> side_f{}, side_g{};
        for (int k = 0; k < 3; ++k) side_f[k] = side(tf[k], g);
        if (side_f[0] == side_f[1] && side_f[1] == side_f[2]) return std::nullopt;
        for (int k = 0; k < 3; ++k) side_g[k] = side(tg[k], f);
        if (side_g[0] == side_g[1] && side_g[1] == side_g[2]) return std::nullopt;

        std::array<Pierce, 4> found;
        int count = 0;
        auto pierces_from = [&](uint32_t face, const std::array<int, 3>& sides, uint32_t other) {
            for (int k = 0; k < 3; ++k) {
                if (sides[k] == sides[(k + 1) % 3]) continue;
                const uint32_t e = face_edges_[face][k];
                if (pierces(e, other) && count < 4) found[count++] = pierce(e, other);
            }
        };
        pierces_from(f, side_f, g);
        pierces_from(g, side_g, f);
        if (count != 2) return std::nullopt;  // only where rounding broke a tie of ties inconsistently
        return Segment{f, g, {found[0], found[1]}};
    }

  private:
    glm::dvec3 position(uint32_t v) const { return glm::dvec3(mesh_.positions[v]); }
    Point point(uint32_t v) const {
        const glm::vec3& p = mesh_.positions[v];
        return {p.x, p.y, p.z};
    }

    // The sign of det[q - p, r - p, s - p] for vertices p, q, r, s: exact (CGAL), with ties
    // broken by the perturbation above. Never 0.
    int orient(uint32_t p, uint32_t q, uint32_t r, uint32_t s) const {
        const int exact = sign_of(CGAL::orientation(point(p), point(q), point(r), point(s)));
        if (exact != 0) return exact;
        // First-order change of the determinant when the points move by d_p .. d_s.
        const glm::dvec3 pp = position(p), qp = position(q) - pp, rp = position(r) - pp, sp = position(s) - pp;
        const glm::dvec3 grad_q = glm::cross(rp, sp), grad_r = glm::cross(sp, qp), grad_s = glm::cross(qp, rp);
        auto change = [&](auto step) {
            const glm::dvec3 dp = step(p);
            return glm::dot(grad_q, step(q) - dp) + glm::dot(grad_r, step(r) - dp) + glm::dot(grad_s, step(s) - dp);
        };
        const int by_object = sign_of(change([&](uint32_t v) { return kNudge * double(vertex_objects_[v]); }));
        if (by_object != 0) return by_object;
        const int by_vertex = sign_of(change([](uint32_t v) { return jitter(v); }));
        return by_vertex != 0 ? by_vertex : 1;
    }

    // The side of face g's plane that vertex v lies on: +1 or -1.
    int side(uint32_t v, uint32_t g) const {
        const glm::uvec3 t = mesh_.triangles[g];
        return orient(t.x, t.y, t.z, v);
    }

    // Whether edge e (its ends on opposite sides of face g's plane) passes through face g: the
    // edge's line passes each of g's edges on the same side.
    bool pierces(uint32_t e, uint32_t g) const {
        const glm::uvec2 ab = table_.edge_vertices[e];
        const glm::uvec3 t = mesh_.triangles[g];
        const int first = orient(ab.x, ab.y, t.x, t.y);
        return orient(ab.x, ab.y, t.y, t.z) == first && orient(ab.x, ab.y, t.z, t.x) == first;
    }

    // The point where edge e meets face g's plane; a function of (e, g) alone, so both face pairs
    // that share the pierce compute the same point.
    Pierce pierce(uint32_t e, uint32_t g) const {
        const glm::uvec2 ab = table_.edge_vertices[e];
        const glm::uvec3 t = mesh_.triangles[g];
        const glm::dvec3 a = position(ab.x), b = position(ab.y), u = position(t.x);
        const glm::dvec3 n = glm::cross(position(t.y) - u, position(t.z) - u);
        const double da = glm::dot(n, a - u), db = glm::dot(n, b - u);
        const double t_ab = da != db ? std::clamp(da / (da - db), 0.0, 1.0) : 0.5;
        return {e, g, a + (b - a) * t_ab};
    }

    const Mesh& mesh_;
    const EdgeTable& table_;
    std::span<const glm::uvec3> face_edges_;
    std::span<const uint32_t> face_objects_;
    std::vector<uint32_t> vertex_objects_;
};

// Boxes in float, as the positions are: comparisons of floats are exact.
struct Box3 {
    glm::vec3 min{HUGE_VALF}, max{-HUGE_VALF};
    void add(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    bool overlaps(const Box3& o) const {
        return min.x <= o.max.x && o.min.x <= max.x && min.y <= o.max.y && o.min.y <= max.y && min.z <= o.max.z &&
               o.min.z <= max.z;
    }
};

Box3 face_box(const Mesh& mesh, uint32_t f) {
    Box3 box;
    for (int c = 0; c < 3; ++c) box.add(mesh.positions[mesh.triangles[f][c]]);
    return box;
}

bool share_vertex(const glm::uvec3& a, const glm::uvec3& b) {
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (a[i] == b[j]) return true;
        }
    }
    return false;
}

// The axis along which a sweep over the boxes compares the fewest pairs: for each box, those
// that start within its extent along the axis.
int sweep_axis(const std::vector<std::pair<Box3, uint32_t>>& boxes) {
    int best = 0;
    size_t fewest = SIZE_MAX;
    std::vector<float> starts(boxes.size());
    for (int axis = 0; axis < 3; ++axis) {
        for (size_t i = 0; i < boxes.size(); ++i) starts[i] = boxes[i].first.min[axis];
        std::sort(starts.begin(), starts.end());
        size_t compared = 0;
        for (const auto& [box, face] : boxes) {
            const auto lo = std::lower_bound(starts.begin(), starts.end(), box.min[axis]);
            const auto hi = std::upper_bound(lo, starts.end(), box.max[axis]);
            compared += size_t(hi - lo);
        }
        if (compared < fewest) fewest = compared, best = axis;
    }
    return best;
}

// Face pairs whose boxes overlap and that may cross under the options, each (first, other).
std::vector<std::pair<uint32_t, uint32_t>> candidate_pairs(const Mesh& mesh, const EdgeTable& table,
                                                           const Crossings& crossings, uint32_t objects,
                                                           const IntersectionOptions& options) {
    const auto faces = uint32_t(mesh.triangles.size());
    // Between objects, only faces inside another object's box can cross one of its faces.
    std::vector<Box3> object_boxes(objects);
    for (size_t v = 0; v < mesh.positions.size(); ++v) object_boxes[crossings.object_of_vertex(uint32_t(v))].add(mesh.positions[v]);
    std::vector<std::vector<uint32_t>> neighbours(objects);
    for (uint32_t a = 0; a < objects; ++a) {
        for (uint32_t b = 0; b < objects; ++b) {
            if (a != b && object_boxes[a].overlaps(object_boxes[b])) neighbours[a].push_back(b);
        }
    }
    std::vector<uint8_t> wanted(faces, 0);
    internal::parallel_for(faces, 65536, [&](size_t begin, size_t end) {
        for (size_t f = begin; f < end; ++f) {
            if (!table.face_valid[f]) continue;
            if (options.self) {
                wanted[f] = 1;
                continue;
            }
            const std::vector<uint32_t>& near = neighbours[crossings.object_of(uint32_t(f))];
            if (near.empty()) continue;
            const Box3 b = face_box(mesh, uint32_t(f));
            for (uint32_t o : near) {
                if (object_boxes[o].overlaps(b)) {
                    wanted[f] = 1;
                    break;
                }
            }
        }
    });
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    auto meet = [&](uint32_t f, uint32_t g) {
        const uint32_t of = crossings.object_of(f), og = crossings.object_of(g);
        if (of == og) {
            if (!options.self || share_vertex(mesh.triangles[f], mesh.triangles[g])) return;
            if (g < f) std::swap(f, g);
        } else {
            if (!options.between_objects) return;
            if (og < of) std::swap(f, g);
        }
        pairs.emplace_back(f, g);
    };
    std::vector<std::pair<Box3, uint32_t>> boxes;
    for (uint32_t f = 0; f < faces; ++f) {
        if (wanted[f]) boxes.emplace_back(face_box(mesh, f), f);
    }
    if (boxes.size() <= kMaxSweptBoxes) {
        // Few boxes (a ground plane under a few objects): sorted by their least coordinate along
        // one axis, each compared with those that start before it ends. The same pairs as below,
        // with none of its setup. The axis is the one with the fewest such comparisons (a flat
        // ground's boxes all overlap along its normal, long faces along their length).
        const int axis = sweep_axis(boxes);
        std::sort(boxes.begin(), boxes.end(),
                  [axis](const auto& a, const auto& b) { return a.first.min[axis] < b.first.min[axis]; });
        for (size_t i = 0; i < boxes.size(); ++i) {
            const Box3& a = boxes[i].first;
            for (size_t j = i + 1; j < boxes.size() && boxes[j].first.min[axis] <= a.max[axis]; ++j) {
                if (a.overlaps(boxes[j].first)) meet(boxes[i].second, boxes[j].second);
            }
        }
    } else {
        // Many: a segment tree, n log^2 n however the boxes crowd along one axis.
        std::vector<FaceBox> tree_boxes;
        tree_boxes.reserve(boxes.size());
        for (const auto& [b, f] : boxes) {
            tree_boxes.emplace_back(CGAL::Bbox_3(b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z), f);
        }
        CGAL::box_self_intersection_d(tree_boxes.begin(), tree_boxes.end(),
                                      [&](const FaceBox& x, const FaceBox& y) { meet(x.info(), y.info()); });
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

// The edge of face f that a segment's chain names: the one a pierce point lies on, else the
// edge nearest the segment's middle.
uint32_t named_edge(const Mesh& mesh, const EdgeTable& table, std::span<const glm::uvec3> face_edges,
                    const Segment& s) {
    const glm::uvec3 fe = face_edges[s.first];
    for (const Pierce& p : s.ends) {
        if (p.face == s.other) return p.edge;
    }
    const glm::dvec3 mid = 0.5 * (s.ends[0].point + s.ends[1].point);
    uint32_t best = fe[0];
    double best_d = HUGE_VAL;
    for (int k = 0; k < 3; ++k) {
        const glm::uvec2 ab = table.edge_vertices[fe[k]];
        const glm::dvec3 a(mesh.positions[ab.x]), b(mesh.positions[ab.y]);
        const glm::dvec3 d = b - a;
        const double len2 = glm::dot(d, d);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(mid - a, d) / len2, 0.0, 1.0) : 0.0;
        const double dist = glm::length(mid - (a + d * t));
        if (dist < best_d) best_d = dist, best = fe[k];
    }
    return best;
}

// Links the segments through the pierce points they share (a point shared by exactly two).
std::vector<Chain> link_segments(const Mesh& mesh, const EdgeTable& table, std::span<const glm::uvec3> face_edges,
                                 const std::vector<Segment>& segments) {
    const size_t n = segments.size();
    std::vector<std::pair<uint64_t, uint32_t>> ends;  // (pierce key, 2 * segment + end)
    ends.reserve(2 * n);
    for (size_t s = 0; s < n; ++s) {
        for (uint32_t k = 0; k < 2; ++k) ends.emplace_back(segments[s].ends[k].key(), uint32_t(2 * s + k));
    }
    std::sort(ends.begin(), ends.end());
    std::vector<uint32_t> link(2 * n, kNone);
    for (size_t i = 0; i < ends.size();) {
        size_t j = i;
        while (j < ends.size() && ends[j].first == ends[i].first) ++j;
        if (j - i == 2) {
            link[ends[i].second] = ends[i + 1].second;
            link[ends[i + 1].second] = ends[i].second;
        }
        i = j;
    }

    std::vector<uint8_t> used(n, 0);
    std::vector<Chain> chains;
    auto walk = [&](uint32_t start, uint32_t in) {
        Chain c;
        c.kind = LineKind::kIntersection;
        c.points.push_back(segments[start].ends[in].point);
        uint32_t s = start, at = in;
        while (true) {
            used[s] = 1;
            const Segment& seg = segments[s];
            c.points.push_back(seg.ends[1 - at].point);
            c.edges.push_back(named_edge(mesh, table, face_edges, seg));
            c.crossing_faces.push_back(seg.other);
            c.first_faces.push_back(seg.first);
            const uint32_t next = link[2 * s + (1 - at)];
            if (next == kNone) break;
            if (next / 2 == start) {
                c.closed = true;
                c.points.back() = c.points.front();
                break;
            }
            if (used[next / 2]) break;
            s = next / 2;
            at = next % 2;
        }
        chains.push_back(std::move(c));
    };
    for (uint32_t s = 0; s < n; ++s) {
        if (used[s]) continue;
        if (link[2 * s] == kNone) {
            walk(s, 0);
        } else if (link[2 * s + 1] == kNone) {
            walk(s, 1);
        }
    }
    for (uint32_t s = 0; s < n; ++s) {
        if (!used[s]) walk(s, 0);
    }
    return chains;
}

std::vector<Chain> trace_all(const Mesh& mesh, const EdgeTable& table, std::span<const glm::uvec3> face_edges,
                         std::span<const uint32_t> face_objects, const IntersectionOptions& options,
                         IntersectionStats& stats) {
    stats = {};
    uint32_t objects = 1;
    for (uint32_t o : face_objects) objects = std::max(objects, o + 1);
    const bool between = options.between_objects && objects > 1;
    if (!between && !options.self) return {};
    const Crossings crossings(mesh, table, face_edges, face_objects);
    const auto pairs = candidate_pairs(mesh, table, crossings, objects, {.between_objects = between, .self = options.self});
    stats.candidate_pairs = pairs.size();

    std::vector<std::optional<Segment>> crossed(pairs.size());
    internal::parallel_for(pairs.size(), 4096, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) crossed[i] = crossings.cross(pairs[i].first, pairs[i].second);
    });
    std::vector<Segment> segments;
    for (auto& s : crossed) {
        if (s) segments.push_back(*s);
    }
    stats.segments = segments.size();
    return link_segments(mesh, table, face_edges, segments);
}

}  // namespace

std::vector<Chain> trace_intersections(const Mesh& mesh, const EdgeTable& table,
                                       std::span<const uint32_t> face_objects, const IntersectionOptions& options,
                                       IntersectionStats* r_stats) {
    IntersectionStats stats;
    const std::vector<glm::uvec3> face_edges_of = face_edges(mesh, table);
    std::vector<Chain> chains = trace_all(mesh, table, face_edges_of, face_objects, options, stats);
    if (r_stats) *r_stats = stats;
    return chains;
}

const std::vector<Chain>& IntersectionTracer::trace(const Mesh& mesh, const EdgeTable& table,
                                                    std::span<const uint32_t> face_objects, bool positions_changed) {
    if (traced_ && !positions_changed) return chains_;
    if (!traced_ || table_ != &table || face_edges_.size() != mesh.triangles.size()) {
        face_edges_ = face_edges(mesh, table);
        table_ = &table;
    }
    chains_ = trace_all(mesh, table, face_edges_, face_objects, options_, stats_);
    traced_ = true;
    return chains_;
}

}  // namespace inkline::core
