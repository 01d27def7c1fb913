// SPDX-License-Identifier: MIT
#include "core/visibility/exact_visibility.h"

#include "core/error.h"
#include "core/internal/parallel.h"
#include "core/visibility/internal/face_tests.h"

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
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_point(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

struct ExactOcclusion::Impl {
    const EdgeTable& table;
    std::vector<Triangle> triangles;
    std::vector<uint32_t> face_of;  // triangle index -> mesh face
    double reach = 1.0;             // occlusion_reach of the mesh
    Tree tree;

    explicit Impl(const EdgeTable& t) : table(t) {}
};

ExactOcclusion::ExactOcclusion(const Mesh& mesh, const EdgeTable& table)
    : impl_(std::make_unique<Impl>(table)) {
    INKLINE_CHECK_EQ(table.face_valid.size(), mesh.triangles.size());
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        if (!table.face_valid[f]) continue;
        const glm::uvec3 t = mesh.triangles[f];
        impl_->triangles.emplace_back(to_point(glm::dvec3(mesh.positions[t.x])),
                                      to_point(glm::dvec3(mesh.positions[t.y])),
                                      to_point(glm::dvec3(mesh.positions[t.z])));
        impl_->face_of.push_back(f);
    }
    impl_->reach = occlusion_reach(mesh.positions);
    impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
    impl_->tree.build();
}

ExactOcclusion::~ExactOcclusion() = default;

void ExactOcclusion::occluded(const glm::dvec3& eye_object, std::span<const OcclusionQuery> queries,
                              std::span<uint8_t> r_occluded) const {
    INKLINE_CHECK_EQ(queries.size(), r_occluded.size());
    const Impl& impl = *impl_;
    const TriangleIterator first = impl.triangles.cbegin();
    internal::parallel_for(queries.size(), 256, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const OcclusionQuery& q = queries[i];
            const internal::QuerySegment query = internal::query_segment(q.p_object, eye_object, impl.reach);
            const Segment segment(to_point(query.far_end), to_point(query.stop));
            const auto own = impl.table.faces_of(q.edge);
            bool hit = false;
            impl.tree.all_intersected_primitives(
                segment, boost::make_function_output_iterator([&](const TriangleIterator& it) {
                    const uint32_t face = impl.face_of[size_t(it - first)];
                    if (!internal::is_own_face(own, face)) hit = true;
                }));
            r_occluded[i] = hit ? 1 : 0;
        }
    });
}

}  // namespace inkline::core
