#include "prism/camera.hpp"

#include <cmath>

namespace prism {

glm::dvec2 sample_offset(int k) {
  // The R2 low-discrepancy sequence (Roberts 2018), fixed by the format.
  double x = 0.5 + k * 0.7548776662466927;
  double y = 0.5 + k * 0.5698402909980532;
  return {x - std::floor(x), y - std::floor(y)};
}

Ray camera_ray(const Camera& camera, int width, int height, int i, int j, glm::dvec2 offset) {
  double tan_half = std::tan(glm::radians(camera.fov_y) * 0.5);
  double aspect = static_cast<double>(width) / height;
  double u = ((i + offset.x) / width * 2.0 - 1.0) * tan_half * aspect;
  double v = (1.0 - (j + offset.y) / height * 2.0) * tan_half;
  return {camera.position, glm::normalize(camera.forward + u * camera.right + v * camera.up)};
}

}  // namespace prism
