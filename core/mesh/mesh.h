// SPDX-License-Identifier: MIT
// A triangle mesh as plain arrays: positions in object space and counter-clockwise triangles.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace inkline::core {

// Coordinates beyond this magnitude are refused, from every reader and every glTF frame: their
// squares still fit a double comfortably, and no real scene needs them (float meshes lose all
// precision long before).
inline constexpr double kMaxCoordinate = 1e18;

struct Mesh {
    std::vector<glm::vec3> positions;   // #V, object space
    std::vector<glm::uvec3> triangles;  // #F, counter-clockwise vertex indices
};

// Axis-aligned bounds of a set of points; not valid when there are none.
struct Bounds {
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
    bool valid = false;

    void add(const glm::dvec3& p);
    glm::dvec3 center() const { return (min + max) * 0.5; }
    double radius() const;  // half the diagonal
};

Bounds bounds_of(const std::vector<glm::vec3>& positions);

// Bounds of a box's eight corners under a transform: they hold every point of the box moved by
// it (what a camera fits its near and far planes to, from a mesh's object-space bounds).
Bounds transformed(const Bounds& b, const glm::dmat4& transform);

// Unnormalised face normal (cross product of two edges), in double precision.
glm::dvec3 face_normal(const std::vector<glm::vec3>& positions, const glm::uvec3& tri);

// Area-weighted vertex normals, object space, unit length (zero where a vertex has no face of
// three distinct corners): the smooth surface's normals, which the brush's light and smooth
// contours follow.
std::vector<glm::dvec3> vertex_normals(const Mesh& mesh);

}  // namespace inkline::core
