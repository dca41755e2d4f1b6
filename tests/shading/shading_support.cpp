#include "shading_support.hpp"

#include <OpenImageIO/imageio.h>

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

void write_image(const std::filesystem::path& file, const OIIO::ImageSpec& spec, const void* data) {
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out) << "cannot write " << file << ": " << OIIO::geterror();
  ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(spec.format, data)) << out->geterror();
  ASSERT_TRUE(out->close()) << out->geterror();
}

}  // namespace

void write_exr(const std::filesystem::path& file, int width, int height, int channels,
               const std::vector<float>& values) {
  ASSERT_EQ(values.size(), static_cast<size_t>(width) * height * channels);
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  write_image(file, spec, values.data());
}

void write_png8(const std::filesystem::path& file, int width, int height, int channels,
                const std::vector<unsigned char>& bytes) {
  ASSERT_EQ(bytes.size(), static_cast<size_t>(width) * height * channels);
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  // The bytes are unassociated already: OIIO must not divide them by alpha.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  write_image(file, spec, bytes.data());
}

}  // namespace prism::test
