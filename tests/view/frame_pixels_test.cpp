// The viewer's 8-bit conversion is the one prism's PNG output uses.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "prism/image_file.hpp"
#include "prism/image_io.hpp"
#include "test_support.hpp"
#include "viewer/frame_pixels.hpp"

namespace prism::viewer {
namespace {

TEST(FramePixels, Srgb8OfHandWorkedValues) {
  EXPECT_EQ(srgb8(0.0f), 0);
  EXPECT_EQ(srgb8(1.0f), 255);
  EXPECT_EQ(srgb8(-0.5f), 0);   // clamped
  EXPECT_EQ(srgb8(7.0f), 255);  // clamped
  EXPECT_EQ(srgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(srgb8(std::numeric_limits<float>::infinity()), 255);
  // Linear segment: 255 * 12.92 * 0.001 = 3.2946 -> 3.
  EXPECT_EQ(srgb8(0.001f), 3);
  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.73535698; * 255 = 187.516 -> 188.
  EXPECT_EQ(srgb8(0.5f), 188);
  // 1.055 * 0.2^(1/2.4) - 0.055 = 0.48452920; * 255 = 123.555 -> 124.
  EXPECT_EQ(srgb8(0.2f), 124);
  // 1.055 * 0.9^(1/2.4) - 0.055 = 0.95468717; * 255 = 243.445 -> 243.
  EXPECT_EQ(srgb8(0.9f), 243);
}

TEST(FramePixels, Rgba8KeepsTheTopRowFirst) {
  Image image;
  image.width = 2;
  image.height = 2;
  image.rgb = {1, 0, 0, 0, 1, 0,   // top row: red, green
               0, 0, 1, 0.5f, 0.5f, 0.5f};  // bottom row: blue, grey
  const std::vector<uint8_t> expected = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 188, 188, 188, 255};
  EXPECT_EQ(to_rgba8(image), expected);
}

TEST(FramePixels, EveryCodeSurvivesTheRoundTrip) {
  std::vector<uint8_t> rgba(256 * 4);
  for (int c = 0; c < 256; ++c) {
    rgba[c * 4 + 0] = uint8_t(c);
    rgba[c * 4 + 1] = uint8_t(255 - c);
    rgba[c * 4 + 2] = uint8_t((c * 7) % 256);
    rgba[c * 4 + 3] = 255;
  }
  const Image image = from_rgba8(rgba, 256, 1);
  EXPECT_EQ(image.width, 256);
  EXPECT_EQ(image.height, 1);
  EXPECT_EQ(image.rgb[0], 0.0f);
  EXPECT_EQ(image.rgb[255 * 3], 1.0f);
  EXPECT_EQ(to_rgba8(image), rgba);
}

// What the window shows is byte for byte what `prism render -o x.png` writes.
TEST(FramePixels, MatchesThePngWriter) {
  Image image;
  image.width = 64;
  image.height = 4;
  image.rgb.resize(size_t(64) * 4 * 3);
  for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(std::fmod(i * 0.61803398875, 1.3) - 0.1);
  const auto file = prism::test::fresh_temp_dir() / "frame.png";
  write_image(image, file);
  const ImageFile written = read_image_file(file);
  ASSERT_EQ(written.width, 64);
  ASSERT_EQ(written.height, 4);
  ASSERT_EQ(written.channels, 3);
  const std::vector<uint8_t> shown = to_rgba8(image);
  for (size_t p = 0; p < size_t(64) * 4; ++p)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(long(shown[p * 4 + c]), std::lround(written.pixels[p * 3 + c] * 255.0)) << "pixel " << p << " channel " << c;
}

}  // namespace
}  // namespace prism::viewer
