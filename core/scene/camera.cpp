// SPDX-License-Identifier: MIT
#include "core/scene/camera.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

namespace inkline::core {

glm::dmat4 view_from_world(const Camera& camera) {
    glm::dmat4 view = glm::lookAt(camera.eye, camera.target, camera.up);
    if (camera.orthographic()) {
        // The same matrix, its translation taken about the target: x and y of a point are then
        // measured from the axis near the subject, not from an eye whose distance an
        // orthographic view does not see (a tiny subject under a far eye keeps its precision).
        const glm::dvec3 offset = camera.target;
        const double distance = glm::length(camera.eye - camera.target);
        for (int row = 0; row < 3; ++row) {
            view[3][row] = -(view[0][row] * offset.x + view[1][row] * offset.y + view[2][row] * offset.z);
        }
        view[3][2] -= distance;
    }
    return view;
}

glm::dmat4 clip_from_view(const Camera& camera, ImageSize image) {
    const double aspect = double(image.width) / double(image.height);
    if (camera.ortho_height) {
        const double half_y = 0.5 * *camera.ortho_height;
        return glm::ortho(-half_y * aspect, half_y * aspect, -half_y, half_y, camera.near, camera.far);
    }
    return glm::perspective(glm::radians(camera.fov_y_deg), aspect, camera.near, camera.far);
}

Viewpoint Viewpoint::at_infinity(const glm::dvec3& towards_viewer) {
    Viewpoint v;
    v.xyz = glm::normalize(towards_viewer);
    v.w = 0.0;
    return v;
}

Viewpoint viewpoint_of(const Camera& camera) {
    return camera.orthographic() ? Viewpoint::at_infinity(camera.eye - camera.target) : Viewpoint(camera.eye);
}

Projection::Projection(const Camera& camera, ImageSize image, const glm::dmat4& world_from_object)
    : clip_from_object_(clip_from_view(camera, image) * view_from_world(camera) * world_from_object),
      world_from_object_(world_from_object),
      image_(image),
      near_(camera.near) {
    const glm::dmat4 object_from_world = glm::inverse(world_from_object);
    if (camera.orthographic()) {
        eye_object_ = Viewpoint::at_infinity(glm::dvec3(object_from_world * glm::dvec4(viewpoint_of(camera).xyz, 0.0)));
        // glm::ortho maps depth d in [near, far] to z = (2 d - far - near) / (far - near), w = 1.
        depth_from_z_ = 0.5 * (camera.far - camera.near);
        depth_from_w_ = 0.5 * (camera.far + camera.near);
    } else {
        eye_object_ = Viewpoint(glm::dvec3(object_from_world * glm::dvec4(camera.eye, 1.0)));
    }
}

glm::dvec2 Projection::pixel_from_clip(const glm::dvec4& p_clip) const {
    const double ndc_x = p_clip.x / p_clip.w;
    const double ndc_y = p_clip.y / p_clip.w;
    return {(ndc_x * 0.5 + 0.5) * image_.width, (1.0 - (ndc_y * 0.5 + 0.5)) * image_.height};
}

bool Projection::inside_image(const glm::dvec2& p_px) const {
    return p_px.x >= 0.0 && p_px.y >= 0.0 && p_px.x <= image_.width && p_px.y <= image_.height;
}

}  // namespace inkline::core
