// SPDX-License-Identifier: MIT
#include "tests/support/agreement.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace inkline::test {
namespace {

// A sample lies on an output segment when its distance to it is below this: both are exact
// projections of points on the same straight mesh edge, so only rounding separates them.
constexpr double kOnSegmentPx = 1e-3;

// The midpoint of one step along a chain; `length_px` is 0 for steps not wholly in view.
struct Sample {
    glm::dvec3 p_object;
    glm::dvec2 p_px;
    uint32_t edge;
    double length_px;
};

// Each chain's samples, in order; a step outside the view breaks runs.
std::vector<std::vector<Sample>> sample_chains(const std::vector<core::Chain>& chains, const core::Mesh& mesh,
                                               const core::Projection& projection, double step_px) {
    auto seen = [&](const glm::dvec3& p, glm::dvec2& r_px) {
        const glm::dvec4 clip = projection.clip(p);
        if (!projection.in_front(clip)) return false;
        r_px = projection.pixel_from_clip(clip);
        return projection.inside_image(r_px);
    };
    std::vector<std::vector<Sample>> out(chains.size());
    for (size_t c = 0; c < chains.size(); ++c) {
        const core::Chain& chain = chains[c];
        for (size_t s = 0; s < chain.edges.size(); ++s) {
            const glm::dvec3 a(mesh.positions[chain.vertices[s]]), b(mesh.positions[chain.vertices[s + 1]]);
            glm::dvec2 a_px, b_px;
            const bool both_seen = seen(a, a_px) && seen(b, b_px);
            const double len = both_seen ? glm::length(b_px - a_px) : 64.0 * step_px;
            const int n = std::clamp(int(std::ceil(len / step_px)), 1, 1 << 16);
            glm::dvec2 prev_px;
            bool prev_seen = seen(a, prev_px);
            for (int k = 0; k < n; ++k) {
                glm::dvec2 next_px, mid_px;
                const bool next_seen = seen(a + (b - a) * (double(k + 1) / n), next_px);
                const glm::dvec3 mid = a + (b - a) * ((k + 0.5) / n);
                const bool counted = seen(mid, mid_px) && prev_seen && next_seen;
                out[c].push_back({mid, mid_px, chain.edges[s], counted ? glm::length(next_px - prev_px) : 0.0});
                prev_px = next_px;
                prev_seen = next_seen;
            }
        }
    }
    return out;
}

// Tallies lengths and runs; visible(c, k, r_ref, r_cand) classifies sample k of chain c.
template <typename Classify>
VisibilityAgreement tally(const std::vector<core::Chain>& chains, const std::vector<std::vector<Sample>>& samples,
                          const Classify& classify) {
    VisibilityAgreement out;
    for (size_t c = 0; c < chains.size(); ++c) {
        double run = 0.0;        // current disagreeing run
        double first_run = 0.0;  // the run the chain starts with, joined to the last if closed
        bool in_first_run = true;
        auto end_run = [&] {
            if (in_first_run) first_run = run;
            in_first_run = false;
            run = 0.0;
        };
        for (size_t k = 0; k < samples[c].size(); ++k) {
            const double piece = samples[c][k].length_px;
            if (piece == 0.0) {
                end_run();
                continue;
            }
            bool in_ref = false, in_cand = false;
            classify(c, k, in_ref, in_cand);
            if (in_ref) out.reference_visible_px += piece;
            if (in_cand) out.candidate_visible_px += piece;
            if (in_ref || in_cand) out.visible_either_px += piece;
            if (in_ref != in_cand) {
                out.disagree_px += piece;
                run += piece;
                out.longest_disagreement_px = std::max(out.longest_disagreement_px, run);
            } else {
                end_run();
            }
        }
        // A closed chain's last run continues into its first.
        if (chains[c].closed && !in_first_run) {
            out.longest_disagreement_px = std::max(out.longest_disagreement_px, run + first_run);
        }
    }
    return out;
}

struct Segment {
    glm::dvec2 a, b;  // px
};

// Visible output segments of each mesh edge.
using SegmentIndex = std::unordered_map<uint32_t, std::vector<Segment>>;

SegmentIndex index_visible(const std::vector<core::Polyline>& lines) {
    SegmentIndex index;
    for (const core::Polyline& line : lines) {
        if (!line.visible) continue;
        for (size_t i = 0; i < line.edges.size(); ++i) {
            index[line.edges[i]].push_back({line.points_px[i], line.points_px[i + 1]});
        }
    }
    return index;
}

bool visible_in(const SegmentIndex& index, uint32_t edge, const glm::dvec2& p_px) {
    const auto it = index.find(edge);
    if (it == index.end()) return false;
    for (const Segment& s : it->second) {
        const glm::dvec2 d = s.b - s.a;
        const double len2 = glm::dot(d, d);
        if (len2 == 0.0) continue;
        const double u = glm::dot(p_px - s.a, d) / len2;
        if (u < 0.0 || u > 1.0) continue;
        if (glm::length(p_px - (s.a + d * u)) < kOnSegmentPx) return true;
    }
    return false;
}

}  // namespace

double VisibilityAgreement::agreement() const {
    return visible_either_px > 0.0 ? 1.0 - disagree_px / visible_either_px : 1.0;
}

void VisibilityAgreement::add(const VisibilityAgreement& other) {
    reference_visible_px += other.reference_visible_px;
    candidate_visible_px += other.candidate_visible_px;
    visible_either_px += other.visible_either_px;
    disagree_px += other.disagree_px;
    longest_disagreement_px = std::max(longest_disagreement_px, other.longest_disagreement_px);
}

VisibilityAgreement compare_visibility(const std::vector<core::Chain>& chains, const core::Mesh& mesh,
                                       const core::Projection& projection,
                                       const std::vector<core::Polyline>& reference,
                                       const std::vector<core::Polyline>& candidate, double step_px) {
    const SegmentIndex ref_index = index_visible(reference);
    const SegmentIndex cand_index = index_visible(candidate);
    const std::vector<std::vector<Sample>> samples = sample_chains(chains, mesh, projection, step_px);
    return tally(chains, samples, [&](size_t c, size_t k, bool& r_ref, bool& r_cand) {
        const Sample& s = samples[c][k];
        r_ref = visible_in(ref_index, s.edge, s.p_px);
        r_cand = visible_in(cand_index, s.edge, s.p_px);
    });
}

VisibilityAgreement compare_occlusion(const std::vector<core::Chain>& chains, const core::Mesh& mesh,
                                      const core::Projection& projection, const core::Occlusion& reference,
                                      const core::Occlusion& candidate, double step_px) {
    const std::vector<std::vector<Sample>> samples = sample_chains(chains, mesh, projection, step_px);
    // Both tests in one batch each over the samples in view, as split_by_visibility asks them.
    std::vector<core::OcclusionQuery> queries;
    std::vector<std::vector<size_t>> query_of(samples.size());
    for (size_t c = 0; c < samples.size(); ++c) {
        for (const Sample& s : samples[c]) {
            query_of[c].push_back(queries.size());
            if (s.length_px > 0.0) queries.push_back({s.p_object, s.edge});
        }
    }
    std::vector<uint8_t> ref_hidden(queries.size()), cand_hidden(queries.size());
    reference.occluded(projection.eye_object(), queries, ref_hidden);
    candidate.occluded(projection.eye_object(), queries, cand_hidden);
    return tally(chains, samples, [&](size_t c, size_t k, bool& r_ref, bool& r_cand) {
        r_ref = ref_hidden[query_of[c][k]] == 0;
        r_cand = cand_hidden[query_of[c][k]] == 0;
    });
}

}  // namespace inkline::test
