// SPDX-License-Identifier: MIT
#include "tests/support/ground_plane.h"

#include "tests/support/pipeline.h"

#include <algorithm>
#include <cmath>

namespace inkline::test {

core::Mesh ground_plane(float half_width, float z_far, float z_near) {
    core::Mesh plane;
    plane.positions = {{-half_width, 0.0f, z_far}, {half_width, 0.0f, z_far}, {half_width, 0.0f, z_near},
                       {-half_width, 0.0f, z_near}};
    plane.triangles = {{0, 2, 1}, {0, 3, 2}};
    return plane;
}

core::Scene ground_scene(const core::Mesh& plane, core::ImageSize image) {
    core::Scene scene = scene_for({.eye = {0.0, 1.2, 3.0}, .fov_y_deg = 50.0, .size = image.width}, plane);
    scene.camera.pose.target = {0.0, 0.0, -3.0};
    scene.image = image;
    scene.camera.near = 0.1;
    scene.camera.far = 100.0;
    scene.lines.silhouette = scene.lines.boundary = scene.lines.crease = scene.lines.intersection = false;
    return scene;
}

std::vector<double> ground_band_ink(const core::Mesh& plane, const core::Projection& projection,
                                    std::span<const double> coverage, int bands) {
    const core::ImageSize image = projection.image();
    double lo_x = 0.0, hi_x = 0.0, lo_z = 0.0, hi_z = 0.0;
    for (const glm::vec3& p : plane.positions) {
        lo_x = std::min(lo_x, double(p.x)), hi_x = std::max(hi_x, double(p.x));
        lo_z = std::min(lo_z, double(p.z)), hi_z = std::max(hi_z, double(p.z));
    }
    // Below where the plane's sides leave the image (the part of them in front of the camera).
    double side_row = 0.0;
    for (double z = lo_z; z <= std::min(hi_z, 2.9); z += 0.01) {
        for (const double x : {lo_x, hi_x}) {
            const glm::dvec2 px = projection.pixel({x, 0.0, z});
            if (px.x >= 0.0 && px.x <= image.width) side_row = std::max(side_row, px.y);
        }
    }
    // And below its far edge, for a plane whose sides lie outside the image.
    for (int k = 0; k <= 1000; ++k) {
        const glm::dvec2 px = projection.pixel({lo_x + (hi_x - lo_x) * k / 1000.0, 0.0, lo_z});
        if (px.x >= 0.0 && px.x <= image.width) side_row = std::max(side_row, px.y);
    }
    const int first = int(std::ceil(side_row)) + 2, last = image.height;
    std::vector<double> out;
    if (first >= last - 40) return out;
    for (int band = 0; band < bands; ++band) {
        const int r0 = first + (last - first) * band / bands, r1 = first + (last - first) * (band + 1) / bands;
        double sum = 0.0;
        for (int row = r0; row < r1; ++row) {
            for (int col = 0; col < image.width; ++col) sum += coverage[size_t(row) * size_t(image.width) + size_t(col)];
        }
        out.push_back(sum / double((r1 - r0) * image.width));
    }
    return out;
}

}  // namespace inkline::test
