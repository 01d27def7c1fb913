// SPDX-License-Identifier: MIT
#include "tests/support/tone_raster.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace inkline::test {
namespace {

size_t pixel_count(core::ImageSize image) {
    return size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0));
}

// The unit direction towards the light from a world point.
glm::dvec3 to_light(const core::Light& light, const glm::dvec3& p_world) {
    return glm::normalize(light.is_point ? light.position - p_world : -light.direction);
}

glm::dmat3 normal_matrix(const core::Projection& projection) {
    return glm::transpose(glm::inverse(glm::dmat3(projection.world_from_object())));
}

}  // namespace

std::vector<double> dot_coverage(std::span<const core::Dot> dots, core::ImageSize image, int samples_per_side) {
    if (samples_per_side < 1 || samples_per_side > 8) throw std::invalid_argument("samples_per_side must be 1 to 8");
    const int n = samples_per_side;
    std::vector<uint64_t> bits(pixel_count(image), 0);
    for (const core::Dot& dot : dots) {
        const double r = dot.radius_px;
        if (!(r > 0.0)) continue;
        const glm::dvec2 c = dot.point_px;
        const int x0 = std::max(0, int(std::floor(c.x - r))), x1 = std::min(image.width - 1, int(std::floor(c.x + r)));
        const int y0 = std::max(0, int(std::floor(c.y - r))), y1 = std::min(image.height - 1, int(std::floor(c.y + r)));
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                uint64_t mask = 0;
                for (int j = 0; j < n; ++j) {
                    const double dy = y + (j + 0.5) / n - c.y;
                    for (int i = 0; i < n; ++i) {
                        const double dx = x + (i + 0.5) / n - c.x;
                        if (dx * dx + dy * dy <= r * r) mask |= uint64_t(1) << (j * n + i);
                    }
                }
                bits[size_t(y) * size_t(image.width) + size_t(x)] |= mask;
            }
        }
    }
    std::vector<double> coverage(bits.size());
    for (size_t k = 0; k < bits.size(); ++k) coverage[k] = double(std::popcount(bits[k])) / double(n * n);
    return coverage;
}

bool SurfacePixels::interior(int x, int y) const {
    if (x < 1 || y < 1 || x >= image.width - 1 || y >= image.height - 1) return false;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            if (!on_surface[size_t(y + dy) * size_t(image.width) + size_t(x + dx)]) return false;
        }
    }
    return true;
}

double kept_share(std::span<const core::Dot> before, std::span<const core::Dot> now) {
    if (now.empty()) return 1.0;
    size_t i = 0, kept = 0;
    for (const core::Dot& dot : now) {
        while (i < before.size() && before[i].sample < dot.sample) ++i;
        if (i < before.size() && before[i].sample == dot.sample) ++kept;
    }
    return double(kept) / double(now.size());
}

size_t SurfacePixels::count() const { return size_t(std::count(on_surface.begin(), on_surface.end(), uint8_t(1))); }

SurfacePixels sphere_pixels(const glm::dvec3& centre, double radius, const core::Projection& projection,
                            const core::Light& light) {
    SurfacePixels out;
    out.image = projection.image();
    const size_t size = pixel_count(out.image);
    out.on_surface.assign(size, 0);
    out.n_dot_l.assign(size, 0.0);
    out.face.assign(size, 0);
    const glm::dmat4 object_from_clip = glm::inverse(projection.clip_from_object());
    const glm::dmat3 normals = normal_matrix(projection);
    const glm::dvec3 eye = projection.eye_object().xyz;  // a perspective camera's
    const glm::dvec3 oc = eye - centre;
    for (int y = 0; y < out.image.height; ++y) {
        for (int x = 0; x < out.image.width; ++x) {
            // The pixel centre on the far plane, then the ray from the eye through it.
            const double ndc_x = (x + 0.5) / out.image.width * 2.0 - 1.0;
            const double ndc_y = 1.0 - (y + 0.5) / out.image.height * 2.0;
            const glm::dvec4 far = object_from_clip * glm::dvec4(ndc_x, ndc_y, 1.0, 1.0);
            const glm::dvec3 d = glm::normalize(glm::dvec3(far) / far.w - eye);
            const double b = glm::dot(oc, d);
            const double disc = b * b - (glm::dot(oc, oc) - radius * radius);
            if (disc < 0.0) continue;
            const double t = -b - std::sqrt(disc);
            if (t <= 0.0) continue;
            const glm::dvec3 p = eye + t * d;
            const glm::dvec3 n = glm::normalize(normals * ((p - centre) / radius));
            const glm::dvec3 p_world(projection.world_from_object() * glm::dvec4(p, 1.0));
            const size_t k = size_t(y) * size_t(out.image.width) + size_t(x);
            out.on_surface[k] = 1;
            out.n_dot_l[k] = glm::dot(n, to_light(light, p_world));
        }
    }
    return out;
}

SurfacePixels mesh_pixels(const core::Mesh& mesh, std::span<const glm::dvec3> normals,
                          const core::Projection& projection, const core::Light& light) {
    SurfacePixels out;
    out.image = projection.image();
    const size_t size = pixel_count(out.image);
    out.on_surface.assign(size, 0);
    out.n_dot_l.assign(size, 0.0);
    out.face.assign(size, 0);
    std::vector<double> nearest(size, 0.0);  // 1 / w of the nearest face so far (larger: nearer)
    std::vector<glm::dvec3> weights(size);   // its perspective-correct barycentric coordinates there

    std::vector<glm::dvec3> screen(mesh.positions.size());  // pixel x, y and 1 / w
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::dvec4 clip = projection.clip(glm::dvec3(mesh.positions[v]));
        screen[v] = projection.in_front(clip) ? glm::dvec3(projection.pixel_from_clip(clip), 1.0 / clip.w)
                                              : glm::dvec3(std::numeric_limits<double>::quiet_NaN());
    }
    for (uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        const glm::uvec3 t = mesh.triangles[f];
        const glm::dvec3 a = screen[t.x], b = screen[t.y], c = screen[t.z];
        if (!(a.z > 0.0 && b.z > 0.0 && c.z > 0.0)) continue;  // behind the near plane (or NaN)
        const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (area == 0.0) continue;
        const int x0 = std::max(0, int(std::ceil(std::min({a.x, b.x, c.x}) - 0.5)));
        const int x1 = std::min(out.image.width - 1, int(std::floor(std::max({a.x, b.x, c.x}) - 0.5)));
        const int y0 = std::max(0, int(std::ceil(std::min({a.y, b.y, c.y}) - 0.5)));
        const int y1 = std::min(out.image.height - 1, int(std::floor(std::max({a.y, b.y, c.y}) - 0.5)));
        for (int y = y0; y <= y1; ++y) {
            const double py = y + 0.5;
            for (int x = x0; x <= x1; ++x) {
                const double px = x + 0.5;
                const double l0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
                const double l1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
                const double l2 = 1.0 - l0 - l1;
                if (l0 < 0.0 || l1 < 0.0 || l2 < 0.0) continue;
                const double inv_w = l0 * a.z + l1 * b.z + l2 * c.z;
                const size_t k = size_t(y) * size_t(out.image.width) + size_t(x);
                if (out.on_surface[k] && inv_w <= nearest[k]) continue;
                out.on_surface[k] = 1;
                nearest[k] = inv_w;
                out.face[k] = f;
                weights[k] = glm::dvec3(l0 * a.z, l1 * b.z, l2 * c.z) / inv_w;
            }
        }
    }
    const glm::dmat3 to_world = normal_matrix(projection);
    for (size_t k = 0; k < size; ++k) {
        if (!out.on_surface[k]) continue;
        const glm::uvec3 t = mesh.triangles[out.face[k]];
        const glm::dvec3 w = weights[k];
        glm::dvec3 n = w.x * normals[t.x] + w.y * normals[t.y] + w.z * normals[t.z];
        if (glm::dot(n, n) == 0.0) n = core::face_normal(mesh.positions, t);
        n = glm::normalize(to_world * n);
        const glm::dvec3 p = w.x * glm::dvec3(mesh.positions[t.x]) + w.y * glm::dvec3(mesh.positions[t.y]) +
                             w.z * glm::dvec3(mesh.positions[t.z]);
        const glm::dvec3 p_world(projection.world_from_object() * glm::dvec4(p, 1.0));
        out.n_dot_l[k] = glm::dot(n, to_light(light, p_world));
    }
    return out;
}

std::vector<ToneBand> tone_bands(const SurfacePixels& surface, std::span<const double> coverage,
                                 std::span<const core::Dot> dots, const core::ToneOptions& options, int bands) {
    if (coverage.size() != surface.on_surface.size()) throw std::invalid_argument("coverage of another image size");
    std::vector<ToneBand> out(size_t(std::max(bands, 1)));
    for (size_t i = 0; i < out.size(); ++i) {
        out[i].lo = -1.0 + 2.0 * double(i) / double(out.size());
        out[i].hi = -1.0 + 2.0 * double(i + 1) / double(out.size());
    }
    const auto band_of = [&](double ndl) {
        return size_t(std::clamp(int(std::floor((ndl + 1.0) * 0.5 * double(out.size()))), 0, int(out.size()) - 1));
    };
    for (int y = 0; y < surface.image.height; ++y) {
        for (int x = 0; x < surface.image.width; ++x) {
            if (!surface.interior(x, y)) continue;
            const size_t k = size_t(y) * size_t(surface.image.width) + size_t(x);
            const double ndl = surface.n_dot_l[k];
            ToneBand& band = out[band_of(ndl)];
            band.pixels += 1;
            band.target += core::tone_of(ndl, options);
            band.coverage += coverage[k];
        }
    }
    for (const core::Dot& dot : dots) {
        const int x = int(std::floor(dot.point_px.x)), y = int(std::floor(dot.point_px.y));
        if (!surface.interior(x, y)) continue;
        const size_t k = size_t(y) * size_t(surface.image.width) + size_t(x);
        out[band_of(surface.n_dot_l[k])].fill += std::numbers::pi * dot.radius_px * dot.radius_px;
    }
    for (ToneBand& band : out) {
        if (band.pixels == 0) continue;
        band.target /= double(band.pixels);
        band.coverage /= double(band.pixels);
        band.fill /= double(band.pixels);
    }
    return out;
}

std::string band_table(std::span<const ToneBand> bands) {
    std::string out = "  N.L band         pixels   target  coverage   error     fill\n";
    char line[128];
    for (const ToneBand& band : bands) {
        std::snprintf(line, sizeof line, "  [%+.2f, %+.2f)  %8zu   %.4f   %.4f   %+6.1f%%   %.4f\n", band.lo, band.hi,
                      band.pixels, band.target, band.coverage, 100.0 * band.relative_error(), band.fill);
        out += line;
    }
    return out;
}

}  // namespace inkline::test
