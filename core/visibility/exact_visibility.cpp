// SPDX-License-Identifier: MIT
#include "core/visibility/exact_visibility.h"

#include "core/error.h"
#include "core/internal/parallel.h"

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

// The query segment stops this fraction of its length short of the point, so faces that merely
// touch the point (those around an end vertex of its edge) do not count as occluders. At a
// 4-unit viewing distance this is 4e-6 units, far below a pixel at any supported image size.
// The segment is first clipped to kOcclusionReachDiagonals (core/visibility/visibility.h), so a far eye
// does not widen the gap past the mesh.
constexpr double kEndGap = 1e-6;

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
            const glm::dvec3 far_end = occlusion_segment_end(q.p_object, eye_object, impl.reach);
            const glm::dvec3 stop = q.p_object + (far_end - q.p_object) * kEndGap;
            const Segment segment(to_point(far_end), to_point(stop));
            const auto own = impl.table.faces_of(q.edge);
            bool hit = false;
            impl.tree.all_intersected_primitives(
                segment, boost::make_function_output_iterator([&](const TriangleIterator& it) {
                    const uint32_t face = impl.face_of[size_t(it - first)];
                    if (std::find(own.begin(), own.end(), face) == own.end()) hit = true;
                }));
            r_occluded[i] = hit ? 1 : 0;
        }
    });
}

}  // namespace inkline::core
