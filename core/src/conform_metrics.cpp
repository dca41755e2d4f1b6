#include "prism/conform_metrics.hpp"

#include <cmath>

namespace prism::conform {

float pixel_error(const Image& reference, const Image& image, size_t p) {
  float worst = 0.0f;
  for (int c = 0; c < 3; ++c) {
    const float v = image.rgb[p * 3 + c];
    if (!std::isfinite(v)) return INFINITY;
    worst = std::max(worst, std::abs(v - reference.rgb[p * 3 + c]));
  }
  return worst;
}

ImageFile rgb_file(const Image& image) {
  ImageFile file;
  file.width = image.width;
  file.height = image.height;
  file.channels = 3;
  file.pixels = image.rgb;
  return file;
}

std::vector<uint8_t> stable_pixels(const Image& reference) {
  const int w = reference.width, h = reference.height;
  std::vector<uint8_t> stable(size_t(w) * h, 0);
  if (reference.path.empty()) return stable;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * w + x;
      bool same = true;
      for_each_neighbour(w, h, x, y, [&](size_t q) { same = same && reference.path[q] == reference.path[p]; });
      stable[p] = same ? 1 : 0;
    }
  }
  return stable;
}

Metrics measure(const Image& reference, const std::vector<uint8_t>& stable, const Image& image, float threshold) {
  Metrics m;
  const ImageComparison c = compare_image_files(rgb_file(reference), rgb_file(image), threshold);
  m.mean_error = c.mean_error;
  m.rms_error = c.rms_error;
  m.psnr = c.psnr;
  m.max_error = c.max_error;
  m.pixels = long(stable.size());
  for (size_t p = 0; p < stable.size(); ++p) {
    const float error = pixel_error(reference, image, p);
    const bool over = error > threshold;
    if (std::isinf(error)) ++m.nonfinite;
    m.pixels_over += over;
    (stable[p] ? m.stable_pixels : m.edge_pixels) += 1;
    (stable[p] ? m.stable_over : m.edge_over) += over;
  }
  return m;
}

}  // namespace prism::conform
