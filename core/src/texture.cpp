#include "prism/texture.hpp"

#include <algorithm>
#include <cmath>

#include "prism/errors.hpp"
#include "prism/image_file.hpp"

namespace prism {

namespace {

// Euclidean modulo: repeat wrap for negative coordinates too.
int wrap(int i, int n) {
  if (static_cast<unsigned>(i) < static_cast<unsigned>(n)) return i;  // the common case, without a division
  int m = i % n;
  return m < 0 ? m + n : m;
}

glm::dvec4 texel(const Texture& t, int x, int y) { return glm::dvec4(t.texels[size_t(y) * t.width + x]); }

// Bilinear blend of the four texels around (x, y) in texel space; `index`
// maps an integer coordinate and the size to a texel row/column.
template <typename IndexFn>
glm::dvec4 bilinear(const Texture& t, double x, double y, IndexFn index) {
  double fx0 = std::floor(x), fy0 = std::floor(y);
  double fx = x - fx0, fy = y - fy0;
  int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  int xa = index(x0, t.width), xb = index(x0 + 1, t.width);
  int ya = index(y0, t.height), yb = index(y0 + 1, t.height);
  glm::dvec4 top = texel(t, xa, ya) * (1 - fx) + texel(t, xb, ya) * fx;
  glm::dvec4 bottom = texel(t, xa, yb) * (1 - fx) + texel(t, xb, yb) * fx;
  return top * (1 - fy) + bottom * fy;
}

glm::vec4 expand_channels(const float* p, int channels) {
  switch (channels) {
    case 1: return {p[0], p[0], p[0], 1.0f};
    case 2: return {p[0], p[0], p[0], p[1]};
    case 3: return {p[0], p[1], p[2], 1.0f};
    default: return {p[0], p[1], p[2], p[3]};
  }
}

}  // namespace

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double linear_to_srgb(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

namespace {

// Refuses a texture whose header says it is larger than what is left of the scene's pixel budget.
void check_texture_size(const std::filesystem::path& path, size_t pixels_left) {
  const ImageFile header = read_image_header(path);
  const size_t pixels = size_t(header.width) * size_t(header.height);
  if (pixels <= pixels_left) return;
  const std::string limit = std::to_string(limits::kMaxTexturePixels) + " pixels all textures of a scene may hold";
  const std::string left = pixels_left == limits::kMaxTexturePixels
                               ? "the limit of " + limit
                               : "the " + std::to_string(pixels_left) + " left of the " + limit;
  throw InputError("'" + path.string() + "' is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                   " = " + std::to_string(pixels) + " pixels, more than " + left);
}

}  // namespace

Texture load_texture(const std::filesystem::path& path, bool srgb, size_t pixels_left) {
  check_texture_size(path, pixels_left);
  ImageFile file = read_image_file(path, pixels_left, 4);  // channels past RGBA are never used
  const int channels = std::min(file.channels, 4);
  // 8- and 16-bit colour is sRGB-encoded unless the scene says otherwise; float formats are linear.
  const bool integer_format = file.format == PixelFormat::UInt8 || file.format == PixelFormat::UInt16;
  const bool decode = srgb && integer_format;
  const int colour_channels = (channels == 2 || channels == 4) ? channels - 1 : channels;
  Texture texture;
  texture.path = path;
  texture.width = file.width;
  texture.height = file.height;
  texture.texels.resize(size_t(file.width) * file.height);
  for (size_t i = 0; i < texture.texels.size(); ++i) {
    float* p = &file.pixels[i * size_t(file.channels)];
    if (decode)
      for (int c = 0; c < colour_channels; ++c) p[c] = static_cast<float>(srgb_to_linear(p[c]));
    texture.texels[i] = expand_channels(p, channels);
  }
  return texture;
}

glm::dvec4 sample_texture(const Texture& texture, glm::dvec2 uv) {
  return bilinear(texture, uv.x * texture.width - 0.5, uv.y * texture.height - 0.5, wrap);
}

namespace {

// A cube-map face sampled at (s, t) with the texture filter, clamped to the face's edge texels.
glm::dvec3 sample_face(const Texture& face, double s, double t) {
  auto clamp_index = [](int i, int n) { return std::clamp(i, 0, n - 1); };
  return glm::dvec3(bilinear(face, s * face.width - 0.5, t * face.height - 0.5, clamp_index));
}

}  // namespace

glm::dvec3 background_radiance(const Scene& scene, const glm::dvec3& d) {
  const Background& bg = scene.background;
  if (!bg.has_cubemap()) return bg.color;
  const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  int face;
  double sc, tc, ma;  // the OpenGL cube-map selection table
  if (ax >= ay && ax >= az) {
    face = d.x >= 0 ? 0 : 1;
    sc = d.x >= 0 ? -d.z : d.z;
    tc = -d.y;
    ma = d.x;
  } else if (ay >= az) {
    face = d.y >= 0 ? 2 : 3;
    sc = d.x;
    tc = d.y >= 0 ? d.z : -d.z;
    ma = d.y;
  } else {
    face = d.z >= 0 ? 4 : 5;
    sc = d.z >= 0 ? d.x : -d.x;
    tc = -d.y;
    ma = d.z;
  }
  const double m = std::abs(ma);
  const double s = (sc / m + 1) / 2, t = (tc / m + 1) / 2;
  return sample_face(scene.textures[size_t(bg.cubemap[size_t(face)])], s, t);
}

}  // namespace prism
