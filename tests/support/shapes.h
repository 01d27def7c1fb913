// SPDX-License-Identifier: MIT
// Analytic test meshes with known silhouettes and boundaries. All are outward-facing, CCW.
#pragma once

#include "core/mesh/mesh.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace inkline::test {

// UV sphere centred at the origin, poles on +-y, closed with triangle fans at the poles.
core::Mesh uv_sphere(int segments, int rings, double radius);
// Upper half (y >= 0) of a UV sphere: open, its boundary is the equator loop.
core::Mesh hemisphere(int segments, int rings, double radius);
// Torus around the y axis: major radius R, minor radius r.
core::Mesh torus(double major_radius, double minor_radius, int major_segments, int minor_segments);
// Axis-aligned cube [-h, h]^3, two triangles per face.
core::Mesh cube(double half_size);
// Unit icosphere: an icosahedron split `levels` times into four (20 * 4^levels faces), every
// vertex on the unit sphere. Vertex indices scatter over the surface as subdivision adds them.
core::Mesh icosphere(int levels);
// What bumpy_sphere raises on a unit sphere: `count` Gaussian bumps spread evenly over it (a
// Fibonacci lattice), each with a height and a width drawn uniformly from their ranges, seeded.
struct Bumps {
    int count = 40;
    uint32_t seed = 1;
    double height_min = 0.02, height_max = 0.08;
    double width_min = 0.08, width_max = 0.25;
    double jitter = 0.0;  // each vertex's radius then moves by up to this much, at random
};
// A unit sphere mesh (every vertex on it, as icosphere gives) pushed out by bumps.
core::Mesh bumpy_sphere(core::Mesh unit_sphere, const Bumps& bumps);
// Torus around y (major radius 1, tube radius 0.35) whose tube radius is modulated by two waves of
// relative amplitudes `wave` (sin 7u sin 3v) and `ripple` (sin(23u + 5v)): folds and
// self-occlusion everywhere. Faces in grid order, two per quad.
core::Mesh wavy_torus(int major_segments, int minor_segments, double wave, double ripple);
// The frames of a deforming sequence: the torus (1, 0.35, 96 x 32) whose tube swells and twists
// over time, frame i at time 0.25 i; same topology, new positions each frame.
std::vector<core::Mesh> swelling_torus(int frames);
// Worst cases for anything quadratic in vertex valence or line count:
// A closed cone of `sides` sides: apex 0 above, base centre 1, the ring 2.. sides+1 on the unit
// circle in y = 0; every side face has the apex and every base face the centre (2 * sides faces).
core::Mesh closed_cone(uint32_t sides);
// Two closed cones touching apex to apex: closed_cone(sides) and its mirror through the apex
// (y -> 2 - y, faces turned to face out), sharing vertex 0: one non-manifold vertex.
core::Mesh twin_cones(uint32_t sides);
// A flat disc in y = 0 of `sides` faces, all around its centre (vertex 0), as a CAD export's cap.
core::Mesh disc_cap(uint32_t sides);
// One convex polygon of `corners` corners on the unit circle in y = 0, fan-triangulated from
// corner 0 as a reader splits it (corners - 2 faces).
core::Mesh fan_polygon(uint32_t corners);
// An n x n heightfield over [-1, 1]^2 in x and z with random heights in [0, amplitude) (seeded):
// terrain or a noisy scan, whose silhouettes break into tens of thousands of short strokes.
core::Mesh noise_terrain(uint32_t n, double amplitude);

// Flat n x n quad grid in the z = 0 plane spanning [-h, h]^2, normals towards +z.
core::Mesh grid(int n, double half_size);

// `b` moved by `offset`, appended to `a`: one mesh of two objects.
core::Mesh combine(core::Mesh a, const core::Mesh& b, const glm::vec3& offset);

}  // namespace inkline::test
