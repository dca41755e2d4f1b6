// The status line: frame rate averaging, text layout, the band's pixels.
#include <gtest/gtest.h>

#include "viewer/overlay.hpp"

namespace prism::viewer {
namespace {

TEST(FrameRate, LeavesOutTheFirstFrameThenAverages) {
  FrameRate rate;
  EXPECT_FALSE(rate.has_value());
  rate.add(900.0);  // start-up frame: ignored
  EXPECT_FALSE(rate.has_value());
  rate.add(20.0);
  ASSERT_TRUE(rate.has_value());
  EXPECT_EQ(rate.ms(), 20.0);
  EXPECT_EQ(rate.fps(), 50.0);
  rate.add(40.0);  // running mean (20 + 40) / 2 = 30
  EXPECT_EQ(rate.ms(), 30.0);
}

TEST(FrameRate, EachCompletedHalfSecondReplacesTheValue) {
  FrameRate rate;
  rate.add(1.0);
  for (int i = 0; i < 5; ++i) rate.add(100.0);  // 500 ms: window complete, mean 100
  EXPECT_EQ(rate.ms(), 100.0);
  for (int i = 0; i < 9; ++i) rate.add(50.0);  // 450 ms: window open, value kept
  EXPECT_EQ(rate.ms(), 100.0);
  rate.add(50.0);  // 500 ms: mean 50
  EXPECT_EQ(rate.ms(), 50.0);
  EXPECT_EQ(rate.fps(), 20.0);
}

TEST(StatusLine, PicksTheWidestLayoutThatFits) {
  FrameRate rate;
  EXPECT_EQ(status_line(rate, "embree", 160, 90, 100), "-- FPS  embree  160x90");
  rate.add(5.0);
  rate.add(40.0);
  EXPECT_EQ(status_line(rate, "embree", 640, 360, 100), "25.0 FPS  40.0 MS  embree  640x360");
  EXPECT_EQ(status_line(rate, "embree", 640, 360, 33), "25.0 FPS 40.0 MS embree 640x360");
  EXPECT_EQ(status_line(rate, "embree", 160, 90, 26), "25FPS 40MS embree 160x90");
  EXPECT_EQ(status_line(rate, "embree", 160, 90, 3), "25FPS 40MS embree 160x90");
}

TEST(StatusLine, CharactersThatFit) {
  // n characters need (6n - 1 + 4) * scale pixels.
  EXPECT_EQ(chars_that_fit(160, 1), 26);  // 26: 159 pixels; 27: 165
  EXPECT_EQ(chars_that_fit(159, 1), 26);
  EXPECT_EQ(chars_that_fit(158, 1), 25);
  EXPECT_EQ(chars_that_fit(640, 2), 52);  // 52: 630 pixels; 53: 642
  EXPECT_EQ(chars_that_fit(2, 1), 0);
}

TEST(Overlay, ScaleAndBand) {
  EXPECT_EQ(overlay_scale(639), 1);
  EXPECT_EQ(overlay_scale(640), 2);
  EXPECT_EQ(overlay_height(1), 11);  // 7 + 2 * 2
  EXPECT_EQ(overlay_height(2), 22);
}

TEST(Overlay, TranslucentBandWithWhiteText) {
  // "1" at scale 1: 5 + 2 * 2 = 9 wide, 11 high; the glyph starts at (2, 2),
  // its stem's top at glyph column 2 -> (4, 2).
  const Rgba8Image band = overlay_image("1", 1, 100);
  ASSERT_EQ(band.width, 9);
  ASSERT_EQ(band.height, 11);
  auto px = [&](int x, int y) { return &band.rgba[(size_t(y) * band.width + x) * 4]; };
  EXPECT_EQ(px(0, 0)[0], 0);
  EXPECT_EQ(px(0, 0)[3], 160);
  EXPECT_EQ(px(4, 2)[0], 255);
  EXPECT_EQ(px(4, 2)[3], 255);
  EXPECT_EQ(px(2, 2)[3], 160);
  // Never wider than the window.
  EXPECT_EQ(overlay_image("a long line of text", 1, 30).width, 30);
}

TEST(WithRefinement, AddsTheSppShownAndTheTargetWhenItFits) {
  EXPECT_EQ(with_refinement("25FPS 40MS embree 160x90", 4, 16, 100), "25FPS 40MS embree 160x90 4/16 SPP");
  // 24 characters + " 4/16 SPP" (9) = 33: fits in 33, not in 32.
  EXPECT_EQ(with_refinement("25FPS 40MS embree 160x90", 4, 16, 33), "25FPS 40MS embree 160x90 4/16 SPP");
  EXPECT_EQ(with_refinement("25FPS 40MS embree 160x90", 4, 16, 32), "25FPS 40MS embree 160x90");
  EXPECT_EQ(with_refinement("25FPS 40MS embree 160x90", 1, 1, 100), "25FPS 40MS embree 160x90");
}

TEST(OverlayImage, LinesUnderEachOther) {
  // Two lines at scale 1: 2 * 7 rows of text + 2 between + 2 * 2 padding = 20.
  const Rgba8Image two = overlay_image(std::vector<std::string>{"AB", "C"}, 1, 100);
  EXPECT_EQ(two.height, 20);
  EXPECT_EQ(overlay_height(2, 1), 20);
  // As wide as the longer line: 2 glyphs = 2 * 6 - 1 = 11 pixels + 2 * 2 padding.
  EXPECT_EQ(two.width, 15);
  EXPECT_EQ(overlay_image("AB", 1, 100).height, overlay_height(1));
}

TEST(KeyHelp, EveryKeyIsListedInCharactersTheFontDraws) {
  const std::vector<std::string>& lines = key_help_lines();
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[6], "C: PRINT THE CAMERA AS JSON");
  EXPECT_EQ(lines[7], "H: HIDE THESE KEYS");
  for (const std::string& line : lines)
    for (char c : line) EXPECT_TRUE(has_glyph(c)) << "'" << c << "' in " << line;
}

}  // namespace
}  // namespace prism::viewer
