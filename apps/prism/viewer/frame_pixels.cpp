#include "frame_pixels.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "prism/texture.hpp"

namespace prism::viewer {

uint8_t srgb8(float linear) { return linear_to_srgb8(linear); }

std::vector<uint8_t> to_rgba8(const Image& image) {
  const size_t pixels = size_t(image.width) * size_t(image.height);
  std::vector<uint8_t> out(pixels * 4);
  for (size_t p = 0; p < pixels; ++p) {
    out[p * 4 + 0] = srgb8(image.rgb[p * 3 + 0]);
    out[p * 4 + 1] = srgb8(image.rgb[p * 3 + 1]);
    out[p * 4 + 2] = srgb8(image.rgb[p * 3 + 2]);
    out[p * 4 + 3] = 255;
  }
  return out;
}

Image from_rgba8(const std::vector<uint8_t>& rgba, int width, int height) {
  static const std::array<float, 256> decode = [] {
    std::array<float, 256> table{};
    for (int c = 0; c < 256; ++c) table[c] = static_cast<float>(srgb_to_linear(c / 255.0));
    return table;
  }();
  Image image;
  image.width = width;
  image.height = height;
  const size_t pixels = size_t(width) * size_t(height);
  image.rgb.resize(pixels * 3);
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) image.rgb[p * 3 + c] = decode[rgba[p * 4 + c]];
  return image;
}

}  // namespace prism::viewer
