// SPDX-License-Identifier: MIT
// Fans: the faces around a vertex of very high valence (a cone's apex, a disc cap's centre, the
// first corner of a fan-triangulated polygon), indexed so that a query segment finds the few
// faces it can meet in O(log N). An axis-aligned BVH cannot: the boxes of long slivers that
// share one vertex all overlap near it, so a ray there visits a share of all N.
//
// Past the fan's box, two tests, each necessary for a segment to meet face T = (A, B, C) of the
// fan around apex A:
//  - Rim: if the segment does not pass through A, the plane through A and the segment's line
//    separates or touches B and C (the hit point is a mix of A, B and C with weight on B or C,
//    and lies in that plane). In ring order the corners B - A, C - A run along the fan's rim,
//    which a plane through the apex crosses about twice (a cone's or a disc's rim), so of a
//    balanced box hierarchy over consecutive runs of the rim O(log N) boxes are crossed.
//  - Tilt: if the line passes at distance h from A and the segment stays r >= h away from it,
//    a hit point H has |H - A| >= r and the line meets T's plane at an angle whose sine is at
//    most h / r. The rim test keeps everything for a line through or almost through the apex
//    (a query at the apex itself); this one then keeps only the faces whose planes nearly hold
//    the line: the box hierarchy bounds the faces' unit normals too.
#pragma once

#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace inkline::core::internal {

// A vertex gets a fan when at least this many of its faces are fan faces: faces whose two edges
// at the vertex have at most two faces each (an umbrella, whole or in parts). Sheets around one
// non-manifold edge are not a fan: they all hold that edge, so the rim test would keep half of
// them. Below this many faces the BVH's overlap costs less than a second structure.
inline constexpr size_t kMinFanFaces = 64;

// Both tests keep what lies within this much slack, relative to the sizes involved (|d| (|p - A|
// + |x|) |x| for n . x in the rim test, the lengths of the segment and the fan for distances,
// 1 for sines). Double rounding in the tests, and the distance by which a triangle test in
// double may count a segment that misses a face as meeting it, stay near 1e-15 of those sizes,
// so no face the segment meets, or is counted as meeting, is passed over.
inline constexpr double kFanSlack = 1e-12;

class FanIndex {
  public:
    // No fans.
    FanIndex() = default;
    // Finds the fans among the valid faces of the mesh; positions are taken times `scale`, a
    // power of two (the frame the faces are tested in). A face goes to at most one fan, that of
    // its apex with the most fan faces.
    FanIndex(const Mesh& mesh, const EdgeTable& table, double scale);

    bool empty() const { return fans_.empty(); }
    size_t fan_count() const { return fans_.size(); }
    // Per mesh face, 1 when it belongs to a fan; empty when there are no fans.
    const std::vector<uint8_t>& in_fan() const { return in_fan_; }
    // The apex of a fan (mesh vertex) and its faces (mesh faces, in ring order).
    uint32_t apex(uint32_t fan) const { return vertex_of_[fans_[fan].apex]; }
    std::vector<uint32_t> faces(uint32_t fan) const;
    // Bounds of a fan's faces, in the scaled frame.
    Bounds bounds(uint32_t fan) const { return fans_[fan].bounds; }

    // Moves the fans to `mesh`'s positions times `scale` (same topology): the ring order stays,
    // the boxes are fitted again.
    void update_positions(const Mesh& mesh, double scale);

    // Calls visit(face, a, b, c) for the faces of `fan` that the segment point + t direction,
    // t0 <= t <= t1 (scaled frame), may meet, a superset of those it meets, with the face's
    // corners in the scaled frame (a the apex), until visit returns true; returns whether it did.
    template <class Visit>
    bool find_face(uint32_t fan, const glm::dvec3& point, const glm::dvec3& direction, double t0, double t1,
                   Visit&& visit) const;

  private:
    // Centre plus or minus half[i] along the orthonormal axes[i]. The first axis runs along the
    // chord of the run of points bounded, the second towards its middle, so a run of a smooth
    // curve (a cone's rim, its faces' normals) lies in a box as thin as the arc's sagitta: a
    // plane that touches the curve then crosses O(1) boxes a level, where axis-aligned boxes,
    // as thick as they are long, cross O(sqrt N) near the point of contact. (The rim plane of a
    // ray from a cone's silhouette is such a plane: it touches the cone along the silhouette.)
    struct Box {
        glm::dvec3 center{0.0};
        glm::dvec3 axes[3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
        glm::dvec3 half{0.0};

        // Whether the box meets the slab low <= dot(v, x) <= high.
        bool meets(const glm::dvec3& v, double low, double high) const {
            const double middle = glm::dot(v, center);
            const double spread = std::abs(glm::dot(v, axes[0])) * half.x + std::abs(glm::dot(v, axes[1])) * half.y +
                                  std::abs(glm::dot(v, axes[2])) * half.z;
            return middle - spread <= high && middle + spread >= low;
        }
        // An upper bound of |x|_1 over the box (|axes[i]|_1 <= sqrt 3).
        double size() const {
            return std::abs(center.x) + std::abs(center.y) + std::abs(center.z) + 2.0 * (half.x + half.y + half.z);
        }
    };
    // Over the faces [begin, end): the rim points relative to the apex, and the unit normals
    // (with their rounding). An inner node's children are the next node and `right`.
    struct Node {
        Box rim;
        Box normals;
        uint32_t begin = 0, end = 0;
        uint32_t right = 0;  // 0 for a leaf
    };
    struct Fan {
        uint32_t apex = 0;               // index into positions_
        uint32_t root = 0;               // its box hierarchy in nodes_
        uint32_t first = 0, end = 0;     // its faces in faces_, rims_, normals_
        double radius = 0.0;             // largest |B - A|_1 of its rim points
        glm::dvec3 low{0.0}, high{0.0};  // bounds of its faces relative to the apex
        Bounds bounds;
    };

    uint32_t build_nodes(uint32_t begin, uint32_t end);
    void fit(uint32_t fan);
    void fit_node(uint32_t node, const glm::dvec3& apex, std::vector<glm::dvec3>& r_scratch);

    std::vector<Fan> fans_;
    std::vector<Node> nodes_;
    std::vector<uint32_t> faces_;        // mesh face of each fan face, fan by fan in ring order
    std::vector<glm::uvec2> rims_;       // its two corners other than the apex (into positions_)
    std::vector<glm::dvec3> normals_;    // its unit normal, in its corners' turning order
    std::vector<double> normal_errors_;  // a bound on that normal's rounding (2: unknown)
    std::vector<glm::dvec3> positions_;  // the fans' vertices, scaled frame
    std::vector<uint32_t> vertex_of_;    // mesh vertex of each of positions_
    std::vector<uint8_t> in_fan_;
};

template <class Visit>
bool FanIndex::find_face(uint32_t fan_id, const glm::dvec3& point, const glm::dvec3& direction, double t0, double t1,
                         Visit&& visit) const {
    const auto l1 = [](const glm::dvec3& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); };
    const Fan& fan = fans_[fan_id];
    const glm::dvec3 apex = positions_[fan.apex];
    const glm::dvec3 from_apex = point - apex;
    // Rounding in the tests below, and in the triangle test, stays far within this distance.
    const double reach = l1(from_apex);
    const double position_slack =
        kFanSlack * (reach + fan.radius + l1(direction) * std::max(std::abs(t0), std::abs(t1)));

    // The fan's box first (Embree calls a lone user primitive without testing its bounds): a
    // segment leaving a flat fan's plane, as from any point of a fan-triangulated polygon, ends
    // here. Relative to the apex, as every test here, so rounding scales with the fan.
    double t_enter = t0, t_leave = t1;
    for (int k = 0; k < 3; ++k) {
        const double low = fan.low[k] - position_slack - from_apex[k];
        const double high = fan.high[k] + position_slack - from_apex[k];
        if (direction[k] == 0.0) {
            if (low > 0.0 || high < 0.0) return false;
            continue;
        }
        const double t_low = low / direction[k], t_high = high / direction[k];
        t_enter = std::max(t_enter, std::min(t_low, t_high));
        t_leave = std::min(t_leave, std::max(t_low, t_high));
    }
    if (t_enter > t_leave) return false;

    // Rim test: the plane through the apex and the line.
    const glm::dvec3 normal = glm::cross(from_apex, direction);
    const double slack = kFanSlack * l1(direction);
    const auto rim_tolerance = [&](double size) { return slack * (reach + size) * size; };
    // Tilt test: the largest sine between the line and a face plane it can meet within the
    // fan's box; above 1 (a segment through or close by the apex) it keeps everything.
    const double length = glm::length(direction);
    double tilt = std::numeric_limits<double>::infinity();
    glm::dvec3 along(0.0);
    if (length > 0.0) {
        along = direction / length;
        const double t_closest = std::clamp(-glm::dot(from_apex, direction) / (length * length), t_enter, t_leave);
        const double apex_distance = glm::length(from_apex + direction * t_closest);
        const double line_distance = glm::length(normal) / length;
        if (apex_distance > 2.0 * position_slack) {
            tilt = (line_distance + position_slack) / (apex_distance - position_slack) + kFanSlack;
        }
    }
    const bool tilted = tilt < 1.0;

    // Balanced: depth at most 32 for 2^32 faces, one pending node per level.
    uint32_t stack[64];
    int top = 0;
    stack[top++] = fan.root;
    while (top > 0) {
        const uint32_t index = stack[--top];
        const Node& node = nodes_[index];
        const double tolerance = rim_tolerance(node.rim.size());
        if (!node.rim.meets(normal, -tolerance, tolerance)) continue;
        if (tilted && !node.normals.meets(along, -tilt, tilt)) continue;
        if (node.right != 0) {
            stack[top++] = node.right;
            stack[top++] = index + 1;
            continue;
        }
        for (uint32_t i = node.begin; i < node.end; ++i) {
            const glm::dvec3& b = positions_[rims_[i].x];
            const glm::dvec3& c = positions_[rims_[i].y];
            const glm::dvec3 to_b = b - apex, to_c = c - apex;
            const double side_b = glm::dot(normal, to_b), side_c = glm::dot(normal, to_c);
            const double face_tolerance = rim_tolerance(std::max(l1(to_b), l1(to_c)));
            if ((side_b > face_tolerance && side_c > face_tolerance) ||
                (side_b < -face_tolerance && side_c < -face_tolerance)) {
                continue;
            }
            if (tilted && std::abs(glm::dot(normals_[i], along)) > tilt + normal_errors_[i]) continue;
            if (visit(faces_[i], apex, b, c)) return true;
        }
    }
    return false;
}

}  // namespace inkline::core::internal
