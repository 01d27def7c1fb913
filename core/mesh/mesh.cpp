// SPDX-License-Identifier: MIT
#include "core/mesh/mesh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace inkline::core {

void Bounds::add(const glm::dvec3& p) {
    if (!valid) {
        min = max = p;
        valid = true;
        return;
    }
    min = glm::min(min, p);
    max = glm::max(max, p);
}

double Bounds::radius() const { return valid ? 0.5 * glm::length(max - min) : 0.0; }

Bounds bounds_of(const std::vector<glm::vec3>& positions) {
    Bounds b;
    if (positions.empty()) return b;
    // The least and greatest floats, widened once: the same bounds as widening every point.
    glm::vec3 lo = positions[0], hi = positions[0];
    for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    b.add(glm::dvec3(lo));
    b.add(glm::dvec3(hi));
    return b;
}

Bounds transformed(const Bounds& b, const glm::dmat4& transform) {
    Bounds out;
    if (!b.valid) return out;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
        out.add(glm::dvec3(transform * glm::dvec4(corner, 1.0)));
    }
    return out;
}

glm::dvec3 face_normal(const std::vector<glm::vec3>& positions, const glm::uvec3& tri) {
    const glm::dvec3 a(positions[tri.x]);
    const glm::dvec3 b(positions[tri.y]);
    const glm::dvec3 c(positions[tri.z]);
    return glm::cross(b - a, c - a);
}

std::vector<glm::dvec3> vertex_normals(const Mesh& mesh) {
    std::vector<glm::dvec3> normals(mesh.positions.size(), glm::dvec3(0.0));
    // The unnormalised face normal is twice the area times the unit normal: area weighting.
    for (const glm::uvec3& tri : mesh.triangles) {
        if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) continue;
        const glm::dvec3 n = face_normal(mesh.positions, tri);
        for (int c = 0; c < 3; ++c) normals[tri[c]] += n;
    }
    for (glm::dvec3& n : normals) {
        const double len = glm::length(n);
        n = len > 0.0 ? n / len : glm::dvec3(0.0);
    }
    return normals;
}

}  // namespace inkline::core
