// SPDX-License-Identifier: MIT
// The light at a point of a mesh, as stippling and hatching both read it (their tone curves turn
// it into a tone: tone_of).
#pragma once

#include "core/strokes/brush_style.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace inkline::core::internal {

// The light's intensity at a point: its object-space normal taken to world space, against the
// direction to the light. A directional light's direction is normalized once, the same bits as at
// every call; a point's world position is computed only for a point light.
class ToneLight {
  public:
    ToneLight(const glm::dmat4& world_from_object, const Light& light)
        : world_from_object_(world_from_object),
          normal_matrix_(glm::transpose(glm::inverse(glm::dmat3(world_from_object)))),
          light_(light),
          direction_(glm::normalize(-light.direction)) {}

    // The intensity at p (object space) with normal `normal` (object space, not zero).
    double intensity(const glm::dvec3& p, const glm::dvec3& normal) const {
        const glm::dvec3 n = glm::normalize(normal_matrix_ * normal);
        const glm::dvec3 to_light =
            light_.is_point ? glm::normalize(light_.position - glm::dvec3(world_from_object_ * glm::dvec4(p, 1.0)))
                            : direction_;
        return glm::dot(n, to_light);
    }

  private:
    glm::dmat4 world_from_object_;
    glm::dmat3 normal_matrix_;
    Light light_;
    glm::dvec3 direction_;
};

}  // namespace inkline::core::internal
