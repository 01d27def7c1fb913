// SPDX-License-Identifier: MIT
// Exact occlusion: segment queries against a CGAL AABB tree of the mesh triangles. The faces of
// fans (core/visibility/internal/fan_index.h) are left out of that tree: a second tree holds one
// box per fan, and a segment that meets a fan's box tests only the fan's faces that the fan
// index finds for it, with the same exact predicates.
#include "core/visibility/exact_visibility.h"

#include "core/error.h"
#include "core/internal/parallel.h"
#include "core/visibility/internal/face_tests.h"
#include "core/visibility/internal/fan_index.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <boost/iterator/function_output_iterator.hpp>

#include <vector>

namespace inkline::core {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;
using Box = Kernel::Iso_cuboid_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// A fan's box as a primitive of a CGAL AABB tree (the AABBPrimitive concept); its id points at
// the box, whose offset in the vector is the fan's number.
class FanPrimitive {
  public:
    using Id = std::vector<Box>::const_iterator;
    using Datum = Box;
    using Point = Kernel::Point_3;

    FanPrimitive() = default;
    explicit FanPrimitive(Id box) : box_(box) {}
    const Datum& datum() const { return *box_; }
    Id id() const { return box_; }
    Point reference_point() const { return box_->min(); }

  private:
    Id box_;
};
using FanTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, FanPrimitive>>;

Point to_point(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

struct ExactOcclusion::Impl {
    const EdgeTable& table;
    std::vector<Triangle> triangles;
    std::vector<uint32_t> face_of;  // triangle index -> mesh face
    double reach = 1.0;             // occlusion_reach of the mesh
    Tree tree;
    internal::FanIndex fans;        // faces left out of `tree`
    std::vector<Box> fan_boxes;     // one per fan
    FanTree fan_tree;

    explicit Impl(const EdgeTable& t) : table(t) {}
};

ExactOcclusion::ExactOcclusion(const Mesh& mesh, const EdgeTable& table)
    : impl_(std::make_unique<Impl>(table)) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    Impl& impl = *impl_;
    impl.fans = internal::FanIndex(mesh, table, 1.0);
    const std::vector<uint8_t>& in_fan = impl.fans.in_fan();
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (!table.face_valid[f] || (!in_fan.empty() && in_fan[f])) continue;
        const glm::uvec3 t = mesh.triangles[f];
        impl.triangles.emplace_back(to_point(glm::dvec3(mesh.positions[t.x])),
                                    to_point(glm::dvec3(mesh.positions[t.y])),
                                    to_point(glm::dvec3(mesh.positions[t.z])));
        impl.face_of.push_back(f);
    }
    impl.reach = occlusion_reach(mesh.positions);
    impl.tree.insert(impl.triangles.cbegin(), impl.triangles.cend());
    impl.tree.build();
    for (uint32_t fan = 0; fan < impl.fans.fan_count(); ++fan) {
        const Bounds b = impl.fans.bounds(fan);
        impl.fan_boxes.emplace_back(to_point(b.min), to_point(b.max));
    }
    if (!impl.fan_boxes.empty()) {
        impl.fan_tree.insert(impl.fan_boxes.cbegin(), impl.fan_boxes.cend());
        impl.fan_tree.build();
    }
}

ExactOcclusion::~ExactOcclusion() = default;

void ExactOcclusion::occluded(const Viewpoint& eye_object, std::span<const OcclusionQuery> queries,
                              std::span<uint8_t> r_occluded) const {
    INKLINE_CHECK_EQ(queries.size(), r_occluded.size());
    const Impl& impl = *impl_;
    const TriangleIterator first = impl.triangles.cbegin();
    internal::parallel_for(queries.size(), 256, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const OcclusionQuery& q = queries[i];
            const internal::QuerySegment query = internal::query_segment(q.p_object, eye_object, impl.reach);
            const Segment segment(to_point(query.far_end), to_point(query.stop));
            const internal::OwnFaces own = internal::own_faces_of(q, impl.table);
            bool hit = false;
            impl.tree.all_intersected_primitives(
                segment, boost::make_function_output_iterator([&](const TriangleIterator& it) {
                    const uint32_t face = impl.face_of[size_t(it - first)];
                    if (!own.has(face)) hit = true;
                }));
            if (!hit && !impl.fan_boxes.empty()) {
                const glm::dvec3 direction = query.far_end - query.stop;
                impl.fan_tree.all_intersected_primitives(
                    segment, boost::make_function_output_iterator([&](const FanPrimitive::Id& box) {
                        if (hit) return;
                        const auto fan = uint32_t(box - impl.fan_boxes.cbegin());
                        hit = impl.fans.find_face(
                            fan, query.stop, direction, 0.0, 1.0,
                            [&](uint32_t face, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
                                return !own.has(face) &&
                                       internal::segment_meets_triangle(query, a, b, c);
                            });
                    }));
            }
            r_occluded[i] = hit ? 1 : 0;
        }
    });
}

}  // namespace inkline::core
