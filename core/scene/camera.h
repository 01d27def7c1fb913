// SPDX-License-Identifier: MIT
// Cameras (perspective and orthographic) and the pixel convention: glm::lookAt + glm::perspective
// or glm::ortho, origin top-left, y down.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <optional>

namespace inkline::core {

struct ImageSize {
    int width = 0;   // px
    int height = 0;  // px
};

struct Camera {
    glm::dvec3 eye{0.0, 0.0, 4.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fov_y_deg = 35.0;  // vertical field of view (perspective)
    double near = 0.1;        // distances along the view axis from the eye, world units
    double far = 100.0;
    // Set: an orthographic camera whose view is this high (world units) at every depth; the
    // eye is then where the view axis starts, for near and far, and fov_y_deg is unused.
    std::optional<double> ortho_height{};

    bool orthographic() const { return ortho_height.has_value(); }
    bool operator==(const Camera&) const = default;
};

// Where a camera sees from, in one coordinate space, as a homogeneous point: the eye of a
// perspective camera (w = 1), or for an orthographic one the point at infinity (w = 0) in the
// unit direction towards the viewer. Every "towards the eye" of the pipeline is toward(p), so
// facing tests, contours and occlusion treat both projections alike.
struct Viewpoint {
    glm::dvec3 xyz{0.0, 0.0, 4.0};
    double w = 1.0;

    Viewpoint() = default;
    Viewpoint(const glm::dvec3& eye) : xyz(eye) {}  // NOLINT(google-explicit-constructor): a point eye
    // The orthographic viewpoint looking along -towards_viewer (normalised here).
    static Viewpoint at_infinity(const glm::dvec3& towards_viewer);

    bool orthographic() const { return w == 0.0; }
    // From p towards the viewer: eye - p, or the direction towards the viewer (unit length).
    glm::dvec3 toward(const glm::dvec3& p) const { return xyz - w * p; }
};

// The camera's viewpoint in world space.
Viewpoint viewpoint_of(const Camera& camera);

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
    // Distance along the view axis from the eye (world units) of a clip-space point: its w in
    // perspective, read from its z in orthographic projection (where w is 1).
    double depth(const glm::dvec4& p_clip) const { return depth_from_z_ * p_clip.z + depth_from_w_ * p_clip.w; }
    // In front of the near plane.
    bool in_front(const glm::dvec4& p_clip) const { return depth(p_clip) > near_; }
    bool inside_image(const glm::dvec2& p_px) const;

    // The camera's viewpoint in object space.
    const Viewpoint& eye_object() const { return eye_object_; }
    bool orthographic() const { return eye_object_.orthographic(); }
    const glm::dmat4& clip_from_object() const { return clip_from_object_; }
    double near() const { return near_; }
    const glm::dmat4& world_from_object() const { return world_from_object_; }
    ImageSize image() const { return image_; }

  private:
    glm::dmat4 clip_from_object_;
    glm::dmat4 world_from_object_;
    Viewpoint eye_object_;
    ImageSize image_;
    double near_;
    double depth_from_z_ = 0.0, depth_from_w_ = 1.0;
};

}  // namespace inkline::core
