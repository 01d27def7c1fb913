// SPDX-License-Identifier: MIT
#include "core/visibility/internal/face_tests.h"

#include "core/visibility/visibility.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <utility>

namespace inkline::core::internal {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 to_point(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

double raycast_scale(const std::vector<glm::vec3>& positions) {
    float largest = 0.0f;
    for (const glm::vec3& p : positions) largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return largest > 0.0f && std::isfinite(largest) ? std::ldexp(1.0, -std::ilogb(largest)) : 1.0;
}

ScaledRay occlusion_ray(const glm::dvec3& p_object, const Viewpoint& eye_object, double reach, double scale) {
    const glm::dvec3 far_end = occlusion_segment_end(p_object, eye_object, reach);
    ScaledRay ray;
    ray.origin = glm::vec3(p_object * scale);
    ray.direction = glm::vec3((far_end - p_object) * scale);
    return ray;
}

RayTriangleTest::RayTriangleTest(const ScaledRay& ray)
    : origin_(ray.origin), tnear_(double(ray.tnear)), tfar_(double(ray.tfar)) {
    // Step along the direction's largest component (kz), keeping the winding: the triangle is
    // sheared so the ray runs along z, then the edge functions decide in the xy plane.
    const glm::dvec3 d(ray.direction);
    const glm::dvec3 size = glm::abs(d);
    kz_ = size.x > size.y ? (size.x > size.z ? 0 : 2) : (size.y > size.z ? 1 : 2);
    kx_ = (kz_ + 1) % 3;
    ky_ = (kx_ + 1) % 3;
    if (d[kz_] < 0.0) std::swap(kx_, ky_);
    if (d[kz_] == 0.0) {
        tfar_ = -1.0;  // no direction: meets nothing, as Embree answers
        return;
    }
    shear_x_ = d[kx_] / d[kz_];
    shear_y_ = d[ky_] / d[kz_];
    shear_z_ = 1.0 / d[kz_];
}

bool RayTriangleTest::meets(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const {
    if (tfar_ < tnear_) return false;
    const glm::dvec3 pa = a - origin_, pb = b - origin_, pc = c - origin_;
    const double ax = pa[kx_] - shear_x_ * pa[kz_], ay = pa[ky_] - shear_y_ * pa[kz_];
    const double bx = pb[kx_] - shear_x_ * pb[kz_], by = pb[ky_] - shear_y_ * pb[kz_];
    const double cx = pc[kx_] - shear_x_ * pc[kz_], cy = pc[ky_] - shear_y_ * pc[kz_];
    // Edge functions: a zero counts as inside, so edges and corners meet the ray.
    const double u = cx * by - cy * bx;
    const double v = ax * cy - ay * cx;
    const double w = bx * ay - by * ax;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    const double det = u + v + w;
    if (det == 0.0) return false;  // the ray lies in the triangle's plane
    // Distance along the ray times det, compared without dividing: tnear < t <= tfar.
    const double t_det = u * (shear_z_ * pa[kz_]) + v * (shear_z_ * pb[kz_]) + w * (shear_z_ * pc[kz_]);
    if (det > 0.0) return t_det > tnear_ * det && t_det <= tfar_ * det;
    return t_det < tnear_ * det && t_det >= tfar_ * det;
}

QuerySegment query_segment(const glm::dvec3& p_object, const Viewpoint& eye_object, double reach) {
    const glm::dvec3 far_end = occlusion_segment_end(p_object, eye_object, reach);
    return {far_end, p_object + (far_end - p_object) * kSegmentEndGap};
}

bool segment_meets_triangle(const QuerySegment& segment, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c) {
    return CGAL::do_intersect(Kernel::Segment_3(to_point(segment.far_end), to_point(segment.stop)),
                              Kernel::Triangle_3(to_point(a), to_point(b), to_point(c)));
}

}  // namespace inkline::core::internal
