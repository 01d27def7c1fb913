// SPDX-License-Identifier: MIT
// Pinhole camera and the pixel convention: glm::lookAt + glm::perspective, origin top-left, y down.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace inkline::core {

struct ImageSize {
    int width = 0;   // px
    int height = 0;  // px
};

struct Camera {
    glm::dvec3 eye{0.0, 0.0, 4.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fov_y_deg = 35.0;  // vertical field of view
    double near = 0.1;        // distances along the view axis, world units
    double far = 100.0;
};

glm::dmat4 view_from_world(const Camera& camera);
glm::dmat4 clip_from_view(const Camera& camera, ImageSize image);

// Maps object-space points to clip space and pixels for one frame.
class Projection {
  public:
    Projection(const Camera& camera, ImageSize image, const glm::dmat4& world_from_object);

    glm::dvec4 clip(const glm::dvec3& p_object) const { return clip_from_object_ * glm::dvec4(p_object, 1.0); }
    // Pixel position of a clip-space point with w > 0: x right, y down, origin top-left.
    glm::dvec2 pixel_from_clip(const glm::dvec4& p_clip) const;
    glm::dvec2 pixel(const glm::dvec3& p_object) const { return pixel_from_clip(clip(p_object)); }
    // In front of the near plane (clip w is the view-space depth).
    bool in_front(const glm::dvec4& p_clip) const { return p_clip.w > near_; }
    bool inside_image(const glm::dvec2& p_px) const;

    const glm::dvec3& eye_object() const { return eye_object_; }
    const glm::dmat4& clip_from_object() const { return clip_from_object_; }
    double near() const { return near_; }
    const glm::dmat4& world_from_object() const { return world_from_object_; }
    ImageSize image() const { return image_; }

  private:
    glm::dmat4 clip_from_object_;
    glm::dmat4 world_from_object_;
    glm::dvec3 eye_object_;
    ImageSize image_;
    double near_;
};

}  // namespace inkline::core
