// SPDX-License-Identifier: MIT
#include "core/strokes/stroke_coherence.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <span>
#include <tuple>

#include "core/strokes/internal/sample_tree.h"
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

using internal::SampleTree;
using internal::TracedSample;

// Last frame's samples are searched in trees of one kind and visibility each, so that a search
// never reads samples it would pass over (crowds of another kind, or of strokes already matched).
size_t class_of(LineKind kind, bool visible) { return 2 * size_t(kind) + (visible ? 1 : 0); }

// The way a trace runs at a sample: from the sample before to the one after (zero for a trace
// of one sample).
glm::dvec2 tangent(const StrokeTrace& trace, size_t s) {
    const std::vector<glm::dvec2>& q = trace.samples_px;
    return q[std::min(s + 1, q.size() - 1)] - q[s > 0 ? s - 1 : 0];
}

// The samples of the traces `use` accepts, a tree for each class_of, with the angle of each
// sample's tangent when asked.
template <typename Use>
std::vector<SampleTree> class_trees(const std::vector<StrokeTrace>& traces, Use use, bool with_angles) {
    std::vector<std::vector<TracedSample>> samples(2 * kLineKindCount);
    for (size_t t = 0; t < traces.size(); ++t) {
        if (!use(t)) continue;
        std::vector<TracedSample>& to = samples[class_of(traces[t].kind, traces[t].visible)];
        for (size_t s = 0; s < traces[t].samples_px.size(); ++s) {
            to.push_back(
                {traces[t].samples_px[s], t, s, with_angles ? internal::line_angle(tangent(traces[t], s)) : NAN});
        }
    }
    std::vector<SampleTree> trees;
    for (std::vector<TracedSample>& of_class : samples) trees.emplace_back(std::move(of_class));
    return trees;
}

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
// trees: class_trees of the traces not taken; radius: this round's. Pairs whose visibility
// changed are found only when `cross` asks for them. r_hits: for each candidate searched, the
// nearest sample of its own class at each of its samples.
std::vector<Pair> overlaps(const std::vector<StrokeCandidate>& candidates, const std::vector<StrokeTrace>& traces,
                           const std::vector<SampleTree>& trees, double radius, bool cross,
                           const std::vector<uint8_t>& candidate_done, const std::vector<uint8_t>& trace_taken,
                           std::vector<std::vector<SampleTree::Hit>>& r_hits) {
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
        const SampleTree& same = trees[class_of(cand.geometry.kind, cand.geometry.visible)];
        const SampleTree& other = trees[class_of(cand.geometry.kind, !cand.geometry.visible)];
        std::vector<SampleTree::Hit>& hits = r_hits[c];
        hits.clear();
        for (const glm::dvec2& p : cand.samples_px) {
            if (!(share > 0.0)) break;
            hits.push_back(same.nearest(p, radius));
            if (hits.back().trace != size_t(-1)) add(hits.back().trace, share);
            if (!cross) continue;
            if (const SampleTree::Hit hit = other.nearest(p, radius); hit.trace != size_t(-1)) add(hit.trace, share);
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

// Distances from points to a closed polyline: the least distance_to_segment over its segments,
// as a pass over every segment finds it. Segments go in runs of kRun, each in its box; the run
// whose box lies nearest is measured first, and a run whose box lies farther than the nearest
// segment so far is passed over.
class LoopDistance {
  public:
    explicit LoopDistance(const std::vector<glm::dvec2>& loop) : loop_(loop) {
        for (size_t first = 0; first < loop.size(); first += kRun) {
            Box box{loop[first], loop[first]};
            for (size_t i = first; i <= std::min(first + kRun, loop.size()); ++i) {
                const glm::dvec2& q = loop[i % loop.size()];
                box.lo = glm::min(box.lo, q), box.hi = glm::max(box.hi, q);
            }
            boxes_.push_back(box);
        }
    }

    double operator()(const glm::dvec2& p) const {
        double best = HUGE_VAL;
        size_t nearest_run = 0;
        double nearest_d2 = HUGE_VAL;
        for (size_t r = 0; r < boxes_.size(); ++r) {
            if (const double d2 = distance2(boxes_[r], p); d2 < nearest_d2) nearest_d2 = d2, nearest_run = r;
        }
        const auto measure = [&](size_t r) {
            for (size_t i = r * kRun; i < std::min((r + 1) * kRun, loop_.size()); ++i)
                best = std::min(best, distance_to_segment(p, loop_[i], loop_[(i + 1) % loop_.size()]));
        };
        if (!boxes_.empty()) measure(nearest_run);
        for (size_t r = 0; r < boxes_.size(); ++r) {
            // A segment lies no nearer than its box; the margin is far more than rounding.
            if (r == nearest_run || distance2(boxes_[r], p) > best * best * (1.0 + 1e-9) + 1e-18) continue;
            measure(r);
        }
        return best;
    }

  private:
    static constexpr size_t kRun = 8;
    struct Box {
        glm::dvec2 lo, hi;
    };
    static double distance2(const Box& box, const glm::dvec2& p) {
        const double dx = std::max({box.lo.x - p.x, p.x - box.hi.x, 0.0});
        const double dy = std::max({box.lo.y - p.y, p.y - box.hi.y, 0.0});
        return dx * dx + dy * dy;
    }

    const std::vector<glm::dvec2>& loop_;
    std::vector<Box> boxes_;  // of each run of segments
};

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
    const LoopDistance to_last_loop(trace.samples_px);
    std::vector<double> motion(n, -1.0);
    auto motion_at = [&](size_t i) {
        if (motion[i] < 0.0) motion[i] = to_last_loop(cand.samples_px[i]);
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

// Direction and u offset of a candidate from last frame's u at its nearest samples within
// radius (px) of trace t, searched in `tree`, the tree of t's class. nearest: where given, the
// nearest sample within radius at each of the candidate's samples among a set of traces that
// holds t: where that is t's, or none, it is t's nearest too.
void propagate(const StrokeCandidate& cand, const std::vector<StrokeTrace>& traces, size_t t, const SampleTree& tree,
               double radius, std::span<const SampleTree::Hit> nearest, StrokeMatch& r_match) {
    const StrokeTrace& trace = traces[t];
    const auto of_trace = [t](size_t trace_index, size_t) { return trace_index == t; };
    std::vector<double> s, u;
    for (size_t i = 0; i < cand.samples_px.size(); ++i) {
        const bool known = i < nearest.size() && (nearest[i].trace == t || nearest[i].trace == size_t(-1));
        const SampleTree::Hit hit = known ? nearest[i] : tree.nearest(cand.samples_px[i], radius, of_trace);
        if (hit.trace == size_t(-1)) continue;
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

StrokeCoherence::StrokeCoherence() : StrokeCoherence({}, 0) {}

StrokeCoherence::StrokeCoherence(std::vector<StrokeTrace> traces, uint32_t next_id) {
    remember(std::move(traces), next_id);
}

void StrokeCoherence::remember(std::vector<StrokeTrace> traces, uint32_t next_id) {
    traces_ = std::move(traces);
    next_id_ = next_id;
    trees_ = std::make_shared<const std::vector<SampleTree>>(class_trees(traces_, [](size_t) { return true; }, true));
}

std::vector<StrokeCoherence::Nearest> StrokeCoherence::nearest_visible(const std::vector<glm::dvec2>& points_px,
                                                                       LineKind kind) const {
    std::vector<Nearest> out(points_px.size());
    if (traces_.empty()) return out;
    const SampleTree& tree = (*trees_)[class_of(kind, true)];
    for (size_t i = 0; i < points_px.size(); ++i) {
        const SampleTree::Hit hit = tree.nearest(points_px[i], kMatchRadiusPx);
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
    for (size_t i = 0; i < sides.size(); ++i) {
        const SampleTree& tree = (*trees_)[class_of(kinds[i], true)];
        // The nearest sample for each point, in order from the end inward.
        std::vector<SampleTree::Hit> hits;
        std::map<int64_t, size_t> votes;
        // Only samples of last frame running along the side: at a sharp corner, the other branch
        // lies as near. The tree passes over boxes of samples that all run across it (where
        // thousands of strokes cross the side, most of those near it).
        const glm::dvec2 along = sides[i].empty() ? glm::dvec2(0.0) : sides[i].back() - sides[i].front();
        const double reach = glm::length(along);
        auto along_side = [&](size_t t, size_t s) {
            if (reach < kSideDirectionPx || traces_[t].samples_px.size() < 2) return true;
            const glm::dvec2 d = tangent(traces_[t], s);
            return std::abs(glm::dot(along, d)) >= kSideAlongCos * reach * glm::length(d);
        };
        std::optional<internal::AngleCone> cone;
        if (reach >= kSideDirectionPx) cone = {internal::line_angle(along), std::acos(kSideAlongCos)};
        for (const glm::dvec2& p : sides[i]) {
            hits.push_back(tree.nearest(p, kMatchRadiusPx, along_side, cone));
            if (hits.back().trace != size_t(-1)) ++votes[traces_[hits.back().trace].id];
        }
        for (const auto& [id, n] : votes) {
            if (2 * n < hits.size()) continue;
            SideMemory m{.id = id};
            size_t seen = 0;
            for (const SampleTree::Hit& hit : hits) {
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
    const bool mixed =
        std::any_of(candidates.begin(), candidates.end(), [](const StrokeCandidate& c) { return !c.geometry.visible; }) ||
        std::any_of(traces_.begin(), traces_.end(), [](const StrokeTrace& t) { return !t.visible; });
    // The traces not yet taken, searched by class: all of them at first, built again once a
    // round takes any.
    const std::vector<SampleTree>* trees = trees_.get();
    std::vector<SampleTree> untaken;
    std::vector<std::vector<SampleTree::Hit>> hits(candidates.size());
    bool stale = false;
    for (const bool cross : {false, true}) {
        if (cross && !mixed) break;
        for (int round = 0; round < kMatchRounds; ++round) {
            const double radius = kMatchRadiusPx * double(1 << round);
            if (stale) {
                untaken = class_trees(traces_, [&](size_t t) { return !trace_taken[t]; }, false);
                trees = &untaken;
                stale = false;
            }
            // Largest overlaps first; ties by candidate, then trace, so the result is
            // deterministic.
            std::vector<Pair> pairs =
                overlaps(candidates, traces_, *trees, radius, cross, candidate_done, trace_taken, hits);
            if (!cross) std::erase_if(pairs, [](const Pair& p) { return p.cross; });
            std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
                return std::tie(a.cross, b.score, a.candidate, a.trace) < std::tie(b.cross, a.score, b.candidate, b.trace);
            });
            for (const Pair& p : pairs) {
                if (candidate_done[p.candidate] || trace_taken[p.trace]) continue;
                candidate_done[p.candidate] = trace_taken[p.trace] = 1;
                stale = true;
                StrokeMatch& m = matches[p.candidate];
                m.id = traces_[p.trace].id;
                m.inherited = true;
                const StrokeTrace& trace = traces_[p.trace];
                propagate(candidates[p.candidate], traces_, p.trace, (*trees_)[class_of(trace.kind, trace.visible)],
                          radius, p.cross ? std::span<const SampleTree::Hit>() : hits[p.candidate], m);
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
