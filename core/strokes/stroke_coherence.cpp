// SPDX-License-Identifier: MIT
#include "core/strokes/stroke_coherence.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <tuple>
#include <type_traits>

#include "core/internal/point_grid.h"
#include "core/strokes/stroke_path.h"

namespace inkline::core {
namespace {

// Matching rounds; each doubles the radius of the one before.
constexpr int kMatchRounds = 3;
// A side whose samples span at least this (px) has a direction: last frame's samples count for it
// only where they run within acos(kSideAlongCos) of it, either way.
constexpr double kSideDirectionPx = 6.0;
constexpr double kSideAlongCos = 0.5;
// Loop starts are placed to 1/8 of the sample spacing.
constexpr int kStartSubdivisions = 8;
// A loop start moves to a steadier place when the move pays off within this many frames.
constexpr double kStartLookahead = 30.0;
// The outline's motion is judged over this length (px) either side of a start, so that a
// single crossing of last frame's outline does not count as standing still.
constexpr double kStartMotionWindowPx = 24.0;

// Cells of the sample grid per match radius. The nearest sample is searched ring by ring from
// the query's cell, and the search stops at the first ring beyond the nearest found: where last
// frame's strokes crowd the image (a noisy scan draws tens of thousands), it so looks at the few
// samples next to the query rather than all within the radius.
constexpr int kCellsPerRadius = 3;

// Last frame's samples on a grid of cells a third of the radius.
class SampleGrid {
  public:
    SampleGrid(const std::vector<StrokeTrace>& traces, double radius)
        : traces_(traces), radius_(radius), grid_(radius / kCellsPerRadius) {
        for (size_t t = 0; t < traces.size(); ++t) {
            for (size_t s = 0; s < traces[t].samples_px.size(); ++s) grid_.add(traces[t].samples_px[s], {t, s});
        }
        grid_.sort();
    }

    struct Hit {
        size_t trace = size_t(-1), sample = 0;
        double distance = HUGE_VAL;
    };

    // Nearest sample within the radius among traces accepted by `use`; ties go to the lower
    // (trace, sample).
    template <typename Filter>
    Hit nearest(const glm::dvec2& p, Filter use) const {
        Hit best;
        const double cell = grid_.cell_px();
        const auto more = [&](int ring) {
            return !(best.distance < double(ring) * cell - Grid::kRingSlack);
        };
        grid_.rings(p, kCellsPerRadius + 1, [&](const std::pair<size_t, size_t>& ts) {
            const auto [trace, sample] = ts;
            if constexpr (std::is_invocable_v<Filter, size_t, size_t>) {
                if (!use(trace, sample)) return;
            } else {
                if (!use(trace)) return;
            }
            const double d = glm::length(traces_[trace].samples_px[sample] - p);
            const bool better =
                d < best.distance || (d == best.distance && std::tie(trace, sample) < std::tie(best.trace, best.sample));
            if (d <= radius_ && better) best = {trace, sample, d};
        }, more);
        return best;
    }

  private:
    const std::vector<StrokeTrace>& traces_;
    double radius_;
    using Grid = internal::PointGrid<std::pair<size_t, size_t>>;  // (trace, sample)
    Grid grid_;
};

// Strokes of one kind match; a hidden part that comes into view (or a visible one that goes
// behind) is the same line, so visibility may change, but such pairs come after every pair of
// the same visibility (a hidden line may run right behind a visible one).
bool compatible(const StrokeCandidate& c, const StrokeTrace& t) { return c.geometry.kind == t.kind; }
bool crosses(const StrokeCandidate& c, const StrokeTrace& t) { return c.geometry.visible != t.visible; }

struct Pair {
    size_t candidate, trace;
    double score;
    bool cross;  // the visibility changed
};

// Overlap (px) of every candidate with every compatible trace it touches.
std::vector<Pair> overlaps(const std::vector<StrokeCandidate>& candidates, const std::vector<StrokeTrace>& traces,
                           const SampleGrid& grid, const std::vector<uint8_t>& candidate_done,
                           const std::vector<uint8_t>& trace_taken) {
    // (edge, trace) pairs, sorted, to look up the traces that used an edge.
    std::vector<std::pair<uint32_t, size_t>> edge_owner;
    for (size_t t = 0; t < traces.size(); ++t) {
        if (trace_taken[t]) continue;
        for (uint32_t e : traces[t].edges) edge_owner.emplace_back(e, t);
    }
    std::sort(edge_owner.begin(), edge_owner.end());

    std::vector<Pair> pairs;
    std::vector<double> score(traces.size(), 0.0);
    std::vector<size_t> touched;
    for (size_t c = 0; c < candidates.size(); ++c) {
        if (candidate_done[c]) continue;
        const StrokeCandidate& cand = candidates[c];
        const auto use_same = [&](size_t t) {
            return !trace_taken[t] && compatible(cand, traces[t]) && !crosses(cand, traces[t]);
        };
        const auto use_cross = [&](size_t t) {
            return !trace_taken[t] && compatible(cand, traces[t]) && crosses(cand, traces[t]);
        };
        auto add = [&](size_t t, double amount) {
            if (score[t] == 0.0) touched.push_back(t);
            score[t] += amount;
        };
        // Shared mesh edges count with their image length.
        const std::vector<uint32_t>& edges = cand.geometry.edges;
        const std::vector<glm::dvec2>& points = cand.geometry.points_px;
        for (size_t s = 0; s < edges.size(); ++s) {
            auto it = std::lower_bound(edge_owner.begin(), edge_owner.end(), std::make_pair(edges[s], size_t(0)));
            if (it == edge_owner.end() || it->first != edges[s]) continue;
            const double length = glm::length(points[s + 1] - points[s]);
            for (; it != edge_owner.end() && it->first == edges[s]; ++it) {
                if (compatible(cand, traces[it->second]) && length > 0.0) add(it->second, length);
            }
        }
        // Samples count with their share of the length where last frame's nearest stroke lies
        // close: the nearest of the same visibility, and the nearest of the other.
        const double share = cand.samples_px.empty() ? 0.0 : cand.length_px / double(cand.samples_px.size());
        for (const glm::dvec2& p : cand.samples_px) {
            for (const SampleGrid::Hit& hit : {grid.nearest(p, use_same), grid.nearest(p, use_cross)}) {
                if (hit.trace != size_t(-1) && share > 0.0) add(hit.trace, share);
            }
        }
        std::sort(touched.begin(), touched.end());
        for (size_t t : touched) {
            const double shorter = std::min(cand.length_px, traces[t].length_px);
            if (score[t] >= kMinOverlapFraction * shorter) pairs.push_back({c, t, score[t], crosses(cand, traces[t])});
            score[t] = 0.0;
        }
        touched.clear();
    }
    return pairs;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(mid), v.end());
    return v[mid];
}

// Distance from p to a closed polyline.
double distance_to_loop(const glm::dvec2& p, const std::vector<glm::dvec2>& loop) {
    double best = HUGE_VAL;
    for (size_t i = 0; i < loop.size(); ++i)
        best = std::min(best, distance_to_segment(p, loop[i], loop[(i + 1) % loop.size()]));
    return best;
}

// The loop's new start, within kMatchRadiusPx of last frame's: the point that costs least now
// (its distance from last frame's start) plus later (kStartLookahead frames of the motion the
// loop made around it since last frame, averaged over kStartMotionWindowPx either side). The
// start so stays put where the outline stands still and slides off the parts that sweep. A
// start anchored last frame, before any motion was known, may move anywhere on the loop once.
std::optional<glm::dvec2> loop_start(const StrokeCandidate& cand, const StrokeTrace& trace) {
    const size_t n = cand.samples_px.size();
    if (n == 0 || trace.samples_px.empty()) return std::nullopt;
    const auto reach = std::ptrdiff_t(kStartMotionWindowPx / kTraceSpacingPx);
    const auto sn = std::ptrdiff_t(n);
    auto wrap = [sn](std::ptrdiff_t i) { return size_t(((i % sn) + sn) % sn); };
    // Motion at samples near last frame's start, computed once each.
    std::vector<double> motion(n, -1.0);
    auto motion_at = [&](size_t i) {
        if (motion[i] < 0.0) motion[i] = distance_to_loop(cand.samples_px[i], trace.samples_px);
        return motion[i];
    };
    auto mean_motion = [&](size_t i) {
        double sum = 0.0;
        for (std::ptrdiff_t k = -reach; k <= reach; ++k) sum += motion_at(wrap(std::ptrdiff_t(i) + k));
        return sum / double(2 * reach + 1);
    };

    const double slide = trace.start_anchored ? HUGE_VAL : kMatchRadiusPx;
    std::optional<glm::dvec2> best, nearest;
    double best_cost = HUGE_VAL, nearest_d = HUGE_VAL;
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = cand.samples_px[i], b = cand.samples_px[(i + 1) % n];
        if (std::min(glm::length(a - trace.start_px), glm::length(b - trace.start_px)) > slide + kTraceSpacingPx) {
            // Far from last frame's start: only the fallback (nearest point) can lie here.
            const double d = distance_to_segment(trace.start_px, a, b);
            if (d < nearest_d) nearest_d = d, nearest = a;
            continue;
        }
        const double m0 = mean_motion(i), m1 = mean_motion((i + 1) % n);
        for (int k = 0; k < kStartSubdivisions; ++k) {
            const double f = double(k) / kStartSubdivisions;
            const glm::dvec2 p = a + (b - a) * f;
            const double d = glm::length(p - trace.start_px);
            if (d < nearest_d) nearest_d = d, nearest = p;
            if (d > slide) continue;
            const double cost = d + kStartLookahead * (m0 + (m1 - m0) * f);
            if (cost < best_cost) best_cost = cost, best = p;
        }
    }
    return best ? best : nearest;
}

// Direction and u offset of a candidate from last frame's u at its nearest samples.
void propagate(const StrokeCandidate& cand, const StrokeTrace& trace, size_t trace_index, const SampleGrid& grid,
               StrokeMatch& r_match) {
    std::vector<double> s, u;
    std::vector<uint8_t> matched(cand.samples_px.size(), 0);
    for (size_t i = 0; i < cand.samples_px.size(); ++i) {
        const SampleGrid::Hit hit = grid.nearest(cand.samples_px[i], [&](size_t t) { return t == trace_index; });
        if (hit.trace == size_t(-1)) continue;
        matched[i] = 1;
        s.push_back(cand.samples_arc[i]);
        u.push_back(trace.samples_u[hit.sample]);
    }
    if (u.empty()) return;
    // Unwrap last frame's u around a loop so neighbours differ by about the sample spacing.
    const double period = trace.closed ? trace.length_px : 0.0;
    double flow = 0.0;
    for (size_t i = 1; i < u.size(); ++i) {
        double du = u[i] - u[i - 1];
        if (period > 0.0) du -= period * std::round(du / period);
        u[i] = u[i - 1] + du;
        flow += du;
    }
    r_match.reverse = flow < 0.0;
    if (r_match.reverse) {
        for (double& a : s) a = cand.length_px - a;
    }
    std::vector<double> offsets(u.size());
    for (size_t i = 0; i < u.size(); ++i) offsets[i] = u[i] - s[i];
    r_match.u_offset = median(std::move(offsets));
    if (cand.geometry.closed && trace.closed) r_match.start_px = loop_start(cand, trace);
}

}  // namespace

StrokeCoherence::StrokeCoherence(std::vector<StrokeTrace> traces, uint32_t next_id)
    : traces_(std::move(traces)), next_id_(next_id) {}

void StrokeCoherence::remember(std::vector<StrokeTrace> traces, uint32_t next_id) {
    traces_ = std::move(traces);
    next_id_ = next_id;
}

std::vector<StrokeCoherence::Nearest> StrokeCoherence::nearest_visible(const std::vector<glm::dvec2>& points_px,
                                                                       LineKind kind) const {
    std::vector<Nearest> out(points_px.size());
    if (traces_.empty()) return out;
    const SampleGrid grid(traces_, kMatchRadiusPx);
    for (size_t i = 0; i < points_px.size(); ++i) {
        const SampleGrid::Hit hit =
            grid.nearest(points_px[i], [&](size_t t) { return traces_[t].visible && traces_[t].kind == kind; });
        if (hit.trace == size_t(-1)) continue;
        const StrokeTrace& t = traces_[hit.trace];
        out[i] = {int64_t(t.id), t.samples_u[hit.sample], t.closed ? t.length_px : 0.0};
    }
    return out;
}

std::vector<glm::dvec2> side_samples(const std::vector<glm::dvec2>& points_px, int end) {
    std::vector<glm::dvec2> pts = points_px;
    if (end == 1) std::reverse(pts.begin(), pts.end());
    std::vector<glm::dvec2> out;
    if (pts.size() < 2) return out;
    // Where the stroke first gets each kSideSpacingPx farther from its end: a zig-zag tangle
    // that runs back and forth near the end is passed over, not sampled.
    const glm::dvec2 origin = pts.front();
    double next = kSideSpacingPx;
    for (size_t i = 0; i + 1 < pts.size() && next <= kSideReachPx; ++i) {
        const glm::dvec2 a = pts[i], d = pts[i + 1] - pts[i];
        // Solve |a + t d - origin| = next for the larger root t in [0, 1], while one exists.
        while (next <= kSideReachPx && glm::length(pts[i + 1] - origin) >= next) {
            const glm::dvec2 f = a - origin;
            const double qa = glm::dot(d, d), qb = 2.0 * glm::dot(f, d), qc = glm::dot(f, f) - next * next;
            const double t = qa > 0.0 ? (-qb + std::sqrt(std::max(0.0, qb * qb - 4.0 * qa * qc))) / (2.0 * qa) : 1.0;
            out.push_back(a + d * std::clamp(t, 0.0, 1.0));
            next += kSideSpacingPx;
        }
    }
    if (out.empty()) out.push_back(0.5 * (pts.front() + pts.back()));
    return out;
}

namespace {

// The shorter way from u0 to u1 along a stroke (signed, px): on a loop, u wraps at period.
double u_step(double u0, double u1, double period) {
    double du = u1 - u0;
    if (period > 0.0) du -= period * std::round(du / period);
    return du;
}

// Which way u runs from a side's end inward: +1, -1, or 0 where it barely changes.
int heading(const SideMemory& m) {
    const double du = u_step(m.u, m.u_far, m.period);
    return std::abs(du) < kSideSpacingPx ? 0 : (du > 0.0 ? 1 : -1);
}

}  // namespace

std::optional<double> continuation_fit(const std::vector<SideMemory>& a, const std::vector<SideMemory>& b,
                                       double path_px, SideHeadings headings) {
    std::optional<double> best;
    for (const SideMemory& ma : a) {
        for (const SideMemory& mb : b) {
            if (ma.id != mb.id) continue;
            if (std::abs(u_step(ma.u, mb.u, ma.period)) > path_px + 2.0 * kSideReachPx) continue;
            if (headings == SideHeadings::kOpposite && (heading(ma) == 0 || heading(ma) != -heading(mb))) continue;
            if (headings == SideHeadings::kSame && (heading(ma) == 0 || heading(ma) != heading(mb))) continue;
            const double fit = ma.distance + mb.distance;
            if (!best || fit < *best) best = fit;
        }
    }
    return best;
}

std::vector<std::vector<SideMemory>> StrokeCoherence::side_memory(const std::vector<std::vector<glm::dvec2>>& sides,
                                                                  const std::vector<LineKind>& kinds) const {
    std::vector<std::vector<SideMemory>> out(sides.size());
    if (traces_.empty()) return out;
    const SampleGrid grid(traces_, kMatchRadiusPx);
    for (size_t i = 0; i < sides.size(); ++i) {
        // The nearest sample for each point, in order from the end inward.
        std::vector<SampleGrid::Hit> hits;
        std::map<int64_t, size_t> votes;
        // Only samples of last frame running along the side: at a sharp corner, the other branch
        // lies as near.
        const glm::dvec2 along = sides[i].empty() ? glm::dvec2(0.0) : sides[i].back() - sides[i].front();
        const double reach = glm::length(along);
        auto along_side = [&](size_t t, size_t s) {
            const StrokeTrace& trace = traces_[t];
            if (!trace.visible || trace.kind != kinds[i]) return false;
            const std::vector<glm::dvec2>& q = trace.samples_px;
            if (reach < kSideDirectionPx || q.size() < 2) return true;
            const glm::dvec2 tangent = q[std::min(s + 1, q.size() - 1)] - q[s > 0 ? s - 1 : 0];
            return std::abs(glm::dot(along, tangent)) >= kSideAlongCos * reach * glm::length(tangent);
        };
        for (const glm::dvec2& p : sides[i]) {
            hits.push_back(grid.nearest(p, along_side));
            if (hits.back().trace != size_t(-1)) ++votes[traces_[hits.back().trace].id];
        }
        for (const auto& [id, n] : votes) {
            if (2 * n < hits.size()) continue;
            SideMemory m{.id = id};
            size_t seen = 0;
            for (const SampleGrid::Hit& hit : hits) {
                if (hit.trace == size_t(-1) || traces_[hit.trace].id != id) continue;
                const StrokeTrace& t = traces_[hit.trace];
                if (seen++ == 0) m.u = t.samples_u[hit.sample], m.period = t.closed ? t.length_px : 0.0;
                m.u_far = t.samples_u[hit.sample];
                m.distance += hit.distance;
            }
            m.distance /= double(seen);
            out[i].push_back(m);
        }
    }
    return out;
}

std::vector<int64_t> StrokeCoherence::nearest_visible_ids(const std::vector<glm::dvec2>& points_px,
                                                          LineKind kind) const {
    std::vector<int64_t> out;
    for (const Nearest& n : nearest_visible(points_px, kind)) out.push_back(n.id);
    return out;
}

std::vector<StrokeMatch> StrokeCoherence::match(const std::vector<StrokeCandidate>& candidates) const {
    std::vector<StrokeMatch> matches(candidates.size());
    std::vector<uint8_t> candidate_done(candidates.size(), 0), trace_taken(traces_.size(), 0);
    // Close matches first; what is left is matched again over a wider radius, for lines that
    // sweep fast (a silhouette turning edge-on). Every round keeps the visibility before any
    // round lets it change: a line coming into view can sweep fast too, and a small hidden piece
    // near last frame's stroke must not take its id in a close round.
    std::vector<SampleGrid> grids;
    grids.reserve(kMatchRounds);
    for (int round = 0; round < kMatchRounds; ++round) grids.emplace_back(traces_, kMatchRadiusPx * double(1 << round));
    const bool mixed =
        std::any_of(candidates.begin(), candidates.end(), [](const StrokeCandidate& c) { return !c.geometry.visible; }) ||
        std::any_of(traces_.begin(), traces_.end(), [](const StrokeTrace& t) { return !t.visible; });
    for (const bool cross : {false, true}) {
        if (cross && !mixed) break;
        for (const SampleGrid& grid : grids) {
            // Largest overlaps first; ties by candidate, then trace, so the result is
            // deterministic.
            std::vector<Pair> pairs = overlaps(candidates, traces_, grid, candidate_done, trace_taken);
            if (!cross) std::erase_if(pairs, [](const Pair& p) { return p.cross; });
            std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
                return std::tie(a.cross, b.score, a.candidate, a.trace) < std::tie(b.cross, a.score, b.candidate, b.trace);
            });
            for (const Pair& p : pairs) {
                if (candidate_done[p.candidate] || trace_taken[p.trace]) continue;
                candidate_done[p.candidate] = trace_taken[p.trace] = 1;
                StrokeMatch& m = matches[p.candidate];
                m.id = traces_[p.trace].id;
                m.inherited = true;
                propagate(candidates[p.candidate], traces_[p.trace], p.trace, grid, m);
            }
        }
    }
    uint32_t next = next_id_;
    for (size_t c = 0; c < candidates.size(); ++c) {
        if (!candidate_done[c]) matches[c].id = next++;
    }
    return matches;
}

}  // namespace inkline::core
