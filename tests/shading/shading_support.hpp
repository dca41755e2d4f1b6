// Helpers for the shading tests: the common one-pixel camera, pixel checks,
// and small texture files written with OpenImageIO.
#pragma once

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

}  // namespace prism::test
