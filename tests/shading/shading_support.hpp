// Helpers for the shading tests: the common one-pixel camera, pixel checks,
// and small texture files written through the core's image module.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "prism/backend.hpp"
#include "test_support.hpp"

namespace prism::test {

// `{"prism": 1, <camera>, <image>, BODY}` with a camera at the origin looking
// down -z and a 1x1 image: its only camera ray is exactly (0,0,-1) (the pixel
// centre gives u = v = 0). BODY is the rest of the top level, without braces.
std::string one_pixel_scene(const std::string& body);

glm::dvec3 pixel(const Image& image, int i, int j);

// |pixel - expected| <= tolerance in every channel.
testing::AssertionResult pixel_near(const Image& image, int i, int j, glm::dvec3 expected,
                                    double tolerance = 1e-5);

// Writes a float EXR (channels 1..4, row 0 at the top), values as given.
void write_exr(const std::filesystem::path& file, int width, int height, int channels,
               const std::vector<float>& values);

// Writes an 8-bit PNG storing `bytes` exactly (alpha unassociated, no conversion).
void write_png8(const std::filesystem::path& file, int width, int height, int channels,
                const std::vector<unsigned char>& bytes);

// The same with 16-bit values.
void write_png16(const std::filesystem::path& file, int width, int height, int channels,
                 const std::vector<uint16_t>& values);

// Fixture with a 4x4 EXR "grid.exr" in dir_ whose texel (column i, row j) is
//   ((i+1)/8, (j+1)/8, (i + 4j)/16), all exact in float.
// A uv' on a texel centre, ((i+0.5)/4, (j+0.5)/4), gives x = u'*4 - 0.5 = i and
// y = j exactly: bilinear weight 1 on texel (i, j).
class GridTextureTest : public BackendTest {
 protected:
  void SetUp() override;
  // One pixel seen by `camera` (a JSON object), ambient 1 and no lights, so the
  // pixel is c = tex.rgb of material "m" = grid texture + `material_extra`
  // (JSON members starting with a comma).
  Image render_grid(const std::string& camera, const std::string& material_extra, const std::string& object);
  std::filesystem::path dir_;
};

}  // namespace prism::test
