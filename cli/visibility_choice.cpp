// SPDX-License-Identifier: MIT
#include "cli/visibility_choice.h"

#include "core/error.h"
#include "core/visibility/raycast_visibility.h"
#include "gl/depth_visibility.h"

namespace inkline::cli {

std::optional<core::VisibilityMode> parse_visibility_option(const std::string& text) {
    if (text == "auto") return std::nullopt;
    if (const std::optional<core::VisibilityMode> mode = core::visibility_mode_from_name(text)) return mode;
    throw InputError("--visibility '" + quote_value(text) + "': expected auto, gl, raycast or exact");
}

VisibilityChoice choose_visibility(std::optional<core::VisibilityMode> asked, const std::string& gl_backend) {
    using core::VisibilityMode;
    VisibilityChoice choice;
    if (asked == VisibilityMode::kExact || asked == VisibilityMode::kRaycast) {
        choice.mode = *asked;
        choice.reason = "asked for";
        if (asked == VisibilityMode::kRaycast && !core::raycast_available())
            throw InputError("--visibility raycast: this build has no Embree");
        return choice;
    }
    const VisibilityMode cpu = core::raycast_available() ? VisibilityMode::kRaycast : VisibilityMode::kExact;
    const gl::Backend backend = gl::parse_backend(gl_backend);
    // Without a GPU any context is a software renderer: no need to start one to find out.
    if (!asked && core::raycast_available() && !gl::gpu_device_present()) {
        choice.mode = VisibilityMode::kRaycast;
        choice.reason = "no GPU device (/dev/dri/renderD*, /dev/nvidia*): CPU ray casting";
        return choice;
    }
    try {
        choice.context = gl::create_context(backend);
    } catch (const gl::ContextError& e) {
        if (asked) throw InputError(std::string("--visibility gl: no OpenGL context: ") + e.what());
        choice.mode = cpu;
        choice.reason = std::string("no OpenGL context (") + e.what() + ")";
        return choice;
    } catch (const OutOfMemory& e) {
        if (asked) throw;
        choice.mode = cpu;
        choice.reason = std::string("no OpenGL (") + e.what() + ")";
        return choice;
    }
    const std::string renderer = choice.context->backend_name() + std::string(": ") + choice.context->renderer();
    if (asked) {
        choice.mode = VisibilityMode::kGl;
        choice.reason = "asked for, " + renderer;
    } else if (!choice.context->is_software()) {
        choice.mode = VisibilityMode::kGl;
        choice.reason = "hardware OpenGL (" + renderer + ")";
    } else if (core::raycast_available()) {
        choice.mode = VisibilityMode::kRaycast;
        choice.reason = "software OpenGL (" + renderer + "): CPU ray casting is faster";
        choice.context.reset();
    } else {
        choice.mode = VisibilityMode::kGl;
        choice.reason = "software OpenGL (" + renderer + ") and no Embree in this build";
    }
    return choice;
}

std::unique_ptr<core::OcclusionSource> make_occlusion(const VisibilityChoice& choice) {
    if (choice.mode == core::VisibilityMode::kGl) return std::make_unique<gl::DepthOcclusionSource>(*choice.context);
    return core::make_cpu_occlusion(choice.mode);
}

}  // namespace inkline::cli
