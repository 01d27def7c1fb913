// SPDX-License-Identifier: MIT
#include "tests/support/shapes.h"

#include "core/mesh/topology.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace inkline::test {
namespace {

using core::Mesh;

// A UV sphere of `rings` latitude bands from the north pole; `full` closes it at the south
// pole, otherwise it stops open at the equator.
Mesh uv_cap(int segments, int rings, double radius, bool full) {
    Mesh m;
    const double pi = std::numbers::pi;
    m.positions.emplace_back(0.0f, float(radius), 0.0f);  // north pole
    const int inner_rings = full ? rings - 1 : rings / 2;  // vertex rings besides the poles
    for (int i = 1; i <= inner_rings; ++i) {
        const double theta = pi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2.0 * pi * j / segments;
            m.positions.emplace_back(float(radius * std::sin(theta) * std::cos(phi)),
                                     float(radius * std::cos(theta)),
                                     float(-radius * std::sin(theta) * std::sin(phi)));
        }
    }
    auto ring = [&](int i, int j) { return unsigned(1 + (i - 1) * segments + (j % segments)); };
    for (int j = 0; j < segments; ++j) m.triangles.emplace_back(0u, ring(1, j), ring(1, j + 1));
    for (int i = 1; i < inner_rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            m.triangles.emplace_back(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
            m.triangles.emplace_back(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
        }
    }
    if (full) {
        const unsigned south = unsigned(m.positions.size());
        m.positions.emplace_back(0.0f, float(-radius), 0.0f);
        for (int j = 0; j < segments; ++j) m.triangles.emplace_back(ring(inner_rings, j), south, ring(inner_rings, j + 1));
    }
    return m;
}

// Torus around y: tube radius tube_radius(u, v) at major angle u and tube angle v, faces in grid
// order, two per quad, counter-clockwise seen from outside.
template <typename TubeRadius>
Mesh torus_grid(double major_radius, int major_segments, int minor_segments, TubeRadius tube_radius) {
    Mesh m;
    const double pi = std::numbers::pi;
    for (int i = 0; i < major_segments; ++i) {
        const double u = 2.0 * pi * i / major_segments;
        for (int j = 0; j < minor_segments; ++j) {
            const double v = 2.0 * pi * j / minor_segments;
            const double r = tube_radius(u, v);
            const double rho = major_radius + r * std::cos(v);
            m.positions.emplace_back(float(rho * std::cos(u)), float(r * std::sin(v)), float(-rho * std::sin(u)));
        }
    }
    auto at = [&](int i, int j) { return unsigned((i % major_segments) * minor_segments + (j % minor_segments)); };
    for (int i = 0; i < major_segments; ++i) {
        for (int j = 0; j < minor_segments; ++j) {
            m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return m;
}

}  // namespace

Mesh uv_sphere(int segments, int rings, double radius) { return uv_cap(segments, rings, radius, true); }

Mesh hemisphere(int segments, int rings, double radius) { return uv_cap(segments, rings, radius, false); }

Mesh torus(double major_radius, double minor_radius, int major_segments, int minor_segments) {
    return torus_grid(major_radius, major_segments, minor_segments, [&](double, double) { return minor_radius; });
}

Mesh cube(double h) {
    Mesh m;
    const float s = float(h);
    for (int i = 0; i < 8; ++i) m.positions.emplace_back((i & 1) ? s : -s, (i & 2) ? s : -s, (i & 4) ? s : -s);
    // Each quad listed counter-clockwise seen from outside.
    const unsigned quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.triangles.emplace_back(q[0], q[1], q[2]);
        m.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

Mesh grid(int n, double h) {
    Mesh m;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            m.positions.emplace_back(float(-h + 2.0 * h * j / n), float(-h + 2.0 * h * i / n), 0.0f);
        }
    }
    auto at = [&](int i, int j) { return unsigned(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            m.triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
            m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
        }
    }
    return m;
}

Mesh icosphere(int levels) {
    const float t = float((1.0 + std::sqrt(5.0)) / 2.0);
    Mesh m;
    m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                   {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (glm::vec3& p : m.positions) p = glm::normalize(p);
    for (int level = 0; level < levels; ++level) {
        // One new vertex per edge; each face (a, b, c) becomes four.
        const core::EdgeTable table = core::build_edge_table(m);
        const std::vector<glm::uvec3> edges_of = core::face_edges(m, table);
        const auto base = uint32_t(m.positions.size());
        for (const glm::uvec2& e : table.edge_vertices) {
            m.positions.push_back(glm::normalize(m.positions[e.x] + m.positions[e.y]));
        }
        std::vector<glm::uvec3> split;
        split.reserve(4 * m.triangles.size());
        for (size_t f = 0; f < m.triangles.size(); ++f) {
            const glm::uvec3 c = m.triangles[f];
            const glm::uvec3 mid = edges_of[f] + glm::uvec3(base);  // (ab, bc, ca)
            split.emplace_back(c.x, mid.x, mid.z);
            split.emplace_back(mid.x, c.y, mid.y);
            split.emplace_back(mid.z, mid.y, c.z);
            split.emplace_back(mid.x, mid.y, mid.z);
        }
        m.triangles = std::move(split);
    }
    return m;
}

Mesh bumpy_sphere(Mesh m, const Bumps& b) {
    std::mt19937 rng(b.seed);
    std::uniform_real_distribution<double> height(b.height_min, b.height_max), width(b.width_min, b.width_max);
    struct Bump {
        glm::dvec3 centre;
        double height, inv_width2;
    };
    std::vector<Bump> bumps;
    for (int k = 0; k < b.count; ++k) {
        const double y = 1.0 - 2.0 * (k + 0.5) / b.count;
        const double phi = k * std::numbers::pi * (3.0 - std::sqrt(5.0));
        const double rho = std::sqrt(1.0 - y * y);
        const double w = width(rng);
        bumps.push_back({{rho * std::cos(phi), y, rho * std::sin(phi)}, height(rng), 1.0 / (w * w)});
    }
    std::uniform_real_distribution<double> jitter(-b.jitter, b.jitter);
    for (glm::vec3& p : m.positions) {
        const glm::dvec3 dir = glm::normalize(glm::dvec3(p));
        double r = 1.0 + (b.jitter > 0.0 ? jitter(rng) : 0.0);
        for (const Bump& bump : bumps) {
            r += bump.height * std::exp(-2.0 * (1.0 - glm::dot(dir, bump.centre)) * bump.inv_width2);
        }
        p = glm::vec3(dir * r);
    }
    return m;
}

std::vector<Mesh> swelling_torus(int frames) {
    const Mesh rest = torus(1.0, 0.35, 96, 32);
    std::vector<Mesh> out;
    for (int i = 0; i < frames; ++i) {
        Mesh m = rest;
        const double t = 0.25 * i;
        for (glm::vec3& p : m.positions) {
            const double u = std::atan2(double(p.z), double(p.x));
            const double wave = 1.0 + 0.25 * std::sin(3.0 * u + t);
            const double lift = 0.3 * std::sin(2.0 * u - 0.5 * t);
            p = glm::vec3(float(p.x * (0.9 + 0.1 * wave)), float(p.y * wave + lift), float(p.z));
        }
        out.push_back(std::move(m));
    }
    return out;
}

Mesh wavy_torus(int major_segments, int minor_segments, double wave, double ripple) {
    return torus_grid(1.0, major_segments, minor_segments, [&](double u, double v) {
        return 0.35 * (1.0 + wave * std::sin(7.0 * u) * std::sin(3.0 * v) + ripple * std::sin(23.0 * u + 5.0 * v));
    });
}

core::Mesh closed_cone(uint32_t sides) {
    core::Mesh m;
    m.positions = {{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    for (uint32_t i = 0; i < sides; ++i) {
        const double a = 2.0 * std::numbers::pi * double(i) / sides;
        m.positions.push_back({float(std::cos(a)), 0.0f, float(std::sin(a))});
    }
    for (uint32_t i = 0; i < sides; ++i) {
        const uint32_t a = 2 + i, b = 2 + (i + 1) % sides;
        m.triangles.push_back({0, b, a});
        m.triangles.push_back({1, a, b});
    }
    return m;
}

core::Mesh twin_cones(uint32_t sides) {
    core::Mesh two = closed_cone(sides);
    const auto n = uint32_t(two.positions.size());
    for (uint32_t v = 1; v < n; ++v) two.positions.push_back({two.positions[v].x, 2.0f - two.positions[v].y, two.positions[v].z});
    const size_t faces = two.triangles.size();
    for (size_t f = 0; f < faces; ++f) {
        glm::uvec3 t = two.triangles[f];
        for (int c = 0; c < 3; ++c) t[c] = t[c] == 0 ? 0 : t[c] + n - 1;
        two.triangles.push_back({t.x, t.z, t.y});  // mirrored: turned to face out again
    }
    return two;
}

core::Mesh disc_cap(uint32_t sides) {
    core::Mesh m;
    m.positions = {{0.0f, 0.0f, 0.0f}};
    for (uint32_t i = 0; i < sides; ++i) {
        const double a = 2.0 * std::numbers::pi * double(i) / sides;
        m.positions.push_back({float(std::cos(a)), 0.0f, float(std::sin(a))});
    }
    for (uint32_t i = 0; i < sides; ++i) m.triangles.push_back({0, 1 + (i + 1) % sides, 1 + i});
    return m;
}

core::Mesh fan_polygon(uint32_t corners) {
    core::Mesh m;
    for (uint32_t i = 0; i < corners; ++i) {
        const double a = 2.0 * std::numbers::pi * double(i) / corners;
        m.positions.push_back({float(std::cos(a)), 0.0f, float(std::sin(a))});
    }
    for (uint32_t i = 1; i + 1 < corners; ++i) m.triangles.push_back({0, i, i + 1});
    return m;
}

core::Mesh noise_terrain(uint32_t n, double amplitude) {
    core::Mesh m;
    uint32_t seed = 1;
    for (uint32_t j = 0; j <= n; ++j) {
        for (uint32_t i = 0; i <= n; ++i) {
            seed = seed * 1664525u + 1013904223u;
            const double h = amplitude * double(seed >> 8) / double(1u << 24);
            m.positions.push_back({float(2.0 * i / n - 1.0), float(h), float(2.0 * j / n - 1.0)});
        }
    }
    for (uint32_t j = 0; j < n; ++j) {
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            m.triangles.push_back({a, c, b});
            m.triangles.push_back({b, c, d});
        }
    }
    return m;
}

core::Mesh combine(core::Mesh a, const core::Mesh& b, const glm::vec3& offset) {
    const uint32_t base = uint32_t(a.positions.size());
    for (const glm::vec3& p : b.positions) a.positions.push_back(p + offset);
    for (const glm::uvec3& t : b.triangles) a.triangles.push_back(t + glm::uvec3(base));
    return a;
}

}  // namespace inkline::test
