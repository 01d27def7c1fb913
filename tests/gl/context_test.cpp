// SPDX-License-Identifier: MIT
#include "gl/context.h"

#include "tests/gl/context_or_skip.h"

#include <gtest/gtest.h>

#include <iostream>

namespace inkline {
namespace {

using test::context_or_skip;

TEST(GlContext, EglGivesARenderer) {
    const auto context = context_or_skip(gl::Backend::kEgl);
    EXPECT_STREQ(context->backend_name(), "egl");
    EXPECT_EQ(context->backend(), gl::Backend::kEgl);
    EXPECT_FALSE(context->renderer().empty());
    std::cout << "EGL renderer: " << context->renderer() << ", " << context->version() << "\n";
}

TEST(GlContext, OsmesaGivesARenderer) {
    const auto context = context_or_skip(gl::Backend::kOsmesa);
    EXPECT_STREQ(context->backend_name(), "osmesa");
    EXPECT_EQ(context->backend(), gl::Backend::kOsmesa);
    EXPECT_FALSE(context->renderer().empty());
    EXPECT_TRUE(context->is_software());
}

}  // namespace
}  // namespace inkline
