// SPDX-License-Identifier: MIT
// How closely two visibility results on the same chains agree: the visible length classified
// the same way and the longest run classified differently, found by sampling every chain finely
// and either looking each sample up in both results' polylines (what a user sees) or asking both
// occlusion tests directly (the test alone, without the splitter's sampling and bisection).
#pragma once

#include "core/lines/chaining.h"
#include "core/mesh/mesh.h"
#include "core/scene/camera.h"
#include "core/visibility/visibility.h"

#include <vector>

namespace inkline::test {

struct VisibilityAgreement {
    double reference_visible_px = 0.0;     // visible length in the reference result
    double candidate_visible_px = 0.0;     // visible length in the candidate result
    double visible_either_px = 0.0;        // length visible in at least one of them
    double disagree_px = 0.0;              // length visible in exactly one of them
    double longest_disagreement_px = 0.0;  // longest such run along one chain

    // Fraction of the length visible in either result that both classify the same way;
    // 1 when nothing is visible in either.
    double agreement() const;
    // Adds another frame's or view's lengths; keeps the longest run of both.
    void add(const VisibilityAgreement& other);
};

// Compares two outputs of core::split_by_visibility over the same chains and projection.
// Each chain segment is sampled at midpoints of steps at most step_px long; a sample counts as
// visible in a result when it lies on one of that result's visible polyline segments of the
// same mesh edge. Samples outside the image or behind the near plane are skipped and end runs.
VisibilityAgreement compare_visibility(const std::vector<core::Chain>& chains, const core::Mesh& mesh,
                                       const core::Projection& projection,
                                       const std::vector<core::Polyline>& reference,
                                       const std::vector<core::Polyline>& candidate, double step_px = 0.25);

// Compares two occlusion tests directly on the same samples: a sample is visible for a test
// when it lies inside the image, in front of the near plane and the test finds it unoccluded.
VisibilityAgreement compare_occlusion(const std::vector<core::Chain>& chains, const core::Mesh& mesh,
                                      const core::Projection& projection, const core::Occlusion& reference,
                                      const core::Occlusion& candidate, double step_px = 0.25);

}  // namespace inkline::test
