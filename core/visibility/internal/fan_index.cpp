// SPDX-License-Identifier: MIT
#include "core/visibility/internal/fan_index.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace inkline::core::internal {
namespace {

// A leaf box holds at most this many faces: their own rim test costs two dot products each,
// less than descending a level, and a node (two boxes, 256 bytes) costs more memory than 16
// faces' own data.
constexpr uint32_t kLeafFaces = 16;

// The fan faces of `vertex`, ascending: valid faces whose two edges at the vertex each have at
// most two valid faces. A face is listed by both of its edges at the vertex exactly then.
std::vector<uint32_t> fan_faces(const EdgeTable& table, uint32_t vertex, std::vector<uint32_t>& r_scratch) {
    r_scratch.clear();
    for (const uint32_t e : table.edges_around(vertex)) {
        const auto faces = table.faces_of(e);
        size_t valid = 0;
        for (const uint32_t f : faces) valid += table.face_valid[f];
        if (valid > 2) continue;
        for (const uint32_t f : faces) {
            if (table.face_valid[f]) r_scratch.push_back(f);
        }
    }
    std::sort(r_scratch.begin(), r_scratch.end());
    std::vector<uint32_t> out;
    for (size_t i = 1; i < r_scratch.size(); ++i) {
        if (r_scratch[i] == r_scratch[i - 1]) out.push_back(r_scratch[i]);
    }
    return out;
}

// Orders the faces of the fan around `apex` so that each shares an edge at the apex with the one
// before wherever the fan allows: a whole umbrella becomes one ring, a fan with gaps (or several
// umbrellas at one vertex) one run per piece. Returns each face's two corners other than the
// apex, in the face's own turning order.
std::vector<glm::uvec2> ring_order(const Mesh& mesh, uint32_t apex, std::vector<uint32_t>& r_faces) {
    const auto n = uint32_t(r_faces.size());
    std::vector<glm::uvec2> rims(n);
    for (uint32_t i = 0; i < n; ++i) {
        const glm::uvec3 t = mesh.triangles[r_faces[i]];
        const int k = t.x == apex ? 0 : t.y == apex ? 1 : 2;
        rims[i] = {t[(k + 1) % 3], t[(k + 2) % 3]};
    }
    // Faces meeting at a rim vertex share the edge (apex, rim vertex), which has at most two.
    struct End {
        uint32_t vertex, face;
        int side;
    };
    std::vector<End> ends;
    ends.reserve(2 * size_t(n));
    for (uint32_t i = 0; i < n; ++i) {
        ends.push_back({rims[i].x, i, 0});
        ends.push_back({rims[i].y, i, 1});
    }
    std::sort(ends.begin(), ends.end(),
              [](const End& a, const End& b) { return a.vertex != b.vertex ? a.vertex < b.vertex : a.face < b.face; });
    std::vector<glm::uvec2> next(n, glm::uvec2(kNoIndex));
    for (size_t i = 1; i < ends.size(); ++i) {
        if (ends[i].vertex != ends[i - 1].vertex) continue;
        next[ends[i - 1].face][ends[i - 1].side] = ends[i].face;
        next[ends[i].face][ends[i].side] = ends[i - 1].face;
    }
    // Walk from the ends of open runs first, then round the closed rings.
    std::vector<uint32_t> order;
    order.reserve(n);
    std::vector<uint8_t> visited(n, 0);
    auto walk = [&](uint32_t face) {
        while (face != kNoIndex && !visited[face]) {
            visited[face] = 1;
            order.push_back(face);
            const glm::uvec2 link = next[face];
            face = link.x != kNoIndex && !visited[link.x] ? link.x : link.y;
        }
    };
    for (uint32_t i = 0; i < n; ++i) {
        if (next[i].x == kNoIndex || next[i].y == kNoIndex) walk(i);
    }
    for (uint32_t i = 0; i < n; ++i) walk(i);
    INKLINE_CHECK_EQ(order.size(), size_t(n));

    std::vector<uint32_t> faces(n);
    std::vector<glm::uvec2> ordered_rims(n);
    for (uint32_t i = 0; i < n; ++i) {
        faces[i] = r_faces[order[i]];
        ordered_rims[i] = rims[order[i]];
    }
    r_faces = std::move(faces);
    return ordered_rims;
}

// Unit vector along v; nullopt when v has no usable length.
std::optional<glm::dvec3> unit(const glm::dvec3& v) {
    const double length = glm::length(v);
    if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
    return v / length;
}

// An orthonormal frame for a run of points (rim points or normals): the first axis along the
// chord from `first` to `last`, the second towards `middle` (the plane of a circular arc), the
// third across. Falls back to the coordinate axes where the points do not span a direction; any
// frame bounds correctly, these bound a smooth curve tightly.
void run_frame(const glm::dvec3& first, const glm::dvec3& middle, const glm::dvec3& last, glm::dvec3 (&r_axes)[3]) {
    // Below this fraction of the run's size a direction is rounding, not geometry.
    constexpr double kFlat = 1e-6;
    const double size = std::max(glm::length(last - first), glm::length(middle - first));
    glm::dvec3 u(1.0, 0.0, 0.0);
    if (const auto chord = unit(last - first); chord && glm::length(last - first) > kFlat * size) {
        u = *chord;
    } else if (const auto half = unit(middle - first)) {
        u = *half;
    }
    // The second axis: the middle point's offset across the chord, or the coordinate axis
    // least along u; made orthogonal to u twice, so rounding leaves it at right angles.
    glm::dvec3 v = middle - first;
    v -= u * glm::dot(u, v);
    if (!(glm::length(v) > kFlat * size)) {
        const glm::dvec3 size_u = glm::abs(u);
        v = size_u.x <= size_u.y && size_u.x <= size_u.z ? glm::dvec3(1.0, 0.0, 0.0)
            : size_u.y <= size_u.z                       ? glm::dvec3(0.0, 1.0, 0.0)
                                                         : glm::dvec3(0.0, 0.0, 1.0);
        v -= u * glm::dot(u, v);
    }
    v = glm::normalize(v);
    v = glm::normalize(v - u * glm::dot(u, v));
    r_axes[0] = u;
    r_axes[1] = v;
    r_axes[2] = glm::cross(u, v);
}

// Half the distance from 1 to the next double: the relative rounding of one operation.
constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2.0;

double l1(const glm::dvec3& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); }

// Sets the centre and half extents of `box` (its axes set) to hold the points.
template <class Box>
void fit_box(const std::vector<glm::dvec3>& points, Box& box) {
    glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
    for (const glm::dvec3& x : points) {
        const glm::dvec3 along(glm::dot(x, box.axes[0]), glm::dot(x, box.axes[1]), glm::dot(x, box.axes[2]));
        low = glm::min(low, along);
        high = glm::max(high, along);
    }
    const glm::dvec3 mid = (low + high) * 0.5;
    box.center = box.axes[0] * mid.x + box.axes[1] * mid.y + box.axes[2] * mid.z;
    box.half = (high - low) * 0.5;
}

}  // namespace

FanIndex::FanIndex(const Mesh& mesh, const EdgeTable& table, double scale) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    // Apexes. A fan face's two edges at the apex have at most two faces each, so a vertex with
    // fewer edges than kMinFanFaces has fewer fan faces: most meshes stop after this pass over
    // the vertices' edge counts.
    struct Candidate {
        uint32_t vertex;
        std::vector<uint32_t> faces;
    };
    std::vector<Candidate> candidates;
    std::vector<uint32_t> scratch;
    const size_t vertices = table.vertex_edge_offsets.empty() ? 0 : table.vertex_edge_offsets.size() - 1;
    for (uint32_t v = 0; v < vertices; ++v) {
        if (table.vertex_edge_offsets[v + 1] - table.vertex_edge_offsets[v] < kMinFanFaces) continue;
        std::vector<uint32_t> faces = fan_faces(table, v, scratch);
        if (faces.size() >= kMinFanFaces) candidates.push_back({v, std::move(faces)});
    }
    if (candidates.empty()) return;

    // The apex with the most fan faces first; a face it takes is no other fan's.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.faces.size() > b.faces.size(); });
    in_fan_.assign(mesh.triangles.size(), 0);
    std::vector<uint32_t> local(mesh.positions.size(), kNoIndex);
    auto local_of = [&](uint32_t v) {
        if (local[v] == kNoIndex) {
            local[v] = uint32_t(vertex_of_.size());
            vertex_of_.push_back(v);
        }
        return local[v];
    };
    for (Candidate& candidate : candidates) {
        std::erase_if(candidate.faces, [&](uint32_t f) { return in_fan_[f] != 0; });
        if (candidate.faces.size() < kMinFanFaces) continue;
        for (const uint32_t f : candidate.faces) in_fan_[f] = 1;
        const std::vector<glm::uvec2> rims = ring_order(mesh, candidate.vertex, candidate.faces);
        Fan fan;
        fan.apex = local_of(candidate.vertex);
        fan.first = uint32_t(faces_.size());
        for (size_t i = 0; i < rims.size(); ++i) {
            faces_.push_back(candidate.faces[i]);
            rims_.emplace_back(local_of(rims[i].x), local_of(rims[i].y));
        }
        fan.end = uint32_t(faces_.size());
        nodes_.reserve(nodes_.size() + 2 * ((rims.size() + kLeafFaces - 1) / kLeafFaces));
        fan.root = build_nodes(fan.first, fan.end);
        fans_.push_back(fan);
    }
    if (fans_.empty()) {
        in_fan_.clear();
        vertex_of_.clear();
        return;
    }
    positions_.resize(vertex_of_.size());
    normals_.resize(faces_.size());
    normal_errors_.resize(faces_.size());
    update_positions(mesh, scale);
}

std::vector<uint32_t> FanIndex::faces(uint32_t fan) const {
    return {faces_.begin() + fans_[fan].first, faces_.begin() + fans_[fan].end};
}

void FanIndex::update_positions(const Mesh& mesh, double scale) {
    for (size_t v = 0; v < vertex_of_.size(); ++v) {
        INKLINE_CHECK(vertex_of_[v] < mesh.positions.size());
        positions_[v] = glm::dvec3(mesh.positions[vertex_of_[v]]) * scale;
    }
    for (uint32_t fan = 0; fan < fans_.size(); ++fan) fit(fan);
}

uint32_t FanIndex::build_nodes(uint32_t begin, uint32_t end) {
    const auto index = uint32_t(nodes_.size());
    nodes_.push_back({});
    nodes_[index].begin = begin;
    nodes_[index].end = end;
    if (end - begin > kLeafFaces) {
        // Half, rounded up to whole leaves: the leaves come out full but for the last.
        const uint32_t half = (end - begin) / 2;
        const uint32_t middle = begin + (half + kLeafFaces - 1) / kLeafFaces * kLeafFaces;
        build_nodes(begin, middle);  // index + 1
        const uint32_t right = build_nodes(middle, end);
        nodes_[index].right = right;
    }
    return index;
}

void FanIndex::fit(uint32_t fan_id) {
    Fan& fan = fans_[fan_id];
    const glm::dvec3 apex = positions_[fan.apex];
    fan.bounds = Bounds();
    fan.bounds.add(apex);
    fan.radius = 0.0;
    fan.low = fan.high = glm::dvec3(0.0);
    for (uint32_t i = fan.first; i < fan.end; ++i) {
        const glm::dvec3 b = positions_[rims_[i].x], c = positions_[rims_[i].y];
        fan.bounds.add(b);
        fan.bounds.add(c);
        const glm::dvec3 to_b = b - apex, to_c = c - apex;
        fan.low = glm::min(fan.low, glm::min(to_b, to_c));
        fan.high = glm::max(fan.high, glm::max(to_b, to_c));
        fan.radius = std::max({fan.radius, l1(to_b), l1(to_c)});
        // The cross product's components are off by a few units of rounding of |to_b| |to_c|,
        // so its direction by that over its length; a face too thin for any bound gets 2.
        const glm::dvec3 cross = glm::cross(to_b, to_c);
        const double area = glm::length(cross);
        const double error = 32.0 * kUnitRoundoff * glm::length(to_b) * glm::length(to_c) / area + 4.0 * kUnitRoundoff;
        if (area > 0.0 && error < 1.0) {
            normals_[i] = cross / area;
            normal_errors_[i] = error;
        } else {
            normals_[i] = glm::dvec3(0.0);
            normal_errors_[i] = 2.0;
        }
    }
    std::vector<glm::dvec3> scratch;
    fit_node(fan.root, apex, scratch);
}

void FanIndex::fit_node(uint32_t index, const glm::dvec3& apex, std::vector<glm::dvec3>& r_scratch) {
    // Bottom-up in one pass: a leaf's boxes from its faces' rim points and normals, an inner
    // node's from the corners of its children's boxes (which hold their points).
    if (nodes_[index].right != 0) {
        fit_node(index + 1, apex, r_scratch);
        fit_node(nodes_[index].right, apex, r_scratch);
    }
    Node& node = nodes_[index];
    const uint32_t first = node.begin, middle = (node.begin + node.end) / 2, last = node.end - 1;
    std::vector<glm::dvec3>& points = r_scratch;
    for (const bool rim : {true, false}) {
        Box& box = rim ? node.rim : node.normals;
        points.clear();
        double error = 0.0;
        if (node.right == 0) {
            for (uint32_t i = node.begin; i < node.end; ++i) {
                if (rim) {
                    points.push_back(positions_[rims_[i].x] - apex);
                    points.push_back(positions_[rims_[i].y] - apex);
                } else {
                    points.push_back(normals_[i]);
                    error = std::max(error, normal_errors_[i]);
                }
            }
        } else {
            for (const Node* child : {&nodes_[index + 1], &nodes_[node.right]}) {
                const Box& part = rim ? child->rim : child->normals;
                for (int corner = 0; corner < 8; ++corner) {
                    glm::dvec3 x = part.center;
                    for (int k = 0; k < 3; ++k) x += part.axes[k] * (corner >> k & 1 ? part.half[k] : -part.half[k]);
                    points.push_back(x);
                }
            }
        }
        // The frame from the run's first, middle and last points.
        if (rim) {
            const glm::dvec3 a = positions_[rims_[first].x] - apex;
            const glm::dvec3 last_x = positions_[rims_[last].x] - apex, last_y = positions_[rims_[last].y] - apex;
            const glm::dvec3 c = glm::length(last_x - a) > glm::length(last_y - a) ? last_x : last_y;
            run_frame(a, positions_[rims_[middle].x] - apex, c, box.axes);
        } else {
            run_frame(normals_[first], normals_[middle], normals_[last], box.axes);
        }
        fit_box(points, box);
        box.half += glm::dvec3(error);
    }
}

}  // namespace inkline::core::internal
