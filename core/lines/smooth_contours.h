// SPDX-License-Identifier: MIT
// Smooth contours: the contour of the smooth surface that the mesh's vertex normals describe,
// instead of the zig-zag of mesh edges between front and back faces.
//
// g(p) = n(p) . (p - eye) is evaluated at every vertex with the area-weighted vertex normal and
// taken as linear over each face (Hertzmann and Zorin, "Illustrating smooth surfaces", SIGGRAPH
// 2000); for an orthographic camera, p - eye is the view direction (-eye.toward(p), Viewpoint in
// core/scene/camera.h). A vertex faces away from the eye where g > 0 and towards it where
// g <= 0. The contour crosses each edge whose two vertices differ, at the point where g
// interpolated along the edge is zero, and each face with two such edges as one straight
// segment. Segments through shared edges chain into closed loops, or into open curves that end
// on an edge of one face (a boundary) or of three and more (non-manifold).
//
// Creases split the surface into smooth pieces: a vertex on a crease has a normal per piece (its
// corners whose faces join without crossing a crease edge), and the contour of each piece ends
// on the crease edges around it.
//
// Along a crease the outline passes from one piece to the other: where the pieces on its two
// sides face opposite ways (g interpolated along the crease edge from each side's corners, as on
// their faces), the crease edge is part of the outline, as a crease edge between a front and a
// back face is a silhouette in mesh mode. Those stretches are traced too, as silhouette chains
// that end exactly where the pieces' contours end on the crease, so that the stroke stage links
// them into one outline; cut_crease_outline takes them out of the crease lines.
//
// Incremental tracing tests only the faces that a hierarchy of cones over the corner normals
// cannot prove free of the contour (all corners of a cluster on one side); it gives the same
// chains as testing every face.
#pragma once

#include "core/lines/chaining.h"
#include "core/lines/silhouette_tracker.h"
#include "core/lines/smooth_pieces.h"
#include "core/mesh/mesh.h"
#include "core/mesh/topology.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace inkline::core {

namespace internal {
class ConeTree;
}  // namespace internal

struct SmoothContourOptions {
    // kIncremental: the cone hierarchy, built on the first trace; kBrute: every face, every trace.
    TrackerMode mode = TrackerMode::kIncremental;
    // Positions change between traces (same topology): the corner normals are recomputed and
    // the hierarchy refitted each trace. Otherwise every trace must pass the first one's positions.
    bool deforming = false;
    uint32_t leaf_faces = 16;  // faces per leaf cluster of the hierarchy
    // Edges whose faces meet at a sharper angle than this (is_crease) split the vertex normals.
    double crease_angle_deg = 180.0;
};

struct SmoothContourStats {
    size_t faces_tested = 0;   // faces whose corner signs were compared
    size_t segments = 0;       // faces the contour crosses
    size_t nodes_visited = 0;  // cone tests (incremental)
};

// A stretch of a crease edge on the outline: from p0 to p1 (in the direction from the edge's
// lower-numbered vertex) the smooth pieces on its two sides face opposite ways.
struct CreaseOutline {
    uint32_t edge = 0;
    glm::dvec3 p0{0.0}, p1{0.0};  // object space: an end of the edge, or where a side's g is zero
    bool vertex0 = false, vertex1 = false;  // whether p0 (p1) is the edge's vertex
    uint32_t face = 0;  // the face of the side that faces the eye there
};

// Traces the smooth contours of one frame's mesh seen from eye_object. Chains are silhouettes
// (core/lines/chaining.h says how their points, edges and faces relate); deterministic: the
// same mesh and eye give the same chains, points bit for bit, in either mode.
class SmoothContourTracer {
  public:
    // `table` is the mesh's edge table; the edges of every face are listed here once.
    SmoothContourTracer(const Mesh& mesh, const EdgeTable& table, const SmoothContourOptions& options = {});
    ~SmoothContourTracer();
    SmoothContourTracer(SmoothContourTracer&&) noexcept;
    SmoothContourTracer& operator=(SmoothContourTracer&&) noexcept;

    const std::vector<Chain>& trace(const Mesh& mesh, const EdgeTable& table, const Viewpoint& eye_object);
    const SmoothContourStats& stats() const { return stats_; }
    // The last trace's stretches of crease edges on the outline, by edge, and along each edge
    // from its lower-numbered vertex.
    const std::vector<CreaseOutline>& crease_outline() const { return crease_outline_; }
    // How the smooth surface faces the last trace's eye at p (object space) on face `face` of
    // the last trace's mesh: g interpolated over the face from its corners' values, which the
    // contour crosses where it is zero (> 0: turned away). NaN where the face is degenerate, or
    // where its connected part of the mesh is not closed (has an edge of one face, or of three
    // and more), as a sheet whose back hides nothing behind it.
    double facing(const Mesh& mesh, uint32_t face, const glm::dvec3& p) const;
    // Fills an intersection chain's `facing` (core/lines/chaining.h) from the last trace.
    void set_facing(const Mesh& mesh, Chain& r_chain) const;

  private:
    // The corner groups and their normals for the mesh's positions.
    void smooth_pieces(const Mesh& mesh, const EdgeTable& table);
    void test_every_face(const Mesh& mesh, const EdgeTable& table, const Viewpoint& eye_object);
    void search(uint32_t node);        // the faces under a node the cones cannot rule out
    bool back(uint32_t group);         // g > 0, computed once a trace (incremental)
    // g of a corner group at the last trace's eye: the one expression every test of a corner
    // uses, so that the contour and `facing` agree bit for bit.
    double corner_value(const Mesh& mesh, uint32_t group) const;
    void chain(const Mesh& mesh, const EdgeTable& table);
    // g of a corner group this trace (incremental: computed where not yet).
    double value(uint32_t group);
    // The stretches of crease edges on the outline, and their chains.
    void trace_crease_outline(const Mesh& mesh, const EdgeTable& table);

    SmoothContourOptions options_;
    std::vector<glm::uvec3> face_edges_;
    // The corner groups, their normals (incremental: of the last trace) and which sides join.
    SmoothPieces pieces_;
    std::vector<uint8_t> closed_;       // per face: its connected part of the mesh is closed
    // The crease edges between two faces (not joined), each with the side it is of each face.
    struct CreaseEdge {
        uint32_t edge;
        uint32_t face[2];
        uint8_t side[2];
    };
    std::vector<CreaseEdge> creases_;   // by edge
    std::vector<CreaseOutline> crease_outline_;
    std::unique_ptr<internal::ConeTree> tree_;  // incremental, from the first trace on
    // Per group: g, read once per trace where it is tested (incremental: valid where stamp holds
    // this trace's frame_). One record, so that a group costs one cache line.
    struct VertexValue {
        double g = 0.0;
        uint32_t stamp = 0;
        bool back() const { return g > 0.0; }
    };
    std::vector<VertexValue> values_;
    uint32_t frame_ = 0;
    // Valid during trace (incremental).
    const Mesh* mesh_ = nullptr;
    Viewpoint eye_;
    std::vector<uint32_t> contour_faces_;  // faces whose corners differ
    struct Crossing {
        uint32_t edge, face, side;  // the contour crosses the face's edge `side` (face_edges_ order)
    };
    std::vector<Crossing> crossings_;      // by edge, then face
    std::vector<uint8_t> face_used_;       // per face; zero between traces
    std::vector<Chain> chains_;
    SmoothContourStats stats_;
};

// Crease chains (core/lines/chaining.h) with the stretches on the outline taken out: a chain
// with none is kept as it is; one with some is cut into chains of points (`points` set, no
// `vertices`) that end where the outline's stretches begin and end.
std::vector<Chain> cut_crease_outline(std::vector<Chain> creases, const std::vector<CreaseOutline>& outline,
                                      const Mesh& mesh, const EdgeTable& table);

// The face each segment of a smooth contour line crosses, from the edge each segment starts on
// (what a stroke keeps through the stroke stage): of that edge's faces, the one nearest the
// segment's midpoint. points_object has one point more than edges.
std::vector<uint32_t> faces_crossed(const Mesh& mesh, const EdgeTable& table, std::span<const glm::dvec3> points_object,
                                    std::span<const uint32_t> edges);

}  // namespace inkline::core
