// SPDX-License-Identifier: MIT
#include "core/strokes/bezier_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <span>
#include <unordered_map>

namespace inkline::core {
namespace {

using glm::dvec2;

// A ring turning sharper than this at a vertex keeps a corner there (pointed tips); round caps
// turn by at most OutlineOptions::join_step_deg per vertex and stay smooth.
constexpr double kCornerDeg = 60.0;
// Ring edges are checked (and fitted) at points this far apart at most, so curves cannot bulge
// away between sparse vertices of simplified straight stretches.
constexpr double kCheckSpacingPx = 1.0;
// Newton reparameterization rounds before a piece is split.
constexpr int kNewtonRounds = 4;
// Fits within this multiple of the tolerance are worth reparameterizing rather than splitting.
constexpr double kReparameterizeFactor = 4.0;

dvec2 bezier_d1(const CubicBezier& c, double t) {
    const double s = 1.0 - t;
    return 3.0 * (s * s * (c.p1 - c.p0) + 2.0 * s * t * (c.p2 - c.p1) + t * t * (c.p3 - c.p2));
}

dvec2 bezier_d2(const CubicBezier& c, double t) {
    return 6.0 * ((1.0 - t) * (c.p2 - 2.0 * c.p1 + c.p0) + t * (c.p3 - 2.0 * c.p2 + c.p1));
}

dvec2 unit(const dvec2& v) {
    const double len = glm::length(v);
    return len > 0.0 ? v / len : dvec2(1.0, 0.0);
}

// Chord-length parameters in [0, 1].
std::vector<double> chord_parameters(std::span<const dvec2> d) {
    std::vector<double> u(d.size(), 0.0);
    for (size_t i = 1; i < d.size(); ++i) u[i] = u[i - 1] + glm::length(d[i] - d[i - 1]);
    const double total = u.back();
    for (double& x : u) x = total > 0.0 ? x / total : 0.0;
    return u;
}

// Least-squares control points along the end tangents (Schneider's GenerateBezier).
CubicBezier generate(std::span<const dvec2> d, const std::vector<double>& u, const dvec2& t1, const dvec2& t2) {
    const dvec2 first = d.front(), last = d.back();
    double c00 = 0.0, c01 = 0.0, c11 = 0.0, x0 = 0.0, x1 = 0.0;
    for (size_t i = 0; i < d.size(); ++i) {
        const double t = u[i], s = 1.0 - t;
        const double b0 = s * s * s, b1 = 3.0 * t * s * s, b2 = 3.0 * t * t * s, b3 = t * t * t;
        const dvec2 a0 = t1 * b1, a1 = t2 * b2;
        c00 += glm::dot(a0, a0);
        c01 += glm::dot(a0, a1);
        c11 += glm::dot(a1, a1);
        const dvec2 rest = d[i] - (first * (b0 + b1) + last * (b2 + b3));
        x0 += glm::dot(a0, rest);
        x1 += glm::dot(a1, rest);
    }
    const double det = c00 * c11 - c01 * c01;
    const double span = glm::length(last - first);
    double alpha_l = 0.0, alpha_r = 0.0;
    if (std::abs(det) > 1e-12) {
        alpha_l = (x0 * c11 - x1 * c01) / det;
        alpha_r = (c00 * x1 - c01 * x0) / det;
    }
    // Degenerate or reversed handles: fall back to a third of the chord (Wu-Barsky heuristic).
    const double floor = 1e-6 * span;
    if (alpha_l < floor || alpha_r < floor) alpha_l = alpha_r = span / 3.0;
    return {first, first + t1 * alpha_l, last + t2 * alpha_r, last};
}

struct FitError {
    double squared = 0.0;
    size_t worst = 0;
};

FitError max_error(std::span<const dvec2> d, const CubicBezier& c, const std::vector<double>& u) {
    FitError e;
    for (size_t i = 1; i + 1 < d.size(); ++i) {
        const dvec2 v = c.at(u[i]) - d[i];
        const double d2 = glm::dot(v, v);
        if (d2 > e.squared) e.squared = d2, e.worst = i;
    }
    return e;
}

void reparameterize(std::span<const dvec2> d, const CubicBezier& c, std::vector<double>& u) {
    for (size_t i = 0; i < d.size(); ++i) {
        const dvec2 q = c.at(u[i]) - d[i], q1 = bezier_d1(c, u[i]), q2 = bezier_d2(c, u[i]);
        const double denominator = glm::dot(q1, q1) + glm::dot(q, q2);
        if (std::abs(denominator) > 1e-12) u[i] = std::clamp(u[i] - glm::dot(q, q1) / denominator, 0.0, 1.0);
    }
}

// Fits points d (an open piece) with tangents t1 at the start (pointing in) and t2 at the end
// (pointing back), splitting at the worst point until every point is within tolerance.
void fit_piece(std::span<const dvec2> d, const dvec2& t1, const dvec2& t2, double tolerance,
               std::vector<CubicBezier>& out) {
    if (d.size() == 2) {
        const double third = glm::length(d[1] - d[0]) / 3.0;
        out.push_back({d[0], d[0] + t1 * third, d[1] + t2 * third, d[1]});
        return;
    }
    std::vector<double> u = chord_parameters(d);
    CubicBezier curve = generate(d, u, t1, t2);
    FitError error = max_error(d, curve, u);
    const double tolerance2 = tolerance * tolerance;
    if (error.squared <= tolerance2) {
        out.push_back(curve);
        return;
    }
    if (error.squared <= kReparameterizeFactor * kReparameterizeFactor * tolerance2) {
        for (int round = 0; round < kNewtonRounds; ++round) {
            reparameterize(d, curve, u);
            curve = generate(d, u, t1, t2);
            error = max_error(d, curve, u);
            if (error.squared <= tolerance2) {
                out.push_back(curve);
                return;
            }
        }
    }
    // Split at the worst point with a tangent shared by both halves (a smooth join).
    const size_t split = std::clamp<size_t>(error.worst, 1, d.size() - 2);
    const dvec2 center = unit(d[split - 1] - d[split + 1]);
    fit_piece(d.subspan(0, split + 1), t1, center, tolerance, out);
    fit_piece(d.subspan(split), -center, t2, tolerance, out);
}

// The ring with every edge divided into pieces of at most kCheckSpacingPx; marks which points
// are ring vertices turning sharper than kCornerDeg.
struct Dense {
    std::vector<dvec2> points;
    std::vector<uint8_t> corner;
};

Dense densify(const Ring& ring) {
    Dense dense;
    const size_t n = ring.size();
    const double cos_corner = std::cos(glm::radians(kCornerDeg));
    for (size_t i = 0; i < n; ++i) {
        const dvec2 prev = ring[(i + n - 1) % n], p = ring[i], next = ring[(i + 1) % n];
        const dvec2 a = unit(p - prev), b = unit(next - p);
        dense.points.push_back(p);
        dense.corner.push_back(glm::dot(a, b) < cos_corner);
        const int steps = int(std::ceil(glm::length(next - p) / kCheckSpacingPx));
        for (int k = 1; k < steps; ++k) {
            dense.points.push_back(p + (next - p) * (double(k) / steps));
            dense.corner.push_back(0);
        }
    }
    return dense;
}

}  // namespace

glm::dvec2 CubicBezier::at(double t) const {
    const double s = 1.0 - t;
    return s * s * s * p0 + 3.0 * s * s * t * p1 + 3.0 * s * t * t * p2 + t * t * t * p3;
}

std::vector<CubicBezier> fit_cubics(const Ring& ring, double tolerance) {
    std::vector<CubicBezier> out;
    if (ring.size() < 3) return out;
    const Dense dense = densify(ring);
    const size_t m = dense.points.size();
    // Pieces run between corners; a ring without corners is cut in two smooth halves.
    std::vector<size_t> cuts;
    for (size_t i = 0; i < m; ++i) {
        if (dense.corner[i]) cuts.push_back(i);
    }
    const bool smooth = cuts.empty();
    if (smooth) cuts = {0, m / 2};
    auto point = [&](size_t i) { return dense.points[i % m]; };
    for (size_t c = 0; c < cuts.size(); ++c) {
        const size_t a = cuts[c], b = c + 1 < cuts.size() ? cuts[c + 1] : cuts[0] + m;
        std::vector<dvec2> piece;
        for (size_t i = a; i <= b; ++i) piece.push_back(point(i));
        // At a corner the tangent is one-sided; at a smooth cut it is shared by both pieces.
        const dvec2 t1 = smooth ? unit(point(a + 1) - point(a + m - 1)) : unit(point(a + 1) - point(a));
        const dvec2 t2 = smooth ? unit(point(b - 1) - point(b + 1)) : unit(point(b - 1) - point(b));
        fit_piece(piece, t1, t2, tolerance, out);
    }
    return out;
}

double fit_error_px(const Ring& ring, const std::vector<CubicBezier>& curves) {
    if (ring.empty() || curves.empty()) return 0.0;
    // The curves sampled densely on a grid of 1 px cells; the nearest sample is then refined
    // along its curve by ternary search over the neighbouring parameter interval.
    constexpr double kCell = 1.0, kStep = 0.05;
    struct Sample {
        size_t curve;
        double t, dt;
        dvec2 p;
    };
    std::unordered_map<int64_t, std::vector<Sample>> grid;
    auto key = [](int x, int y) { return (int64_t(x) << 32) ^ int64_t(uint32_t(y)); };
    for (size_t i = 0; i < curves.size(); ++i) {
        const CubicBezier& c = curves[i];
        const double length = glm::length(c.p1 - c.p0) + glm::length(c.p2 - c.p1) + glm::length(c.p3 - c.p2);
        const int steps = std::max(4, int(std::ceil(length / kStep)));
        for (int k = 0; k <= steps; ++k) {
            const double t = double(k) / steps;
            const dvec2 p = c.at(t);
            grid[key(int(std::floor(p.x / kCell)), int(std::floor(p.y / kCell)))].push_back({i, t, 1.0 / steps, p});
        }
    }
    double worst = 0.0;
    for (const dvec2& p : densify(ring).points) {
        const int cx = int(std::floor(p.x / kCell)), cy = int(std::floor(p.y / kCell));
        const Sample* nearest = nullptr;
        double best = HUGE_VAL;
        for (int radius = 1; !nearest && radius < 64; radius *= 2) {
            for (int y = cy - radius; y <= cy + radius; ++y) {
                for (int x = cx - radius; x <= cx + radius; ++x) {
                    const auto it = grid.find(key(x, y));
                    if (it == grid.end()) continue;
                    for (const Sample& q : it->second) {
                        const double d = glm::length(p - q.p);
                        if (d < best) best = d, nearest = &q;
                    }
                }
            }
        }
        if (!nearest) continue;
        const CubicBezier& c = curves[nearest->curve];
        double lo = std::max(0.0, nearest->t - nearest->dt), hi = std::min(1.0, nearest->t + nearest->dt);
        for (int round = 0; round < 40; ++round) {
            const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
            if (glm::length(c.at(m1) - p) < glm::length(c.at(m2) - p)) {
                hi = m2;
            } else {
                lo = m1;
            }
        }
        worst = std::max(worst, std::min(best, glm::length(c.at(0.5 * (lo + hi)) - p)));
    }
    return worst;
}

}  // namespace inkline::core
