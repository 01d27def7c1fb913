// SPDX-License-Identifier: MIT
// The smooth pieces that creases cut a surface into. A vertex's corners whose faces join across
// edges of two faces that are no crease (is_crease at the given angle) form a group, with one
// normal: its faces' area-weighted normals summed. A vertex inside a smooth piece has one group,
// and its normal is the vertex normal (vertex_normals); a vertex on a crease has one per piece
// around it, so that a box's faces are flat and a cylinder's cap meets its side at a sharp edge.
// Smooth contours read g at the groups (core/lines/smooth_contours.h), and tone its light
// (core/tone/tone_normals.h).
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

struct SmoothPieces {
    std::vector<glm::uvec3> face_groups;  // per face, the group of each corner
    std::vector<uint32_t> group_vertex;   // per group, its vertex
    std::vector<glm::dvec3> normals;      // per group: unit, or zero where its faces' normals cancel
    std::vector<uint8_t> joined;          // per face: bit k when side k joins it to the face across
};

// The groups of a mesh's corners, numbered in order of their first corner, and their normals at
// the mesh's positions; `face_edges` as face_edges(mesh, table) gives them. Invalid faces join no
// face and add no normal. Fills r_pieces, keeping its buffers.
void smooth_pieces(const Mesh& mesh, const EdgeTable& table, std::span<const glm::uvec3> face_edges,
                   double crease_angle_deg, SmoothPieces& r_pieces);

}  // namespace inkline::core
