// The conformance metrics: one image against a reference of the same size,
// with the pixels split by the reference's `path` AOV (sample 0's path
// signature) into stable ones (the 3x3 neighbourhood shares one signature)
// and edges (silhouettes, shadow edges, reflected edges). `prism conform`
// and the Python module's prism.compare both use these.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prism/backend.hpp"
#include "prism/image_file.hpp"

namespace prism::conform {

// One image against another (same size), as OpenImageIO's compare reports it.
struct Metrics {
  double mean_error = 0, rms_error = 0, psnr = 0, max_error = 0;
  long pixels = 0, pixels_over = 0;
  long stable_pixels = 0, stable_over = 0;
  long edge_pixels = 0, edge_over = 0;
  long nonfinite = 0;  // NaN or Inf pixels in the image under test
};

// 1 where the 3x3 neighbourhood (inside the image) shares the centre's path
// signature; all 0 (every pixel an edge) when the reference has no path AOV.
std::vector<uint8_t> stable_pixels(const Image& reference);
// Errors are absolute channel differences; a pixel is over when any channel
// differs by more than `threshold`. Throws InputError when the sizes differ.
Metrics measure(const Image& reference, const std::vector<uint8_t>& stable, const Image& image, float threshold);

// The largest absolute channel difference of pixel p; +inf when the image
// under test has a NaN or Inf there.
float pixel_error(const Image& reference, const Image& image, size_t p);
// The RGB of an Image as an ImageFile, for compare_image_files.
ImageFile rgb_file(const Image& image);

// Every 3x3 neighbour of (x, y) inside the image, the pixel itself included.
template <class Visit>
void for_each_neighbour(int width, int height, int x, int y, Visit visit) {
  for (int j = std::max(0, y - 1); j <= std::min(height - 1, y + 1); ++j)
    for (int i = std::max(0, x - 1); i <= std::min(width - 1, x + 1); ++i) visit(size_t(j) * width + i);
}

}  // namespace prism::conform
