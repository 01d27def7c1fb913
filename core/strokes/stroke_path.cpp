// SPDX-License-Identifier: MIT
#include "core/strokes/stroke_path.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numeric>

namespace inkline::core {
namespace {

// A function compiled twice on x86-64, once for AVX2 and once for the baseline, the one to run
// chosen where the program loads (GCC and Clang). Not under ThreadSanitizer, whose instrumented
// resolver would run before the sanitizer is set up.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__SANITIZE_THREAD__)
#define INKLINE_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define INKLINE_AVX2_CLONES
#endif

// Points closer than this (px) are the same point: visibility cuts land a hair from a vertex.
constexpr double kSamePointPx = 1e-6;
// Gaussian kernels are cut at this many sigmas (the tail weighs below 1.2%).
constexpr double kKernelSigmas = 3.0;

constexpr size_t kNone = size_t(-1);

// Unnormalised Gaussian weights for offsets 0..radius samples.
std::vector<double> gaussian_weights(double sigma, std::ptrdiff_t radius) {
    std::vector<double> weight(size_t(radius) + 1);
    for (std::ptrdiff_t k = 0; k <= radius; ++k) weight[size_t(k)] = std::exp(-0.5 * double(k * k) / (sigma * sigma));
    return weight;
}

// out[j] = c[j] w[0] + (c[j - 1] + c[j + 1]) w[1] + ... + (c[j - r] + c[j + r]) w[r] for j in [0, m),
// each sum added in order of k, a pass per k over all j so that the additions of different j
// overlap. c must reach r values before its first and after its last. The wider registers of
// AVX2, where the processor has them, do the same additions in the same order per j.
INKLINE_AVX2_CLONES void symmetric_sums(const double* c, size_t m, std::span<const double> w, double* out) {
    for (size_t j = 0; j < m; ++j) out[j] = c[j] * w[0];
    for (size_t k = 1; k < w.size(); ++k) {
        const double wk = w[k];
        const double *left = c - k, *right = c + k;
        for (size_t j = 0; j < m; ++j) out[j] += (left[j] + right[j]) * wk;
    }
}

// Cumulative arc length of a polyline.
std::vector<double> cumulative_arc(std::span<const glm::dvec2> points) {
    std::vector<double> arc(points.size(), 0.0);
    for (size_t i = 1; i < points.size(); ++i) arc[i] = arc[i - 1] + glm::length(points[i] - points[i - 1]);
    return arc;
}

// Closest point to p on the exact polyline, searched over segments whose arc range meets
// [center - radius, center + radius]; a closed polyline wraps around.
glm::dvec2 closest_on_polyline(const glm::dvec2& p, std::span<const glm::dvec2> points, std::span<const double> arc,
                               bool closed, double center, double radius) {
    const size_t segments = points.size() - 1;
    const double total = arc.back();
    glm::dvec2 best = points[0];
    double best_d = HUGE_VAL;
    auto visit = [&](size_t s) {
        const glm::dvec2 a = points[s], b = points[s + 1];
        const glm::dvec2 ab = b - a;
        const double len2 = glm::dot(ab, ab);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
        const glm::dvec2 q = a + ab * t;
        const double d = glm::length(p - q);
        if (d < best_d) best_d = d, best = q;
    };
    if (closed && 2.0 * radius >= total) {
        for (size_t s = 0; s < segments; ++s) visit(s);
        return best;
    }
    // Segments overlapping the window; a loop's window may wrap past either end.
    auto visit_range = [&](double lo, double hi) {
        auto first = std::upper_bound(arc.begin(), arc.end(), lo);
        size_t s = first == arc.begin() ? 0 : size_t(first - arc.begin()) - 1;
        for (; s < segments && arc[s] <= hi; ++s) visit(s);
    };
    visit_range(center - radius, center + radius);
    if (closed && center - radius < 0.0) visit_range(center - radius + total, total);
    if (closed && center + radius > total) visit_range(0.0, center + radius - total);
    return best;
}

}  // namespace

std::vector<size_t> remove_backtracking(std::span<const glm::dvec2> points, bool closed) {
    const size_t n = points.size();
    std::vector<size_t> kept(n);
    std::iota(kept.begin(), kept.end(), size_t(0));
    if (n < 3) return kept;
    const size_t m = closed ? n - 1 : n;  // distinct points
    if (closed && m < 3) return kept;

    // Doubly linked list over the distinct points; a loop links around.
    std::vector<size_t> prev(m), next(m);
    for (size_t i = 0; i < m; ++i) {
        prev[i] = i > 0 ? i - 1 : (closed ? m - 1 : kNone);
        next[i] = i + 1 < m ? i + 1 : (closed ? 0 : kNone);
    }
    std::vector<uint8_t> alive(m, 1);
    size_t alive_count = m;
    const double cos_backtrack = std::cos(glm::radians(kBacktrackTurnDeg));
    auto removable = [&](size_t i) {
        if (i == 0 || (!closed && i == m - 1)) return false;  // ends and a loop's seam stay
        if (closed && alive_count <= 3) return false;
        const size_t a = prev[i], b = next[i];
        const glm::dvec2 v1 = points[i] - points[a], v2 = points[b] - points[i];
        const double l1 = glm::length(v1), l2 = glm::length(v2);
        if (l1 < kSamePointPx || l2 < kSamePointPx) return true;  // a repeated point
        if (std::min(l1, l2) > kBacktrackPx) return false;
        return glm::dot(v1, v2) < cos_backtrack * l1 * l2;
    };

    // Worklist from the start; a removal re-examines both neighbours, which now meet.
    std::vector<size_t> work;
    for (size_t i = m; i-- > 1;) work.push_back(i);
    while (!work.empty()) {
        const size_t i = work.back();
        work.pop_back();
        if (!alive[i] || !removable(i)) continue;
        alive[i] = 0;
        --alive_count;
        const size_t a = prev[i], b = next[i];
        next[a] = b;
        prev[b] = a;
        work.push_back(b);
        work.push_back(a);
    }
    kept.clear();
    for (size_t i = 0; i < m; ++i) {
        if (alive[i]) kept.push_back(i);
    }
    if (closed) kept.push_back(n - 1);
    return kept;
}

double StrokePath::sample_at(double g_exact) const {
    const size_t n = g.size();
    if (n == 1) return 0.0;
    const auto it = std::upper_bound(g.begin(), g.end(), g_exact);
    if (it == g.begin()) return 0.0;
    const size_t i = size_t(it - g.begin()) - 1;
    const double g1 = i + 1 < n ? g[i + 1] : (closed ? g_end : g[i]);
    if (i + 1 >= n && !closed) return double(n - 1);
    const double f = g1 > g[i] ? std::clamp((g_exact - g[i]) / (g1 - g[i]), 0.0, 1.0) : 0.0;
    return double(i) + f;
}

double StrokePath::arc_at(double sample) const {
    const size_t n = arc_px.size();
    const size_t i = std::min(size_t(std::max(sample, 0.0)), n - 1);
    const double f = std::clamp(sample - double(i), 0.0, 1.0);
    const double next = i + 1 < n ? arc_px[i + 1] : (closed ? length_px : arc_px[i]);
    return arc_px[i] + (next - arc_px[i]) * f;
}

double StrokePath::interpolate(std::span<const double> values, double sample) const {
    const size_t n = values.size();
    const size_t i = std::min(size_t(std::max(sample, 0.0)), n - 1);
    const double f = std::clamp(sample - double(i), 0.0, 1.0);
    const size_t j = i + 1 < n ? i + 1 : (closed ? 0 : i);
    return values[i] + (values[j] - values[i]) * f;
}

StrokePath build_stroke_path(std::span<const glm::dvec2> points, bool closed, const StrokePathOptions& options) {
    StrokePath path;
    path.closed = closed;
    path.g_end = points.empty() ? 0.0 : double(points.size() - 1);
    if (points.empty()) return path;

    // Back-tracking removed: a polyline through kept exact points.
    const std::vector<size_t> kept = remove_backtracking(points, closed);
    std::vector<glm::dvec2> cleaned;
    std::vector<double> cleaned_g;
    cleaned.reserve(kept.size());
    cleaned_g.reserve(kept.size());
    for (size_t k : kept) cleaned.push_back(points[k]), cleaned_g.push_back(double(k));
    const std::vector<double> cleaned_arc = cumulative_arc(cleaned);
    const double length = cleaned_arc.back();
    if (!(length > kSamePointPx) || cleaned.size() < 2) {
        path.closed = false;
        path.points_px = {cleaned.front()};
        path.arc_px = {0.0};
        path.g = {0.0};
        return path;
    }

    // Even resampling; each sample remembers its exact parameter.
    const size_t count = size_t(std::max(1.0, std::ceil(length / options.spacing_px)));
    const double step = length / double(count);
    path.step_px = step;
    std::vector<glm::dvec2> even;
    std::vector<double> even_g;
    const size_t last = closed ? count - 1 : count;
    even.reserve(last + 2);
    even_g.reserve(last + 2);
    for (size_t j = 0, s = 0; j <= last; ++j) {
        const double a = j == count ? length : double(j) * step;
        while (s + 2 < cleaned.size() && cleaned_arc[s + 1] < a) ++s;
        const double seg = cleaned_arc[s + 1] - cleaned_arc[s];
        const double f = seg > 0.0 ? std::clamp((a - cleaned_arc[s]) / seg, 0.0, 1.0) : 0.0;
        even.push_back(cleaned[s] + (cleaned[s + 1] - cleaned[s]) * f);
        even_g.push_back(cleaned_g[s] + (cleaned_g[s + 1] - cleaned_g[s]) * f);
    }
    if (closed && even.size() < 3) {
        path.closed = false;
        closed = false;
        even.push_back(cleaned.back());
        even_g.push_back(cleaned_g.back());
    }

    // Gaussian smoothing: periodic on a loop; an open path is reflected through its end points,
    // which keeps the ends in place and straight lines straight.
    std::vector<glm::dvec2> smooth = even;
    const auto n = std::ptrdiff_t(even.size());
    if (options.smooth_px > 0.0 && n > 2) {
        const double sigma = options.smooth_px / step;
        const std::ptrdiff_t radius =
            std::min(std::ptrdiff_t(std::ceil(kKernelSigmas * sigma)), closed ? n / 2 : n - 1);
        const std::vector<double> weight = gaussian_weights(sigma, radius);
        // Padded copy: periodic on a loop, reflected through the ends of an open path.
        std::vector<glm::dvec2> padded(size_t(n + 2 * radius));
        for (std::ptrdiff_t i = -radius; i < n + radius; ++i) {
            glm::dvec2 p;
            if (closed) {
                p = even[size_t(((i % n) + n) % n)];
            } else if (i < 0) {
                p = 2.0 * even[0] - even[size_t(-i)];
            } else if (i >= n) {
                p = 2.0 * even[size_t(n - 1)] - even[size_t(2 * (n - 1) - i)];
            } else {
                p = even[size_t(i)];
            }
            padded[size_t(i + radius)] = p;
        }
        double total = weight[0];
        for (std::ptrdiff_t k = 1; k <= radius; ++k) total += 2.0 * weight[size_t(k)];
        std::vector<double> sx(static_cast<size_t>(n)), sy(static_cast<size_t>(n));
        std::vector<double> px(padded.size()), py(padded.size());
        for (size_t j = 0; j < padded.size(); ++j) px[j] = padded[j].x, py[j] = padded[j].y;
        symmetric_sums(px.data() + radius, size_t(n), weight, sx.data());
        symmetric_sums(py.data() + radius, size_t(n), weight, sy.data());
        for (std::ptrdiff_t i = 0; i < n; ++i) smooth[size_t(i)] = glm::dvec2(sx[size_t(i)], sy[size_t(i)]) / total;
    }

    // Bounded deviation: pull every sample back to within max_deviation_px of the exact polyline.
    const std::vector<double> exact_arc = cumulative_arc(points);
    const double window = kKernelSigmas * options.smooth_px + 2.0 * kBacktrackPx + options.max_deviation_px + 1.0;
    for (size_t i = 0; i < smooth.size(); ++i) {
        const double g = std::min(even_g[i], double(points.size() - 1));
        const size_t s = std::min(size_t(g), points.size() - 2);
        // The exact segment the sample came from is in the search window, so the nearest point is
        // no farther than it: within the largest deviation so far, the search would change nothing.
        if (distance_to_segment(smooth[i], points[s], points[s + 1]) <= path.deviation_px) continue;
        const double center = exact_arc[s] + (exact_arc[s + 1] - exact_arc[s]) * (g - double(s));
        const glm::dvec2 q = closest_on_polyline(smooth[i], points, exact_arc, closed, center, window);
        const double d = glm::length(smooth[i] - q);
        if (d > options.max_deviation_px) smooth[i] = q + (smooth[i] - q) * (options.max_deviation_px / d);
        path.deviation_px = std::max(path.deviation_px, std::min(d, options.max_deviation_px));
    }

    path.points_px = std::move(smooth);
    path.g = std::move(even_g);
    path.arc_px = cumulative_arc(path.points_px);
    path.length_px = path.arc_px.back();
    if (closed) path.length_px += glm::length(path.points_px.front() - path.points_px.back());
    return path;
}

double removed_extent_px(std::span<const glm::dvec2> points, const StrokePath& path) {
    const size_t n = path.points_px.size();
    if (n < 2) return points.empty() ? 0.0 : glm::length(points[0] - path.points_px[0]);
    // Search the samples within a few back-tracking lengths either side of where each exact
    // point maps (samples are at least half the spacing apart after smoothing).
    const double spacing = path.length_px / double(n);
    const auto reach = std::ptrdiff_t(std::ceil(8.0 * kBacktrackPx / std::max(spacing, 1e-3))) + 2;
    double worst = 0.0;
    for (size_t k = 0; k < points.size(); ++k) {
        const auto center = std::ptrdiff_t(path.sample_at(double(k)));
        // A segment of the window first: within the worst distance so far, this point cannot raise it.
        const auto first = std::min(center, std::ptrdiff_t(n) - 2);
        if (distance_to_segment(points[k], path.points_px[size_t(first)], path.points_px[size_t(first + 1)]) <= worst) {
            continue;
        }
        double best = HUGE_VAL;
        for (std::ptrdiff_t i = center - reach; i <= center + reach; ++i) {
            std::ptrdiff_t a = i, b = i + 1;
            if (path.closed) {
                a = ((a % std::ptrdiff_t(n)) + std::ptrdiff_t(n)) % std::ptrdiff_t(n);
                b = (a + 1) % std::ptrdiff_t(n);
            } else if (a < 0 || b >= std::ptrdiff_t(n)) {
                continue;
            }
            best = std::min(best, distance_to_segment(points[k], path.points_px[size_t(a)], path.points_px[size_t(b)]));
        }
        worst = std::max(worst, best);
    }
    return worst;
}

std::vector<double> smooth_samples(std::span<const double> values, double step_px, double sigma_px, bool closed) {
    const auto n = std::ptrdiff_t(values.size());
    std::vector<double> out(values.begin(), values.end());
    if (!(sigma_px > 0.0) || !(step_px > 0.0) || n < 3) return out;
    const double sigma = sigma_px / step_px;
    const std::ptrdiff_t radius = std::min(std::ptrdiff_t(std::ceil(kKernelSigmas * sigma)), closed ? n / 2 : n - 1);
    const std::vector<double> weight = gaussian_weights(sigma, radius);
    double full = weight[0];
    for (std::ptrdiff_t k = 1; k <= radius; ++k) full += 2.0 * weight[size_t(k)];
    // Samples whose kernel lies inside: a pass per k over them all, each sum in order of k.
    const std::ptrdiff_t inner_begin = radius, inner_end = std::max(radius, n - radius);
    symmetric_sums(values.data() + inner_begin, size_t(inner_end - inner_begin), weight, out.data() + inner_begin);
    for (std::ptrdiff_t i = inner_begin; i < inner_end; ++i) out[size_t(i)] /= full;
    // Near an end: a loop wraps around; an open path's kernel is cut there.
    auto near_end = [&](std::ptrdiff_t i) {
        double sum = values[size_t(i)] * weight[0], total = weight[0];
        for (std::ptrdiff_t k = 1; k <= radius; ++k) {
            for (const std::ptrdiff_t j : {i - k, i + k}) {
                if (!closed && (j < 0 || j >= n)) continue;
                // j lies within n of [0, n): one wrap at most (cheaper than %).
                sum += values[size_t(j < 0 ? j + n : j >= n ? j - n : j)] * weight[size_t(k)];
                total += weight[size_t(k)];
            }
        }
        out[size_t(i)] = sum / total;
    };
    for (std::ptrdiff_t i = 0; i < inner_begin; ++i) near_end(i);
    for (std::ptrdiff_t i = inner_end; i < n; ++i) near_end(i);
    return out;
}

}  // namespace inkline::core
