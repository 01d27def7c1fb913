// SPDX-License-Identifier: MIT
// The built-in brush tip's properties, and tips read from PNG files.
#include "gl/brush_tip.h"

#include "core/error.h"
#include "export/png.h"
#include "tests/support/obj.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace inkline {
namespace {

namespace fs = std::filesystem;

int column(const gl::BrushTip& tip, double x) { return std::clamp(int(x * tip.width), 0, tip.width - 1); }

TEST(BrushTip, DefaultIsInkInsideTheOutlineAndFadesOutside) {
    const gl::BrushTip tip = gl::default_brush_tip();
    ASSERT_EQ(tip.alpha.size(), size_t(tip.width) * size_t(tip.height));
    const int margin = int(std::lround(tip.edge_margin * tip.height));
    ASSERT_GT(margin, 0);
    // Head and middle: every texel inside the outline is ink (alpha above one half), so the
    // preview's coverage is the outline's; outside it, less.
    const int tail_start = column(tip, 1.0 - tip.tail_fraction);
    for (int x = 0; x < tail_start; ++x) {
        for (int y = 0; y < tip.height; ++y) {
            const bool inside = y >= margin && y < tip.height - margin;
            if (inside) {
                ASSERT_GT(tip.at(x, y), 127) << x << ", " << y;
            } else {
                ASSERT_LE(tip.at(x, y), 128) << x << ", " << y;
            }
        }
    }
    EXPECT_LT(tip.at(tip.width / 2, 0), 16) << "the soft edge reaches nearly nothing at the border";
}

TEST(BrushTip, DefaultHasStreaksAndDriesTowardTheTail) {
    const gl::BrushTip tip = gl::default_brush_tip();
    const int margin = int(std::lround(tip.edge_margin * tip.height));
    auto gaps_in = [&](double x0, double x1) {
        size_t gaps = 0, all = 0;
        for (int x = column(tip, x0); x < column(tip, x1); ++x) {
            for (int y = margin; y < tip.height - margin; ++y, ++all) gaps += tip.at(x, y) < 128;
        }
        return double(gaps) / double(all);
    };
    EXPECT_EQ(gaps_in(0.0, 1.0 - tip.tail_fraction), 0.0);
    const double late = gaps_in(0.9, 1.0), early = gaps_in(1.0 - tip.tail_fraction, 0.8);
    EXPECT_GT(late, 0.3) << "dry brush: the tail's last tenth breaks up";
    EXPECT_LT(early, late);
    // Streaks: the middle varies across the stroke.
    const int x = column(tip, 0.5);
    int lo = 255, hi = 0;
    for (int y = margin + 2; y < tip.height - margin - 2; ++y) {
        lo = std::min<int>(lo, tip.at(x, y));
        hi = std::max<int>(hi, tip.at(x, y));
    }
    EXPECT_GT(hi - lo, 30);
}

TEST(BrushTip, DefaultMiddleTilesWithoutASeam) {
    // The middle repeats: its last column continues into its first as neighbouring columns do.
    const gl::BrushTip tip = gl::default_brush_tip();
    const int first = column(tip, tip.head_fraction), last = column(tip, 1.0 - tip.tail_fraction) - 1;
    auto difference = [&](int a, int b) {
        double sum = 0.0;
        for (int y = 0; y < tip.height; ++y) sum += std::abs(int(tip.at(a, y)) - int(tip.at(b, y)));
        return sum / tip.height;
    };
    EXPECT_LT(difference(last, first), 2.0 * difference(first, first + 1) + 1.0);
}

class BrushTipFile : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // A 4x2 PNG whose pixels have the given grey and alpha levels.
    fs::path write_png(const std::string& name, std::array<uint8_t, 8> grey, std::array<uint8_t, 8> alpha) {
        std::vector<uint8_t> rgba;
        for (size_t i = 0; i < 8; ++i) rgba.insert(rgba.end(), {grey[i], grey[i], grey[i], alpha[i]});
        test::write_text(dir / name, output::png_from_rgba(4, 2, rgba));
        return dir / name;
    }
};

TEST_F(BrushTipFile, BrightnessIsInk) {
    const fs::path png =
        write_png("tip.png", {0, 64, 128, 255, 255, 128, 64, 0}, {255, 255, 255, 255, 255, 255, 255, 255});
    const gl::BrushTip tip = gl::load_brush_tip(png);
    ASSERT_EQ(tip.width, 4);
    ASSERT_EQ(tip.height, 2);
    EXPECT_EQ(tip.at(0, 0), 0);
    EXPECT_EQ(tip.at(3, 0), 255);
    EXPECT_EQ(tip.at(1, 1), 128);
    EXPECT_EQ(tip.edge_margin, 0.0);
}

TEST_F(BrushTipFile, TransparencyIsInkWhenPresent) {
    // Black ink on a transparent background, as painting programs export it.
    const fs::path png = write_png("tip.png", {0, 0, 0, 0, 0, 0, 0, 0}, {0, 100, 200, 255, 255, 200, 100, 0});
    const gl::BrushTip tip = gl::load_brush_tip(png);
    EXPECT_EQ(tip.at(0, 0), 0);
    EXPECT_EQ(tip.at(2, 0), 200);
    EXPECT_EQ(tip.at(0, 1), 255);
}

TEST_F(BrushTipFile, UnreadableFilesNameThemselves) {
    test::write_text(dir / "tip.png", "not a PNG");
    for (const fs::path& bad : {dir / "tip.png", dir / "missing.png"}) {
        try {
            gl::load_brush_tip(bad);
            ADD_FAILURE() << bad << " was read";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
        }
    }
    test::write_text(dir / "dot.png", output::png_from_rgba(1, 1, std::vector<uint8_t>{255, 255, 255, 255}));
    EXPECT_THROW(gl::load_brush_tip(dir / "dot.png"), InputError) << "a single texel is no tip";
}

}  // namespace
}  // namespace inkline
