// SPDX-License-Identifier: MIT
#include "core/mesh/topology.h"

#include "core/internal/parallel.h"
#include "core/internal/union_find.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <numeric>

namespace inkline::core {
namespace {

// A face whose doubled area is below this fraction of its longest edge squared is treated as
// zero-area: its normal would be numerically meaningless for the facing test.
constexpr double kDegenerateAreaRatio = 1e-12;

// Meshes with fewer faces (edges, vertices) are checked on one thread.
constexpr size_t kMinParallelFaces = 100000;
constexpr size_t kMinParallelEdges = 150000;
constexpr size_t kMinParallelVertices = 50000;

// Vertex buckets of more sides than this are sorted with std::sort rather than by insertion,
// whose cost grows with the square of the bucket.
constexpr std::ptrdiff_t kMaxInsertionSort = 32;

bool is_degenerate(const Mesh& mesh, const glm::uvec3& t) {
    if (t.x == t.y || t.y == t.z || t.z == t.x) return true;
    const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
    const double area2 = glm::length(glm::cross(b - a, c - a));
    const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    return !(area2 > kDegenerateAreaRatio * longest * longest);
}

// The table over the faces marked valid.
EdgeTable build_from_valid(const Mesh& mesh, std::vector<uint8_t> face_valid) {
    EdgeTable t;
    const size_t n_faces = mesh.triangles.size();
    const size_t n_vertices = mesh.positions.size();
    t.face_valid = std::move(face_valid);

    // Every corner side (a, b) of a valid face, bucketed by its smaller vertex (a counting sort),
    // in face order within a bucket. Edges are then the distinct larger vertices of each bucket,
    // bucket after bucket: the lexicographic order of (smaller, larger), without sorting all
    // 3F sides at once.
    struct Side {
        uint32_t other;  // the larger vertex
        uint32_t face;
    };
    std::vector<uint32_t> bucket_offsets(n_vertices + 1, 0);
    for (size_t f = 0; f < n_faces; ++f) {
        if (!t.face_valid[f]) continue;
        const glm::uvec3 tri = mesh.triangles[f];
        for (int s = 0; s < 3; ++s) ++bucket_offsets[std::min(tri[s], tri[(s + 1) % 3]) + 1];
    }
    std::partial_sum(bucket_offsets.begin(), bucket_offsets.end(), bucket_offsets.begin());
    std::vector<Side> sides(bucket_offsets.back());
    {
        std::vector<uint32_t> fill(bucket_offsets.begin(), bucket_offsets.end() - 1);
        for (uint32_t f = 0; f < n_faces; ++f) {
            if (!t.face_valid[f]) continue;
            const glm::uvec3 tri = mesh.triangles[f];
            for (uint32_t s = 0; s < 3; ++s) {
                const uint32_t a = tri[int(s)], b = tri[int((s + 1) % 3)];
                sides[fill[std::min(a, b)]++] = {std::max(a, b), f};
            }
        }
    }
    // Within a bucket: by the larger vertex, then the face (already ascending as filled). Most
    // buckets hold a few sides; a vertex shared by very many faces (a fan's apex) gets a real sort.
    size_t n_edges = 0;
    for (size_t v = 0; v < n_vertices; ++v) {
        if (bucket_offsets[v] == bucket_offsets[v + 1]) continue;  // first + 1 would pass the end
        const auto first = sides.begin() + bucket_offsets[v], last = sides.begin() + bucket_offsets[v + 1];
        if (last - first > kMaxInsertionSort) {
            std::sort(first, last, [](const Side& a, const Side& b) {
                return a.other != b.other ? a.other < b.other : a.face < b.face;
            });
        } else {
            for (auto i = first + 1; i < last; ++i) {  // insertion sort, stable
                const Side side = *i;
                auto j = i;
                for (; j > first && (j - 1)->other > side.other; --j) *j = *(j - 1);
                *j = side;
            }
        }
        for (auto i = first; i < last; ++i) n_edges += i == first || i->other != (i - 1)->other;
    }

    t.edge_vertices.reserve(n_edges);
    t.edge_faces.reserve(2 * n_edges);
    t.many_face_offsets.push_back(0);
    for (uint32_t v = 0; v < n_vertices; ++v) {
        for (uint32_t i = bucket_offsets[v]; i < bucket_offsets[v + 1];) {
            const uint32_t other = sides[i].other;
            t.edge_vertices.emplace_back(v, other);
            uint32_t end = i;
            while (end < bucket_offsets[v + 1] && sides[end].other == other) ++end;
            if (end - i <= 2) {
                t.edge_faces.push_back(sides[i].face);
                t.edge_faces.push_back(end - i == 2 ? sides[i + 1].face : kNoIndex);
            } else {
                t.edge_faces.push_back(kNoIndex);
                t.edge_faces.push_back(uint32_t(t.many_face_offsets.size() - 1));
                for (uint32_t k = i; k < end; ++k) t.many_faces.push_back(sides[k].face);
                t.many_face_offsets.push_back(uint32_t(t.many_faces.size()));
            }
            i = end;
        }
    }
    sides = std::vector<Side>();  // (not "= {}": that assigns an empty list and keeps the memory)

    // Vertex -> edges, ascending because edges are visited in ascending order.
    t.vertex_edge_offsets.assign(n_vertices + 1, 0);
    for (const glm::uvec2& e : t.edge_vertices) {
        ++t.vertex_edge_offsets[e.x + 1];
        ++t.vertex_edge_offsets[e.y + 1];
    }
    std::partial_sum(t.vertex_edge_offsets.begin(), t.vertex_edge_offsets.end(),
                     t.vertex_edge_offsets.begin());
    t.vertex_edges.resize(t.vertex_edge_offsets.back());
    std::vector<uint32_t> fill(t.vertex_edge_offsets.begin(), t.vertex_edge_offsets.end() - 1);
    for (uint32_t e = 0; e < t.edge_vertices.size(); ++e) {
        t.vertex_edges[fill[t.edge_vertices[e].x]++] = e;
        t.vertex_edges[fill[t.edge_vertices[e].y]++] = e;
    }
    return t;
}

// A face with the same three vertices as an earlier face shares every edge with it; the later
// copy is marked invalid. Returns how many were found. Only faces sharing an edge are compared.
size_t mark_duplicate_faces(const Mesh& mesh, EdgeTable& r_table) {
    auto sorted = [&](uint32_t f) {
        glm::uvec3 v = mesh.triangles[f];
        if (v.x > v.y) std::swap(v.x, v.y);
        if (v.y > v.z) std::swap(v.y, v.z);
        if (v.x > v.y) std::swap(v.x, v.y);
        return v;
    };
    // Few faces on an edge (almost always two): compare pairwise. Many (a fan of sheets on one
    // edge): sort by vertex set, so the cost stays n log n.
    constexpr size_t kPairwiseFaces = 8;
    size_t duplicates = 0;
    std::vector<std::pair<glm::uvec3, uint32_t>> crowd;
    auto key_less = [](const std::pair<glm::uvec3, uint32_t>& a, const std::pair<glm::uvec3, uint32_t>& b) {
        if (a.first.x != b.first.x) return a.first.x < b.first.x;
        if (a.first.y != b.first.y) return a.first.y < b.first.y;
        if (a.first.z != b.first.z) return a.first.z < b.first.z;
        return a.second < b.second;
    };
    for (uint32_t e = 0; e < r_table.edge_count(); ++e) {
        const auto faces = r_table.faces_of(e);
        if (faces.size() <= kPairwiseFaces) {
            for (size_t i = 1; i < faces.size(); ++i) {
                for (size_t j = 0; j < i; ++j) {
                    if (r_table.face_valid[faces[i]] && r_table.face_valid[faces[j]] && sorted(faces[i]) == sorted(faces[j])) {
                        r_table.face_valid[std::max(faces[i], faces[j])] = 0;
                        ++duplicates;
                    }
                }
            }
            continue;
        }
        crowd.clear();
        for (uint32_t f : faces) {
            if (r_table.face_valid[f]) crowd.emplace_back(sorted(f), f);
        }
        std::sort(crowd.begin(), crowd.end(), key_less);
        for (size_t i = 1; i < crowd.size(); ++i) {
            if (crowd[i].first == crowd[i - 1].first && r_table.face_valid[crowd[i].second]) {
                r_table.face_valid[crowd[i].second] = 0;  // the later face of an equal run
                ++duplicates;
            }
        }
    }
    return duplicates;
}

}  // namespace

void faces_around_corners(const Mesh& mesh, const EdgeTable& table, uint32_t face, std::vector<uint32_t>& r_faces) {
    r_faces.clear();
    for (int c = 0; c < 3; ++c) {
        for (const uint32_t e : table.edges_around(mesh.triangles[face][c])) {
            const std::span<const uint32_t> faces = table.faces_of(e);
            r_faces.insert(r_faces.end(), faces.begin(), faces.end());
        }
    }
    std::sort(r_faces.begin(), r_faces.end());
    r_faces.erase(std::unique(r_faces.begin(), r_faces.end()), r_faces.end());
}

EdgeTable build_edge_table(const Mesh& mesh) {
    const size_t n_faces = mesh.triangles.size();
    std::vector<uint8_t> valid(n_faces);
    internal::parallel_for(n_faces, kMinParallelFaces, [&](size_t begin, size_t end) {
        for (size_t f = begin; f < end; ++f) valid[f] = is_degenerate(mesh, mesh.triangles[f]) ? 0 : 1;
    });
    EdgeTable t = build_from_valid(mesh, std::move(valid));
    const size_t duplicates = mark_duplicate_faces(mesh, t);
    if (duplicates == 0) return t;
    // Rare: build again without the copies, so their edges are not counted twice.
    t = build_from_valid(mesh, std::move(t.face_valid));
    t.duplicate_faces = duplicates;
    return t;
}

namespace {

// A vertex is manifold when its faces form one fan: each joined to the next across an edge of the
// vertex that has exactly two faces. Two cones touching at their tips, or faces meeting at a
// non-manifold edge, make more than one fan. Each face's place among its vertex's faces is
// found by a binary search of them, sorted: n log n at a fan's apex of hundreds of thousands, and
// no table over all faces, so that vertices can be counted on every core.
size_t count_non_manifold_vertices(const EdgeTable& table) {
    const size_t vertices = table.vertex_edge_offsets.empty() ? 0 : table.vertex_edge_offsets.size() - 1;
    std::atomic<size_t> count{0};
    internal::parallel_for(vertices, kMinParallelVertices, [&](size_t begin, size_t end) {
        size_t local = 0;
        std::vector<uint32_t> faces;               // the vertex's faces, ascending
        internal::UnionFind<uint32_t> fans_of(0);  // over indices into `faces`: the faces of one fan form a set
        for (size_t v = begin; v < end; ++v) {
            faces.clear();
            for (uint32_t e : table.edges_around(uint32_t(v))) {
                for (uint32_t f : table.faces_of(e)) faces.push_back(f);
            }
            std::sort(faces.begin(), faces.end());
            faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
            if (faces.size() < 2) continue;
            const auto slot = [&](uint32_t f) {
                return uint32_t(std::lower_bound(faces.begin(), faces.end(), f) - faces.begin());
            };
            fans_of.reset(faces.size());
            size_t fans = faces.size();
            for (uint32_t e : table.edges_around(uint32_t(v))) {
                if (!table.is_interior(e)) continue;
                const auto pair = table.faces_of(e);
                if (fans_of.unite(slot(pair[0]), slot(pair[1]))) --fans;
            }
            if (fans > 1) ++local;
        }
        count += local;
    });
    return count;
}

}  // namespace

uint32_t find_edge(const EdgeTable& table, uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    if (size_t(a) + 1 >= table.vertex_edge_offsets.size()) return kNoIndex;
    // The edges around a vertex are ascending, and edge order is the order of (v0, v1): a binary
    // search, so that a fan's apex with very many edges costs log of them.
    const auto around = table.edges_around(a);
    const glm::uvec2 key(a, b);
    const auto it = std::lower_bound(around.begin(), around.end(), key, [&](uint32_t e, const glm::uvec2& k) {
        const glm::uvec2 v = table.edge_vertices[e];
        return v.x != k.x ? v.x < k.x : v.y < k.y;
    });
    return it != around.end() && table.edge_vertices[*it] == key ? *it : kNoIndex;
}

std::vector<glm::uvec3> face_edges(const Mesh& mesh, const EdgeTable& table) {
    std::vector<glm::uvec3> out(mesh.triangles.size(), glm::uvec3(kNoIndex));
    for (size_t f = 0; f < out.size(); ++f) {
        if (!table.face_valid[f]) continue;
        const glm::uvec3 t = mesh.triangles[f];
        out[f] = {find_edge(table, t.x, t.y), find_edge(table, t.y, t.z), find_edge(table, t.z, t.x)};
    }
    return out;
}

MeshReport describe_mesh(const Mesh& mesh, const EdgeTable& table, MeshReportScope scope) {
    MeshReport r;
    r.vertices = mesh.positions.size();
    r.faces = mesh.triangles.size();
    r.edges = table.edge_count();
    r.duplicate_faces = table.duplicate_faces;
    r.degenerate_faces = size_t(std::count(table.face_valid.begin(), table.face_valid.end(), 0)) - r.duplicate_faces;

    // Consistent neighbours traverse their shared edge in opposite directions.
    auto inconsistent = [&](uint32_t e) {
        const auto faces = table.faces_of(e);
        const uint32_t v0 = table.edge_vertices[e].x;
        auto runs_forward = [&](uint32_t f) {
            const glm::uvec3 tri = mesh.triangles[f];
            for (int s = 0; s < 3; ++s) {
                if (tri[s] == v0) return tri[(s + 1) % 3] == table.edge_vertices[e].y;
            }
            return false;
        };
        return runs_forward(faces[0]) == runs_forward(faces[1]);
    };
    std::atomic<size_t> boundary{0}, non_manifold{0}, inconsistent_edges{0};
    internal::parallel_for(table.edge_count(), kMinParallelEdges, [&](size_t begin, size_t end) {
        size_t b = 0, n = 0, i = 0;
        for (size_t e = begin; e < end; ++e) {
            const size_t faces = table.faces_of(uint32_t(e)).size();
            b += faces == 1;
            n += faces >= 3;
            i += faces == 2 && inconsistent(uint32_t(e));
        }
        boundary += b;
        non_manifold += n;
        inconsistent_edges += i;
    });
    r.boundary_edges = boundary;
    r.non_manifold_edges = non_manifold;
    r.inconsistent_edges = inconsistent_edges;
    if (scope == MeshReportScope::kAll) {
        internal::UnionFind<uint32_t> components(r.faces);
        for (uint32_t e = 0; e < table.edge_count(); ++e) {
            const auto faces = table.faces_of(e);
            for (size_t i = 1; i < faces.size(); ++i) components.unite(faces[0], faces[i]);
        }
        for (uint32_t f = 0; f < r.faces; ++f) {
            if (table.face_valid[f] && components.is_root(f)) ++r.connected_components;
        }
    }
    r.non_manifold_vertices = count_non_manifold_vertices(table);
    return r;
}

std::vector<std::string> mesh_warnings(const MeshReport& r) {
    std::vector<std::string> out;
    if (r.degenerate_faces > 0)
        out.push_back(std::to_string(r.degenerate_faces) + " degenerate face(s) ignored");
    if (r.duplicate_faces > 0)
        out.push_back(std::to_string(r.duplicate_faces) + " duplicate face(s) ignored");
    if (r.non_manifold_edges > 0)
        out.push_back(std::to_string(r.non_manifold_edges) +
                      " non-manifold edge(s), drawn as boundary lines");
    if (r.non_manifold_vertices > 0)
        out.push_back(std::to_string(r.non_manifold_vertices) +
                      " non-manifold vertex(es) where separate sheets touch; lines drawn as usual");
    if (r.inconsistent_edges > 0)
        out.push_back(std::to_string(r.inconsistent_edges) +
                      " edge(s) between faces of inconsistent orientation; silhouettes there "
                      "may be wrong");
    return out;
}

}  // namespace inkline::core
