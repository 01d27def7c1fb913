// SPDX-License-Identifier: MIT
#include "core/scene/frame_pattern.h"

#include "core/error.h"

#include <gtest/gtest.h>

namespace inkline {
namespace {

TEST(FramePattern, FormatsTheFrameField) {
    EXPECT_EQ(core::format_frame("out/frame_%04d.svg", 7), "out/frame_0007.svg");
    EXPECT_EQ(core::format_frame("%d.obj", 12), "12.obj");
    EXPECT_EQ(core::format_frame("a%3db", 5), "a  5b");
    EXPECT_EQ(core::format_frame("100%%_%02d", 3), "100%_03");
    EXPECT_EQ(core::format_frame("plain.svg", 3), "plain.svg");
}

TEST(FramePattern, DetectsFields) {
    EXPECT_TRUE(core::has_frame_field("f_%04d.json"));
    EXPECT_FALSE(core::has_frame_field("f.json"));
    EXPECT_FALSE(core::has_frame_field("100%%.json"));
}

TEST(FramePattern, RejectsMalformedFields) {
    EXPECT_THROW(core::format_frame("f_%s.svg", 1), InputError);
    EXPECT_THROW(core::format_frame("%d_%d.svg", 1), InputError);
    EXPECT_THROW(core::format_frame("f_%4", 1), InputError);
}

}  // namespace
}  // namespace inkline
