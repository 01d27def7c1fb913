// SPDX-License-Identifier: MIT
#include "gl/context.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>

namespace inkline {
namespace {

// Exit code CTest reads as "skipped": only when no context can be created at all.
constexpr int kSkipReturnCode = 77;

std::unique_ptr<gl::Context> context_or_skip(gl::Backend backend) {
    try {
        return gl::create_context(backend);
    } catch (const gl::ContextError& e) {
        std::cerr << "no GL context: " << e.what() << "\n";
        std::exit(kSkipReturnCode);
    }
}

TEST(GlContext, EglGivesARenderer) {
    const auto context = context_or_skip(gl::Backend::kEgl);
    EXPECT_STREQ(context->backend_name(), "egl");
    EXPECT_FALSE(context->renderer().empty());
    std::cout << "EGL renderer: " << context->renderer() << ", " << context->version() << "\n";
}

TEST(GlContext, OsmesaGivesARenderer) {
    const auto context = context_or_skip(gl::Backend::kOsmesa);
    EXPECT_STREQ(context->backend_name(), "osmesa");
    EXPECT_FALSE(context->renderer().empty());
    EXPECT_TRUE(context->is_software());
}

}  // namespace
}  // namespace inkline
