// SPDX-License-Identifier: MIT
// The normals whose light tone reads at a face's corners: one per vertex (vertex_normals), or one
// per group of corners (SmoothPieces, core/lines/smooth_pieces.h), so that a crease shades each
// side as its own piece: a box's faces flat, a cylinder's side round and its cap flat.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

struct ToneNormals {
    std::span<const glm::dvec3> normals;      // per vertex, or per group: unit, or zero for none
    std::span<const glm::uvec3> face_groups;  // per face, the group of each corner; empty: per vertex
    std::span<const uint32_t> group_vertex;   // per group, its vertex

    ToneNormals() = default;
    // One per vertex.
    ToneNormals(std::span<const glm::dvec3> vertex_normals) : normals(vertex_normals) {}  // NOLINT: implicit
    ToneNormals(const std::vector<glm::dvec3>& vertex_normals) : normals(vertex_normals) {}  // NOLINT: implicit
    ToneNormals(std::span<const glm::dvec3> group_normals, std::span<const glm::uvec3> groups,
                std::span<const uint32_t> vertices)
        : normals(group_normals), face_groups(groups), group_vertex(vertices) {}

    // The normals at the corners of face f (triangle t): their indices in `normals`.
    glm::uvec3 corners(uint32_t face, const glm::uvec3& t) const { return face_groups.empty() ? t : face_groups[face]; }
    // The normal of face f (triangle t) at its vertex v.
    uint32_t at_vertex(uint32_t face, const glm::uvec3& t, uint32_t v) const {
        const glm::uvec3 c = corners(face, t);
        return t.x == v ? c.x : t.y == v ? c.y : c.z;
    }
    // The vertex whose position a normal is at.
    uint32_t vertex(size_t normal) const { return group_vertex.empty() ? uint32_t(normal) : group_vertex[normal]; }
    size_t size() const { return normals.size(); }
};

}  // namespace inkline::core
