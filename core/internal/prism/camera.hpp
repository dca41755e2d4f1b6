// Camera rays and the R2 sample offsets of the format.
#pragma once

#include <glm/glm.hpp>

#include "prism/geometry.hpp"
#include "prism/scene.hpp"

namespace prism {

// Offset of sample k in [0,1)^2 (R2 sequence, computed in double).
glm::dvec2 sample_offset(int k);

// The camera rays of one width x height image, with what every ray shares
// (tan(fov/2), the aspect ratio) computed once.
class CameraRays {
 public:
  CameraRays(const Camera& camera, int width, int height);
  // The ray through pixel (i, j) at offset `offset` within it.
  Ray operator()(int i, int j, glm::dvec2 offset) const;

 private:
  Camera camera_;
  double width_, height_;
  double tan_half_, aspect_;
};

// Camera ray through pixel (i, j) of a width x height image at offset `offset`.
Ray camera_ray(const Camera& camera, int width, int height, int i, int j, glm::dvec2 offset);

}  // namespace prism
