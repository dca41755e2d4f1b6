// Radiance HDR (.hdr) output: RGBE pixels, one shared exponent per pixel.
// Written here rather than through OpenImageIO, whose writer does not report
// a failed write (a full disk left an empty file, renamed over the old one).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "image_codecs.hpp"

namespace prism::codec {

namespace {

// Ward's float-to-RGBE: the largest component's mantissa in [128, 256), the
// others scaled alike. Negative, NaN and infinite values store as 0 (RGBE
// holds none of them).
void to_rgbe(const float* rgb, unsigned char* rgbe) {
  float c[3];
  for (int i = 0; i < 3; ++i) c[i] = std::isfinite(rgb[i]) && rgb[i] > 0.0f ? rgb[i] : 0.0f;
  const float largest = std::max({c[0], c[1], c[2]});
  if (largest < 1e-32f) {
    std::fill_n(rgbe, 4, 0);
    return;
  }
  int exponent = 0;
  const float scale = std::frexp(largest, &exponent) * 256.0f / largest;
  for (int i = 0; i < 3; ++i) rgbe[i] = static_cast<unsigned char>(c[i] * scale);
  rgbe[3] = static_cast<unsigned char>(exponent + 128);
}

}  // namespace

void write_hdr(int fd, const ImageFile& image) {
  if (image.channels < 3) throw CodecError("Radiance HDR needs 3 channels, not " + std::to_string(image.channels));
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(image.height) + " +X " +
                             std::to_string(image.width) + "\n";
  write_all(fd, header.data(), header.size());
  // Uncompressed scanlines: a flat pixel never begins 2, 2, <128 (the
  // largest mantissa is at least 128), so readers do not take it for a run.
  std::vector<unsigned char> row(size_t(image.width) * 4);
  const size_t stride = size_t(image.channels);
  for (int y = 0; y < image.height; ++y) {
    const float* pixels = image.pixels.data() + size_t(y) * size_t(image.width) * stride;
    for (size_t x = 0; x < size_t(image.width); ++x) to_rgbe(pixels + x * stride, &row[x * 4]);
    write_all(fd, row.data(), row.size());
  }
}

}  // namespace prism::codec
