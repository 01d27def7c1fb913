// SPDX-License-Identifier: MIT
// Chaining: feature edges of one kind that meet at a vertex become maximal polylines.
#pragma once

#include "core/lines/features.h"
#include "core/mesh/topology.h"

#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace inkline::core {

// A polyline through mesh vertices. edges[i] joins vertices[i] and vertices[i+1]; a closed
// chain repeats its first vertex at the end, so edges.size() + 1 == vertices.size() always.
//
// An intersection chain (core/lines/intersections.h) runs through points where an edge of one
// surface crosses a face of the other instead: `points` holds them (object space) and `vertices`
// is empty. Its segment i lies on two faces: first_faces[i], a face of the first surface, of
// which edges[i] is an edge (where the segment meets that face's border, else the face's edge
// nearest the segment), and crossing_faces[i], the face of the other surface;
// edges.size() + 1 == points.size().
//
// With smooth contours, an intersection chain also knows how its two surfaces face the eye along
// each segment (`facing`): where a closed surface turns away from the eye, as the smooth contour
// takes it, its back hides what lies on it (core/visibility/visibility.h).
//
// A smooth contour chain (core/lines/smooth_contours.h) runs through points on mesh edges where
// the interpolated contour crosses them: `points` holds them (object space), `vertices` is
// empty, point i lies on edges[i] (the last point on the edge after the last segment's face),
// and segment i crosses faces[i], of which edges[i] is an edge.
// How the two surfaces of an intersection segment face the eye, as smooth contours take it
// (core/lines/smooth_contours.h, SmoothContourTracer::facing): g of the first surface at the
// segment's start and end, then of the other surface's (> 0: turned away); NaN for a surface
// that is not closed.
struct SegmentFacing {
    std::array<double, 2> first{NAN, NAN}, other{NAN, NAN};
};

struct Chain {
    LineKind kind = LineKind::kSilhouette;
    bool closed = false;
    std::vector<uint32_t> vertices;
    std::vector<uint32_t> edges;
    std::vector<glm::dvec3> points;         // intersection and smooth contour chains only
    std::vector<uint32_t> crossing_faces;   // intersection chains only
    std::vector<uint32_t> faces;            // smooth contour chains only
    std::vector<uint32_t> first_faces;      // intersection chains only: each segment's face of the first surface
    std::vector<SegmentFacing> facing;      // intersection chains drawn with smooth contours only
};

// Links feature edges of the same kind through vertices where exactly two such edges meet;
// chains end at vertices with any other count. Deterministic: depends only on the edge set.
std::vector<Chain> chain_feature_edges(const FeatureEdges& features, const EdgeTable& table);

}  // namespace inkline::core
