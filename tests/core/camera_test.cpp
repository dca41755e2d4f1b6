// The camera's cone over a tile of pixels (CameraRays::cone), which lets the
// shading skip the light spheres no camera ray of a tile can meet, and the
// rays made a batch at a time (CameraRays::make_batch).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "prism/camera.hpp"

namespace prism {
namespace {

Camera camera_looking_along(const glm::dvec3& forward, const glm::dvec3& up, double fov_y) {
  Camera camera;
  camera.position = {1.5, -2.0, 3.25};
  camera.forward = glm::normalize(forward);
  camera.right = glm::normalize(glm::cross(camera.forward, up));
  camera.up = glm::cross(camera.right, camera.forward);
  camera.fov_y = fov_y;
  return camera;
}

// One pixel under a 90-degree field of view: it spans u, v in [-1, 1], so
// its corner rays are (+-1, +-1, forward), at cos = 1 / sqrt(3) from the
// axis, which is the forward direction; the cone is widened by 1e-9 in
// the cosine for rounding.
TEST(CameraRays, TheConeOfASquarePixelUnderNinetyDegreesIsHandWorked) {
  const Camera camera = camera_looking_along({0, 0, -1}, {0, 1, 0}, 90.0);
  const CameraRays::Cone cone = CameraRays(camera, 1, 1).cone(0, 0, 1, 1);
  EXPECT_NEAR(cone.axis.x, 0.0, 1e-15);
  EXPECT_NEAR(cone.axis.y, 0.0, 1e-15);
  EXPECT_NEAR(cone.axis.z, -1.0, 1e-15);
  EXPECT_NEAR(cone.cos_half, 0.57735026918962576 - 1e-9, 1e-15);
}

// Every ray through a tile, at any offset in its pixels, lies in the tile's
// cone: tiles at the centre, the edges and the corners of the image, for a
// narrow, an ordinary and a wide field of view and a tilted camera.
TEST(CameraRays, ATilesConeHoldsEveryRayThroughIt) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> offset(0.0, std::nextafter(1.0, 0.0));
  const int width = 97, height = 61, tile = 16;
  for (const double fov : {1.0, 42.0, 150.0}) {
    const Camera camera = camera_looking_along({0.3, -0.4, -1.0}, {0.1, 1.0, 0.05}, fov);
    const CameraRays rays(camera, width, height);
    for (int y0 = 0; y0 < height; y0 += tile) {
      for (int x0 = 0; x0 < width; x0 += tile) {
        const int x1 = std::min(x0 + tile, width), y1 = std::min(y0 + tile, height);
        const CameraRays::Cone cone = rays.cone(x0, y0, x1, y1);
        EXPECT_NEAR(glm::length(cone.axis), 1.0, 1e-15);
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            for (const glm::dvec2 at : {glm::dvec2(0, 0), glm::dvec2(offset.max(), offset.max()),
                                        glm::dvec2(offset(random), offset(random))}) {
              const Ray ray = rays(x, y, at);
              ASSERT_GE(glm::dot(cone.axis, ray.dir), cone.cos_half)
                  << "fov " << fov << ", pixel (" << x << ", " << y << ") of the tile at (" << x0 << ", " << y0 << ")";
            }
          }
        }
      }
    }
  }
}

// A ray made in a batch is the bits of the same ray made alone, and of
// glm's expression for it: batches of every count from 1 to a whole batch
// (the vector loop's remainders included), pixels anywhere in the image,
// offsets anywhere in a pixel.
TEST(CameraRays, BatchesMakeTheSameRaysAsOneAtATime) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> offset(0.0, std::nextafter(1.0, 0.0));
  const int width = 97, height = 61;
  for (const double fov : {1.0, 42.0, 150.0}) {
    const Camera camera = camera_looking_along({0.3, -0.4, -1.0}, {0.1, 1.0, 0.05}, fov);
    const CameraRays rays(camera, width, height);
    const double tan_half = std::tan(glm::radians(fov) * 0.5), aspect = double(width) / height;
    auto by_glm = [&](double x, double y) {  // the format's camera ray, written with glm
      const double u = (x / width * 2.0 - 1.0) * tan_half * aspect, v = (1.0 - y / height * 2.0) * tan_half;
      return glm::normalize(camera.forward + u * camera.right + v * camera.up);
    };
    for (const size_t count : {size_t(1), size_t(3), size_t(4), size_t(5), size_t(127), CameraRays::kBatch}) {
      std::vector<int> i(count), j(count);
      std::vector<glm::dvec2> at(count);
      std::vector<double> x(count), y(count);
      for (size_t q = 0; q < count; ++q) {
        i[q] = int(random() % width);
        j[q] = int(random() % height);
        at[q] = {offset(random), offset(random)};
        x[q] = i[q] + at[q].x;
        y[q] = j[q] + at[q].y;
      }
      std::vector<Ray> batch(count);
      rays.make_batch(x.data(), y.data(), count, batch.data());
      for (size_t q = 0; q < count; ++q) {
        const Ray one = rays(i[q], j[q], at[q]);
        const glm::dvec3 want = by_glm(x[q], y[q]);
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(batch[q].origin[c], camera.position[c]) << "fov " << fov << ", ray " << q << " of " << count;
          ASSERT_EQ(batch[q].dir[c], want[c]) << "fov " << fov << ", ray " << q << " of " << count;
          ASSERT_EQ(one.dir[c], want[c]) << "fov " << fov << ", ray " << q << " alone";
        }
      }
    }
  }
}

}  // namespace
}  // namespace prism
