#include "shading_support.hpp"

#include "prism/image_file.hpp"

#include <cmath>
#include <sstream>

namespace prism::test {

std::string one_pixel_scene(const std::string& body) {
  return R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 60},
    "image": {"width": 1, "height": 1},
    )" + body + "}";
}

glm::dvec3 pixel(const Image& image, int i, int j) {
  const size_t at = (static_cast<size_t>(j) * image.width + i) * 3;
  return {image.rgb.at(at), image.rgb.at(at + 1), image.rgb.at(at + 2)};
}

testing::AssertionResult pixel_near(const Image& image, int i, int j, glm::dvec3 expected,
                                    double tolerance) {
  if (i < 0 || j < 0 || i >= image.width || j >= image.height ||
      image.rgb.size() != static_cast<size_t>(image.width) * image.height * 3) {
    return testing::AssertionFailure() << "pixel (" << i << ", " << j << ") is not in a " << image.width
                                       << "x" << image.height << " image with " << image.rgb.size()
                                       << " floats";
  }
  const glm::dvec3 got = pixel(image, i, j);
  for (int c = 0; c < 3; ++c) {
    if (!(std::abs(got[c] - expected[c]) <= tolerance)) {
      std::ostringstream msg;
      msg.precision(9);
      msg << "pixel (" << i << ", " << j << ") is (" << got.r << ", " << got.g << ", " << got.b
          << "), expected (" << expected.r << ", " << expected.g << ", " << expected.b << ") within "
          << tolerance;
      return testing::AssertionFailure() << msg.str();
    }
  }
  return testing::AssertionSuccess();
}

namespace {

// Writes `values` (already in the file's units: 0..255, 0..65535 or linear
// floats) through the core's image module, which stores them unchanged.
template <typename T>
void write_file(const std::filesystem::path& file, int width, int height, int channels, PixelFormat format,
                const std::vector<T>& values, double scale) {
  ASSERT_EQ(values.size(), static_cast<size_t>(width) * height * channels);
  ImageFile image{width, height, channels, {}, format, {}};
  for (T v : values) image.pixels.push_back(static_cast<float>(double(v) / scale));
  ASSERT_NO_THROW(write_image_file(file, image, format));
}

}  // namespace

void write_exr(const std::filesystem::path& file, int width, int height, int channels,
               const std::vector<float>& values) {
  write_file(file, width, height, channels, PixelFormat::Float, values, 1.0);
}

void write_png8(const std::filesystem::path& file, int width, int height, int channels,
                const std::vector<unsigned char>& bytes) {
  write_file(file, width, height, channels, PixelFormat::UInt8, bytes, 255.0);
}

void write_png16(const std::filesystem::path& file, int width, int height, int channels,
                 const std::vector<uint16_t>& values) {
  write_file(file, width, height, channels, PixelFormat::UInt16, values, 65535.0);
}

void GridTextureTest::SetUp() {
  BackendTest::SetUp();
  if (IsSkipped() || HasFatalFailure()) return;
  dir_ = fresh_temp_dir();
  std::vector<float> texels;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) texels.insert(texels.end(), {(i + 1) / 8.0f, (j + 1) / 8.0f, (i + 4 * j) / 16.0f});
  }
  write_exr(dir_ / "grid.exr", 4, 4, 3, texels);
}

Image GridTextureTest::render_grid(const std::string& camera, const std::string& material_extra,
                                   const std::string& object) {
  return render(load(R"({"prism": 1, "camera": )" + camera + R"(,
    "image": {"width": 1, "height": 1},
    "ambient": [1, 1, 1],
    "textures": {"grid": "grid.exr"},
    "materials": {"m": {"color": [1, 1, 1], "texture": "grid")" + material_extra + R"(}},
    "objects": [)" + object + "]}",
                     dir_));
}

}  // namespace prism::test
