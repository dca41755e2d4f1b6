// The core's image comparison against OpenImageIO's ImageBufAlgo::compare
// (linked here as the independent computation), and its edge cases by hand.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cmath>
#include <limits>
#include <random>

#include "prism/errors.hpp"
#include "prism/image_file.hpp"

namespace prism {
namespace {

ImageFile image_of(int width, int height, int channels, std::vector<float> pixels) {
  ImageFile image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  image.pixels = std::move(pixels);
  return image;
}

OIIO::ImageBuf buffer_of(const ImageFile& image) {
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf buffer(spec);
  buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data());
  return buffer;
}

// Random images a little apart: most pixels within the threshold, some
// well over it, some equal.
std::pair<ImageFile, ImageFile> random_pair(std::mt19937& rng, int width, int height, int channels) {
  std::uniform_real_distribution<float> value(0.0f, 1.5f), small(-0.01f, 0.01f), large(-0.5f, 0.5f);
  std::uniform_int_distribution<int> kind(0, 9);
  std::vector<float> a(size_t(width) * height * channels), b(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    a[i] = value(rng);
    const int k = kind(rng);
    b[i] = k == 0 ? a[i] : a[i] + (k == 1 ? large(rng) : small(rng));
  }
  return {image_of(width, height, channels, a), image_of(width, height, channels, b)};
}

TEST(ImageCompare, EqualsOpenImageIOsCompareOnRandomImages) {
  std::mt19937 rng(20261204);
  for (const auto& [width, height, channels] : {std::tuple{1, 1, 1}, {7, 5, 3}, {64, 48, 3}, {33, 200, 4}}) {
    for (float threshold : {0.0f, 0.016f, 0.2f}) {
      const auto [a, b] = random_pair(rng, width, height, channels);
      const ImageComparison ours = compare_image_files(a, b, threshold);
      const auto theirs = OIIO::ImageBufAlgo::compare(buffer_of(a), buffer_of(b), threshold, threshold);
      SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(channels) +
                   " threshold " + std::to_string(threshold));
      EXPECT_EQ(ours.pixels_over, long(theirs.nfail));
      EXPECT_EQ(ours.max_error, theirs.maxerror);
      EXPECT_EQ(ours.max_x, theirs.maxx);
      EXPECT_EQ(ours.max_y, theirs.maxy);
      EXPECT_EQ(ours.max_channel, theirs.maxc);
      // OpenImageIO sums in batches of 4096 pixels: the same sum to rounding.
      EXPECT_NEAR(ours.mean_error, theirs.meanerror, 1e-14);
      EXPECT_NEAR(ours.rms_error, theirs.rms_error, 1e-14);
      if (std::isinf(theirs.PSNR)) EXPECT_EQ(ours.psnr, theirs.PSNR);
      else EXPECT_NEAR(ours.psnr, theirs.PSNR, 1e-10);
    }
  }
}

TEST(ImageCompare, FiguresOfASmallPairByHand) {
  // Differences 0, 0.5, 0.25, 0 over 4 values: mean 0.1875, RMS
  // sqrt(0.3125 / 4) = 0.279508..., PSNR against the peak 1 (no value is
  // larger): 20 log10(1 / RMS) = 11.0721 dB.
  const ImageFile a = image_of(2, 1, 2, {0.0f, 1.0f, 0.5f, 0.25f});
  const ImageFile b = image_of(2, 1, 2, {0.0f, 0.5f, 0.75f, 0.25f});
  const ImageComparison c = compare_image_files(a, b, 0.3f);
  EXPECT_DOUBLE_EQ(c.mean_error, 0.1875);
  EXPECT_DOUBLE_EQ(c.rms_error, std::sqrt(0.078125));
  EXPECT_NEAR(c.psnr, 11.07209969647868, 1e-12);
  EXPECT_EQ(c.max_error, 0.5);
  EXPECT_EQ(c.max_x, 0);
  EXPECT_EQ(c.max_channel, 1);
  EXPECT_EQ(c.pixels_over, 1);
}

TEST(ImageCompare, EqualImagesHaveNoErrorAndAnInfinitePsnr) {
  const ImageFile a = image_of(3, 1, 1, {0.1f, 0.2f, 0.3f});
  const ImageComparison c = compare_image_files(a, a, 0.0f);
  EXPECT_EQ(c.mean_error, 0.0);
  EXPECT_EQ(c.max_error, 0.0);
  EXPECT_EQ(c.pixels_over, 0);
  EXPECT_TRUE(std::isinf(c.psnr));
}

TEST(ImageCompare, ANonFiniteValueMatchesOnlyItselfAndElseFailsItsPixel) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const ImageFile a = image_of(4, 1, 1, {nan, inf, nan, 0.5f});
  const ImageFile b = image_of(4, 1, 1, {nan, inf, 0.5f, 0.5f});
  const ImageComparison c = compare_image_files(a, b, 0.1f);
  EXPECT_EQ(c.pixels_over, 1);
  EXPECT_TRUE(std::isinf(c.max_error));
  EXPECT_EQ(c.max_x, 2);
  EXPECT_EQ(c.mean_error, 0.0) << "finite pairs only are summed";
}

TEST(ImageCompare, ImagesOfDifferentShapesAreRefused) {
  const ImageFile a = image_of(2, 1, 1, {0, 0}), b = image_of(1, 2, 1, {0, 0});
  EXPECT_THROW(compare_image_files(a, b, 0.1f), InputError);
}

}  // namespace
}  // namespace prism
