// SPDX-License-Identifier: MIT
#include "core/scene/camera.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

namespace inkline::core {

glm::dmat4 view_from_world(const Camera& camera) {
    return glm::lookAt(camera.eye, camera.target, camera.up);
}

glm::dmat4 clip_from_view(const Camera& camera, ImageSize image) {
    return glm::perspective(glm::radians(camera.fov_y_deg),
                            double(image.width) / double(image.height), camera.near, camera.far);
}

Projection::Projection(const Camera& camera, ImageSize image, const glm::dmat4& world_from_object)
    : clip_from_object_(clip_from_view(camera, image) * view_from_world(camera) * world_from_object),
      world_from_object_(world_from_object),
      eye_object_(glm::dvec3(glm::inverse(world_from_object) * glm::dvec4(camera.eye, 1.0))),
      image_(image),
      near_(camera.near) {}

glm::dvec2 Projection::pixel_from_clip(const glm::dvec4& p_clip) const {
    const double ndc_x = p_clip.x / p_clip.w;
    const double ndc_y = p_clip.y / p_clip.w;
    return {(ndc_x * 0.5 + 0.5) * image_.width, (1.0 - (ndc_y * 0.5 + 0.5)) * image_.height};
}

bool Projection::inside_image(const glm::dvec2& p_px) const {
    return p_px.x >= 0.0 && p_px.y >= 0.0 && p_px.x <= image_.width && p_px.y <= image_.height;
}

}  // namespace inkline::core
