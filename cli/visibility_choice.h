// SPDX-License-Identifier: MIT
// Which occlusion test a render uses (`--visibility`), and why: `auto` takes the GL depth pass
// on hardware GL and CPU ray casting where GL would be a software renderer or none can be made.
#pragma once

#include "core/visibility/occlusion_source.h"
#include "gl/context.h"

#include <memory>
#include <optional>
#include <string>

namespace inkline::cli {

// --visibility: "auto" (nullopt), "gl", "raycast" or "exact". Throws InputError otherwise.
std::optional<core::VisibilityMode> parse_visibility_option(const std::string& text);

struct VisibilityChoice {
    core::VisibilityMode mode = core::VisibilityMode::kExact;
    std::string reason;                    // for FrameStats::visibility_reason and -v
    std::unique_ptr<gl::Context> context;  // for kGl; also shared by the preview
};

// The test asked for (nullopt: auto), on a context of `gl_backend` ("auto", "egl" or "osmesa")
// when it is GL. Throws InputError when the test asked for cannot run here (no Embree, no GL
// context for kGl).
VisibilityChoice choose_visibility(std::optional<core::VisibilityMode> asked, const std::string& gl_backend);

// The chosen test as the frame pipeline's occlusion provider; a GL one runs on choice.context,
// which must outlive it.
std::unique_ptr<core::OcclusionSource> make_occlusion(const VisibilityChoice& choice);

}  // namespace inkline::cli
