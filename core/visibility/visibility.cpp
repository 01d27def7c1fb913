// SPDX-License-Identifier: MIT
#include "core/visibility/visibility.h"

#include "core/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

namespace inkline::core {
namespace {

enum class State : uint8_t { kVisible, kOccluded, kOutside };

// Bisection stops after this many halvings even if the pixel bracket is still wide, which only
// happens when a bracket end lies behind the camera.
constexpr int kMaxBisections = 48;
// An intersection point drawn with smooth contours, where a closed surface it lies on faces the
// eye, is hidden only by what lies farther than this many of that surface's edges in front of it.
constexpr double kSurfaceBiasEdges = 2.0;

// The faces that cannot hide a smooth contour's segment (the face it crosses and those around its
// corners, ascending), listed when a query first asks: on a fine mesh most segments get none.
// Each list keeps its own buffer as more are added, so a query's span of it stays valid.
class OwnFaceLists {
  public:
    OwnFaceLists(const Mesh& mesh, const EdgeTable* table, const std::vector<Chain>& chains)
        : mesh_(mesh), table_(table), slots_(chains.size()) {
        for (size_t c = 0; c < chains.size(); ++c) {
            if (chains[c].faces.empty()) continue;
            INKLINE_CHECK(table_ != nullptr);  // a smooth contour needs its mesh's edge table
            slots_[c].assign(chains[c].faces.size(), kNoIndex);
        }
    }
    // Empty for a chain that is not a smooth contour.
    std::span<const uint32_t> at(const Chain& chain, size_t c, size_t segment) {
        if (slots_[c].empty()) return {};
        uint32_t& slot = slots_[c][segment];
        if (slot == kNoIndex) {
            slot = uint32_t(lists_.size());
            lists_.emplace_back();
            faces_around_corners(mesh_, *table_, chain.faces[segment], lists_.back());
        }
        return lists_[slot];
    }

  private:
    const Mesh& mesh_;
    const EdgeTable* table_;
    std::vector<std::vector<uint32_t>> slots_;  // per chain, per segment: index in lists_ or kNoIndex
    std::vector<std::vector<uint32_t>> lists_;
};

// Chain parameter: g in [0, segments]; floor(g) is the segment, the fraction the position on it.
class ChainGeometry {
  public:
    // own: where chain number `index`'s segments find their own faces.
    ChainGeometry(const Chain& chain, const Mesh& mesh, OwnFaceLists& own, size_t index)
        : chain_(chain), mesh_(mesh), own_(own), index_(index) {}

    size_t segments() const { return chain_.edges.size(); }
    size_t segment_of(double g) const {
        return std::min(size_t(std::max(g, 0.0)), segments() - 1);
    }
    glm::dvec3 point(double g) const {
        const size_t s = segment_of(g);
        const double t = g - double(s);
        const glm::dvec3 a = corner(s), b = corner(s + 1);
        return a + (b - a) * t;
    }
    uint32_t edge_at(double g) const { return chain_.edges[segment_of(g)]; }
    // The query for point p = point(g).
    OcclusionQuery query_at(double g, const glm::dvec3& p) const {
        const size_t s = segment_of(g);
        return {p, chain_.edges[s], chain_.crossing_faces.empty() ? kNoCrossingFace : chain_.crossing_faces[s],
                own_.at(chain_, index_, s)};
    }
    uint32_t face_at(double g) const { return chain_.faces[segment_of(g)]; }
    // Whether the point at g lies on the back of a closed surface as the smooth contour takes it
    // (an intersection chain with `facing`): that surface hides it. Each surface's g is linear
    // along a segment, which lies on one of its faces.
    bool behind_surface(double g) const {
        if (chain_.facing.empty()) return false;
        const size_t s = segment_of(g);
        const double t = g - double(s);
        const SegmentFacing& f = chain_.facing[s];
        for (const std::array<double, 2>& side : {f.first, f.other}) {
            if (side[0] + (side[1] - side[0]) * t > 0.0) return true;  // false for NaN: not closed
        }
        return false;
    }
    // How far in front of the point at g its occluders must lie (object units): on an
    // intersection chain with `facing`, kSurfaceBiasEdges times the longest edge of each face it
    // lies on of a closed surface, where the polygons may bulge over the smooth surface near its
    // contour (the faces around the point lie within that, as the faces around a contour point
    // are its own); 0 elsewhere.
    double surface_bias(double g) const {
        if (chain_.facing.empty()) return 0.0;
        const size_t s = segment_of(g);
        double bias = 0.0;
        auto add = [&](const std::array<double, 2>& facing, uint32_t face) {
            if (std::isnan(facing[0])) return;  // not closed
            const glm::uvec3 t = mesh_.triangles[face];
            const glm::dvec3 a(mesh_.positions[t.x]), b(mesh_.positions[t.y]), c(mesh_.positions[t.z]);
            const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
            bias = std::max(bias, kSurfaceBiasEdges * longest);
        };
        add(chain_.facing[s].first, chain_.first_faces[s]);
        add(chain_.facing[s].other, chain_.crossing_faces[s]);
        return bias;
    }
    bool smooth() const { return !chain_.faces.empty(); }
    uint32_t crossing_face_at(double g) const { return chain_.crossing_faces[segment_of(g)]; }
    bool crossing() const { return !chain_.crossing_faces.empty(); }

  private:
    glm::dvec3 corner(size_t i) const {
        return chain_.points.empty() ? glm::dvec3(mesh_.positions[chain_.vertices[i]]) : chain_.points[i];
    }

    const Chain& chain_;
    const Mesh& mesh_;
    OwnFaceLists& own_;
    size_t index_;
};

class Splitter {
  public:
    Splitter(const Mesh& mesh, const EdgeTable* table, const Projection& projection, const Occlusion& occlusion,
             const VisibilityOptions& options)
        : mesh_(mesh), table_(table), projection_(projection), occlusion_(occlusion), options_(options) {}

    std::vector<Polyline> run(const std::vector<Chain>& chains) {
        // A smooth contour point is not occluded by the face it crosses or the faces around it.
        own_faces_.emplace(mesh_, table_, chains);
        // Coarse samples of every chain, tested in one batch.
        std::vector<std::vector<double>> params(chains.size());
        std::vector<std::vector<State>> states(chains.size());
        std::vector<OcclusionQuery> queries;
        std::vector<std::pair<size_t, size_t>> query_owner;  // (chain, sample)
        for (size_t c = 0; c < chains.size(); ++c) {
            const ChainGeometry geom(chains[c], mesh_, *own_faces_, c);
            params[c] = sample_params(geom);
            states[c].resize(params[c].size());
            for (size_t i = 0; i < params[c].size(); ++i) {
                const double g = params[c][i];
                const glm::dvec3 p = geom.point(g);
                if (outside(p)) {
                    states[c][i] = State::kOutside;
                } else if (geom.behind_surface(g)) {
                    states[c][i] = State::kOccluded;
                } else {
                    queries.push_back(query(geom, g, p));
                    query_owner.emplace_back(c, i);
                }
            }
        }
        std::vector<uint8_t> hidden(queries.size(), 0);
        occlusion_.occluded(projection_.eye_object(), queries, hidden);
        for (size_t q = 0; q < queries.size(); ++q) {
            const auto [c, i] = query_owner[q];
            states[c][i] = hidden[q] ? State::kOccluded : State::kVisible;
        }

        const std::vector<std::vector<double>> cuts = locate_changes(chains, params, states);
        std::vector<Polyline> out;
        for (size_t c = 0; c < chains.size(); ++c) emit_chain(chains[c], c, params[c], states[c], cuts[c], out);
        for (size_t i = 0; i < out.size(); ++i) out[i].id = uint32_t(i);
        return out;
    }

  private:
    bool outside(const glm::dvec3& p_object) const {
        const glm::dvec4 clip = projection_.clip(p_object);
        return !projection_.in_front(clip) || !projection_.inside_image(projection_.pixel_from_clip(clip));
    }

    // The query for the point p at g, tested from surface_bias nearer the eye.
    OcclusionQuery query(const ChainGeometry& geom, double g, const glm::dvec3& p) const {
        OcclusionQuery q = geom.query_at(g, p);
        const double bias = geom.surface_bias(g);
        const glm::dvec3 to_eye = projection_.eye_object().toward(p);
        const double distance = glm::length(to_eye);
        if (bias > 0.0 && (projection_.orthographic() || distance > bias)) q.p_object = p + to_eye * (bias / distance);
        return q;
    }

    // Where the state changes between neighbouring samples, located to options_.bisection_px:
    // per chain, one cut per change, in order. Every change is bisected at once, one batch of
    // occlusion queries per halving, so that a batch runs in parallel; each change's halvings
    // depend on its own answers only, exactly as when bisected one change at a time.
    std::vector<std::vector<double>> locate_changes(const std::vector<Chain>& chains,
                                                    const std::vector<std::vector<double>>& params,
                                                    const std::vector<std::vector<State>>& states) {
        struct Bracket {
            size_t chain;
            double g0, g1;  // the change lies between; g0 has state s0
            State s0;
            int halvings = 0;
        };
        std::vector<Bracket> brackets;
        std::vector<std::vector<double>> cuts(chains.size());
        for (size_t c = 0; c < chains.size(); ++c) {
            for (size_t i = 0; i + 1 < params[c].size(); ++i) {
                if (states[c][i + 1] != states[c][i]) brackets.push_back({c, params[c][i], params[c][i + 1], states[c][i]});
            }
        }
        auto halve = [](Bracket& b, double mid, State state) {
            (state == b.s0 ? b.g0 : b.g1) = mid;
            ++b.halvings;
        };
        std::vector<size_t> active(brackets.size()), still_active, asked;
        for (size_t k = 0; k < brackets.size(); ++k) active[k] = k;
        std::vector<OcclusionQuery> queries;
        std::vector<uint8_t> hidden;
        while (!active.empty()) {
            still_active.clear();
            asked.clear();
            queries.clear();
            for (size_t k : active) {
                Bracket& b = brackets[k];
                const ChainGeometry geom(chains[b.chain], mesh_, *own_faces_, b.chain);
                if (b.halvings >= kMaxBisections || !(pixel_distance(geom, b.g0, b.g1) > options_.bisection_px)) continue;
                still_active.push_back(k);
                const double mid = 0.5 * (b.g0 + b.g1);
                const glm::dvec3 p = geom.point(mid);
                if (outside(p)) {
                    halve(b, mid, State::kOutside);
                } else if (geom.behind_surface(mid)) {
                    halve(b, mid, State::kOccluded);
                } else {
                    queries.push_back(query(geom, mid, p));
                    asked.push_back(k);
                }
            }
            hidden.assign(queries.size(), 0);
            occlusion_.occluded(projection_.eye_object(), queries, hidden);
            for (size_t q = 0; q < queries.size(); ++q) {
                Bracket& b = brackets[asked[q]];
                halve(b, 0.5 * (b.g0 + b.g1), hidden[q] ? State::kOccluded : State::kVisible);
            }
            active.swap(still_active);
        }
        for (const Bracket& b : brackets) cuts[b.chain].push_back(0.5 * (b.g0 + b.g1));
        return cuts;
    }

    // Pixel distance between two chain points; infinite when either is behind the camera.
    double pixel_distance(const ChainGeometry& geom, double g0, double g1) const {
        const glm::dvec4 c0 = projection_.clip(geom.point(g0));
        const glm::dvec4 c1 = projection_.clip(geom.point(g1));
        if (c0.w <= 0.0 || c1.w <= 0.0) return HUGE_VAL;  // w is 1 in orthographic projection
        return glm::length(projection_.pixel_from_clip(c0) - projection_.pixel_from_clip(c1));
    }

    // Sample parameters, neighbours at most sample_spacing_px apart along the chain: both ends,
    // interior samples along longer segments, and each vertex unless the segments around it are
    // so short that the next sample still lies within that spacing. Where segments are longer
    // than the spacing that is every vertex; a run of sub-spacing segments (a fine mesh, a fan's
    // rim) is sampled once per spacing, so the queries follow the drawing, not the mesh.
    std::vector<double> sample_params(const ChainGeometry& geom) const {
        const double spacing = options_.sample_spacing_px;
        std::vector<double> g;
        double since = HUGE_VAL;  // pixel length from the last sample to the current vertex
        for (size_t s = 0; s < geom.segments(); ++s) {
            const double len = pixel_distance(geom, double(s), double(s) + 1.0);
            if (!(since + len > spacing)) {
                since += len;
                continue;
            }
            // Behind-camera segments are still sampled so the near-plane crossing is found.
            const double n = std::isfinite(len) ? std::ceil(len / spacing) : 16.0;
            const int count = int(std::clamp(n, 1.0, 4096.0));
            for (int k = 0; k < count; ++k) g.push_back(double(s) + double(k) / count);
            since = len / count;
        }
        g.push_back(double(geom.segments()));
        return g;
    }

    struct Run {
        double begin, end;  // chain parameters; end < begin wraps around a closed chain
        State state;
    };

    void emit_chain(const Chain& chain, size_t index, const std::vector<double>& g, const std::vector<State>& s,
                    const std::vector<double>& cuts, std::vector<Polyline>& out) {
        const ChainGeometry geom(chain, mesh_, *own_faces_, index);
        const double g_end = double(geom.segments());
        std::vector<Run> runs;
        double begin = 0.0;
        for (size_t i = 0, change = 0; i + 1 < g.size(); ++i) {
            if (s[i + 1] == s[i]) continue;
            const double cut = cuts[change++];
            runs.push_back({begin, cut, s[i]});
            begin = cut;
        }
        runs.push_back({begin, g_end, s.back()});
        merge_short_runs(geom, runs);

        if (runs.size() == 1) {
            push(geom, chain, runs[0], chain.closed, out);
            return;
        }
        // A split loop: the last run continues through the start into the first.
        if (chain.closed && runs.front().state == runs.back().state) {
            runs.front().begin = runs.back().begin;
            runs.pop_back();
        }
        for (const Run& run : runs) push(geom, chain, run, false, out);
    }

    // Pixel length of a run along the chain (through its vertices: a zig-zag run can end near
    // where it began and still be long).
    double run_length_px(const ChainGeometry& geom, const Run& run) const {
        double length = 0.0, at = run.begin;
        for (double v = std::floor(run.begin) + 1.0; v < run.end; v += 1.0) {
            length += pixel_distance(geom, at, v);
            at = v;
        }
        return length + pixel_distance(geom, at, run.end);
    }

    // A run shorter than twice the bisection precision is below what the bisection resolves:
    // typically a hidden edge ending exactly on a visible silhouette vertex. It joins the run
    // before it (the one after it, for the first run).
    void merge_short_runs(const ChainGeometry& geom, std::vector<Run>& runs) const {
        const double min_px = 2.0 * options_.bisection_px;
        for (size_t i = 0; i < runs.size() && runs.size() > 1;) {
            if (run_length_px(geom, runs[i]) >= min_px) {
                ++i;
                continue;
            }
            if (i > 0) {
                runs[i - 1].end = runs[i].end;
            } else {
                runs[1].begin = runs[0].begin;
            }
            runs.erase(runs.begin() + std::ptrdiff_t(i));
            i = 0;  // neighbours may now share a state; coalesce below
            for (size_t j = 1; j < runs.size();) {
                if (runs[j].state == runs[j - 1].state) {
                    runs[j - 1].end = runs[j].end;
                    runs.erase(runs.begin() + std::ptrdiff_t(j));
                } else {
                    ++j;
                }
            }
        }
    }

    void push(const ChainGeometry& geom, const Chain& chain, const Run& run, bool closed,
              std::vector<Polyline>& out) const {
        if (run.state == State::kOutside) return;
        if (run.state == State::kOccluded && !options_.keep_hidden) return;
        if (run.begin == run.end) return;

        // Parameters of the output points: the run's ends and every chain vertex between them.
        // A run that wraps around a closed chain is unrolled past g == segments.
        const double n = double(geom.segments());
        const double to = run.end > run.begin ? run.end : run.end + n;
        std::vector<double> ps{run.begin};
        for (double v = std::floor(run.begin) + 1.0; v < to; v += 1.0) ps.push_back(v);
        ps.push_back(to);
        auto wrap = [n](double g) { return g > n ? g - n : g; };

        Polyline line;
        line.kind = chain.kind;
        line.closed = closed;
        line.visible = run.state == State::kVisible;
        for (double g : ps) {
            const glm::dvec3 p = geom.point(wrap(g));
            line.points_world.push_back(glm::dvec3(projection_.world_from_object() * glm::dvec4(p, 1.0)));
            line.points_px.push_back(projection_.pixel(p));
        }
        for (size_t i = 0; i + 1 < ps.size(); ++i) {
            const double mid = wrap(0.5 * (ps[i] + ps[i + 1]));
            line.edges.push_back(geom.edge_at(mid));
            if (geom.crossing()) line.crossing_faces.push_back(geom.crossing_face_at(mid));
            if (geom.smooth()) line.faces.push_back(geom.face_at(mid));
        }
        out.push_back(std::move(line));
    }

    const Mesh& mesh_;
    const EdgeTable* table_;
    const Projection& projection_;
    const Occlusion& occlusion_;
    const VisibilityOptions& options_;
    std::optional<OwnFaceLists> own_faces_;  // during run
};

}  // namespace

double occlusion_reach(const std::vector<glm::vec3>& positions) {
    const double diagonal = 2.0 * bounds_of(positions).radius();
    return diagonal > 0.0 ? kOcclusionReachDiagonals * diagonal : 1.0;
}

glm::dvec3 occlusion_segment_end(const glm::dvec3& p, const Viewpoint& eye, double reach) {
    const glm::dvec3 to_eye = eye.toward(p);
    const double length = glm::length(to_eye);
    return eye.orthographic() || length > reach ? p + to_eye * (reach / length) : eye.xyz;
}

double Polyline::length_px() const {
    double len = 0.0;
    for (size_t i = 1; i < points_px.size(); ++i) len += glm::length(points_px[i] - points_px[i - 1]);
    return len;
}

std::vector<Polyline> split_by_visibility(const std::vector<Chain>& chains, const Mesh& mesh, const EdgeTable& table,
                                          const Projection& projection, const Occlusion& occlusion,
                                          const VisibilityOptions& options) {
    return Splitter(mesh, &table, projection, occlusion, options).run(chains);
}

std::vector<Polyline> split_by_visibility(const std::vector<Chain>& chains, const Mesh& mesh,
                                          const Projection& projection, const Occlusion& occlusion,
                                          const VisibilityOptions& options) {
    return Splitter(mesh, nullptr, projection, occlusion, options).run(chains);
}

}  // namespace inkline::core
