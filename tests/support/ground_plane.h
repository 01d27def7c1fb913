// SPDX-License-Identifier: MIT
// A ground plane of two triangles seen in strong perspective, as a shot's ground: the camera
// stands 1.2 units above it at z = 3 looking down towards (0, 0, -3); the plane runs from far
// ahead to z_near, behind the camera when z_near > 3. The tone tests measure ink in bands of
// rows where the plane fills the image from side to side.
#pragma once

#include "core/mesh/mesh.h"
#include "core/scene/camera.h"
#include "core/scene/scene.h"

#include <span>
#include <vector>

namespace inkline::test {

// The plane from x = -half_width to half_width and from z = z_far (ahead, below 0) to z_near.
core::Mesh ground_plane(float half_width, float z_far, float z_near);

// A one-frame scene of the plane from that camera (fov 50 degrees, near 0.1, far 100) at
// `image`, every kind of line off.
core::Scene ground_scene(const core::Mesh& plane, core::ImageSize image);

// The mean of `coverage` (per pixel, rows from the top) in `bands` bands of rows from the first
// row the plane fills from side to side (two rows below where its sides leave the image, and below
// its far edge) to the image's bottom, far to near. Empty when fewer than 40 such rows.
std::vector<double> ground_band_ink(const core::Mesh& plane, const core::Projection& projection,
                                    std::span<const double> coverage, int bands);

}  // namespace inkline::test
