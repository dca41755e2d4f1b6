#include "prism/camera.hpp"

#include <cmath>

namespace prism {

glm::dvec2 sample_offset(int k) {
  // The R2 low-discrepancy sequence (Roberts 2018), fixed by the format.
  double x = 0.5 + k * 0.7548776662466927;
  double y = 0.5 + k * 0.5698402909980532;
  return {x - std::floor(x), y - std::floor(y)};
}

CameraRays::CameraRays(const Camera& camera, int width, int height)
    : camera_(camera),
      width_(width),
      height_(height),
      tan_half_(std::tan(glm::radians(camera.fov_y) * 0.5)),
      aspect_(static_cast<double>(width) / height) {}

Ray CameraRays::operator()(int i, int j, glm::dvec2 offset) const {
  double u = ((i + offset.x) / width_ * 2.0 - 1.0) * tan_half_ * aspect_;
  double v = (1.0 - (j + offset.y) / height_ * 2.0) * tan_half_;
  return {camera_.position, glm::normalize(camera_.forward + u * camera_.right + v * camera_.up)};
}

Ray camera_ray(const Camera& camera, int width, int height, int i, int j, glm::dvec2 offset) {
  return CameraRays(camera, width, height)(i, j, offset);
}

}  // namespace prism
