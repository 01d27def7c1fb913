// SPDX-License-Identifier: MIT
#include "core/strokes/line_styles.h"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace inkline::core {
namespace {

// Role probes are taken about this far apart along a stroke (px).
constexpr double kRoleSpacingPx = 3.0;

template <typename T>
void set_if(const std::optional<T>& value, T& r_target) {
    if (value) r_target = *value;
}

}  // namespace

const char* line_role_name(LineRole role) { return role == LineRole::kOuter ? "outer" : "inner"; }

void BrushPatch::apply_to(BrushStyle& r_style) const {
    set_if(width_min_px, r_style.width_min_px);
    set_if(width_max_px, r_style.width_max_px);
    set_if(gamma, r_style.gamma);
    set_if(invert, r_style.invert);
    set_if(taper_px, r_style.taper_px);
    set_if(max_width_ratio, r_style.max_width_ratio);
    set_if(min_length_px, r_style.min_length_px);
    set_if(color, r_style.color);
    set_if(opacity, r_style.opacity);
    if (line_width_px) r_style.line_width_px = line_width_px;
    if (depth_width) r_style.depth_width = depth_width;
    if (curvature_width) r_style.curvature_width = curvature_width;
    set_if(dash_px, r_style.dash_px);
    set_if(cap, r_style.cap);
    set_if(texture, r_style.texture);
}

bool matches(const StyleSelector& select, const StrokeTraits& traits) {
    if (select.kinds != 0) {
        const uint8_t own = uint8_t(1u << unsigned(traits.kind));
        const uint8_t kinds = select.kinds & uint8_t(kSelectHidden - 1);
        const bool kind_ok = traits.visible ? (select.kinds & own) != 0
                                            : (select.kinds & kSelectHidden) != 0 && (kinds == 0 || (kinds & own) != 0);
        if (!kind_ok) return false;
    }
    if (select.role && (!traits.visible || *select.role != traits.role)) return false;
    if (!select.object.empty()) {
        const std::string object(traits.object);
        if (::fnmatch(select.object.c_str(), object.c_str(), 0) != 0) return false;
    }
    return true;
}

bool selects_role(std::span<const StyleRule> rules) {
    return std::any_of(rules.begin(), rules.end(), [](const StyleRule& r) { return r.select.role.has_value(); });
}

StyleSheet::StyleSheet(const BrushStyle& base, std::span<const StyleRule> rules) : rules_(rules) {
    styles_.push_back({std::string(), -1, base});
    matched_.emplace_back();
}

uint32_t StyleSheet::resolve(const StrokeTraits& traits) {
    std::vector<uint32_t> matched;
    for (size_t r = 0; r < rules_.size(); ++r) {
        if (matches(rules_[r].select, traits)) matched.push_back(uint32_t(r));
    }
    const auto found = std::find(matched_.begin(), matched_.end(), matched);
    if (found != matched_.end()) return uint32_t(found - matched_.begin());
    StrokeStyle style{rules_[matched.back()].name, int32_t(matched.back()), styles_.front().brush};
    for (const uint32_t r : matched) rules_[r].set.apply_to(style.brush);
    styles_.push_back(std::move(style));
    matched_.push_back(std::move(matched));
    return uint32_t(styles_.size() - 1);
}

BackgroundMask::BackgroundMask(const Mesh& mesh, const Projection& projection)
    : width_(projection.image().width), height_(projection.image().height) {
    covered_.assign(size_t(width_) * size_t(height_), 0);
    std::vector<glm::dvec2> px(mesh.positions.size());
    std::vector<uint8_t> in_front(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::dvec4 clip = projection.clip(glm::dvec3(mesh.positions[v]));
        in_front[v] = projection.in_front(clip);
        if (in_front[v]) px[v] = projection.pixel_from_clip(clip);
    }
    for (const glm::uvec3& tri : mesh.triangles) {
        if (!in_front[tri.x] || !in_front[tri.y] || !in_front[tri.z]) continue;
        const glm::dvec2 a = px[tri.x], b = px[tri.y], c = px[tri.z];
        const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (!(std::abs(area) > 0.0)) continue;
        // Pixel centres (x + 0.5, y + 0.5) inside or on the triangle, whichever its orientation.
        const double x0 = std::max(0.0, std::ceil(std::min({a.x, b.x, c.x}) - 0.5));
        const double x1 = std::min(double(width_ - 1), std::floor(std::max({a.x, b.x, c.x}) - 0.5));
        const double y0 = std::max(0.0, std::ceil(std::min({a.y, b.y, c.y}) - 0.5));
        const double y1 = std::min(double(height_ - 1), std::floor(std::max({a.y, b.y, c.y}) - 0.5));
        const double s = area > 0.0 ? 1.0 : -1.0;
        const auto edge = [s](const glm::dvec2& p, const glm::dvec2& q, double x, double y) {
            return s * ((q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x));
        };
        for (double y = y0; y <= y1; ++y) {
            for (double x = x0; x <= x1; ++x) {
                const double cx = x + 0.5, cy = y + 0.5;
                if (edge(a, b, cx, cy) >= 0.0 && edge(b, c, cx, cy) >= 0.0 && edge(c, a, cx, cy) >= 0.0) {
                    covered_[size_t(y) * size_t(width_) + size_t(x)] = 1;
                }
            }
        }
    }
}

bool BackgroundMask::covered(const glm::dvec2& p) const {
    if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < double(width_) && p.y < double(height_))) return false;
    return covered_[size_t(p.y) * size_t(width_) + size_t(p.x)] != 0;
}

LineRole role_of(const StrokePath& path, const BackgroundMask& background) {
    const std::vector<glm::dvec2>& p = path.points_px;
    const size_t n = p.size();
    if (n < 2) return LineRole::kInner;
    size_t probes = 0, outer = 0;
    double next = 0.0;
    for (size_t i = 0; i < n; ++i) {
        if (path.arc_px[i] + 1e-9 < next) continue;
        next = path.arc_px[i] + kRoleSpacingPx;
        const glm::dvec2 d = p[std::min(i + 1, n - 1)] - p[i > 0 ? i - 1 : 0];
        const double len = glm::length(d);
        if (!(len > 0.0)) continue;
        const glm::dvec2 normal(-d.y / len, d.x / len);
        ++probes;
        outer += !background.covered(p[i] + normal * kRoleProbePx) || !background.covered(p[i] - normal * kRoleProbePx);
    }
    return probes > 0 && 2 * outer >= probes ? LineRole::kOuter : LineRole::kInner;
}

std::vector<std::pair<double, double>> dash_intervals(std::span<const double> pattern, double u0, double u1) {
    std::vector<std::pair<double, double>> out;
    if (pattern.empty() || !(u1 >= u0)) return out;
    // An odd list repeats to make an even one, as SVG's stroke-dasharray does.
    std::vector<double> steps(pattern.begin(), pattern.end());
    if (steps.size() % 2 == 1) steps.insert(steps.end(), pattern.begin(), pattern.end());
    double period = 0.0;
    for (const double s : steps) period += s;
    if (!(period > 0.0)) return {{u0, u1}};
    double start = std::floor(u0 / period) * period;
    for (; start <= u1; start += period) {
        double at = start;
        for (size_t k = 0; k < steps.size(); k += 2) {
            const double on_end = at + steps[k];
            const double a = std::max(at, u0), b = std::min(on_end, u1);
            if (steps[k] == 0.0 ? (at >= u0 && at <= u1) : a < b) out.emplace_back(a, std::max(a, b));
            at = on_end + steps[k + 1];
        }
    }
    return out;
}

}  // namespace inkline::core
