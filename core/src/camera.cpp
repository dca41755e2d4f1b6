#include "prism/camera.hpp"

#include <algorithm>
#include <array>
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

CameraRays::Cone CameraRays::cone(int x0, int y0, int x1, int y1) const {
  // forward + u right + v up is affine in (u, v), so every ray through the
  // rectangle is a positive combination of the rays through its corners;
  // a circular cone of half-angle up to 90 degrees is convex, so one that
  // holds the corner rays holds them all.
  const glm::dvec3 corners[4] = {(*this)(x0, y0, {0, 0}).dir, (*this)(x1 - 1, y0, {1, 0}).dir,
                                 (*this)(x0, y1 - 1, {0, 1}).dir, (*this)(x1 - 1, y1 - 1, {1, 1}).dir};
  const glm::dvec3 axis = glm::normalize(corners[0] + corners[1] + corners[2] + corners[3]);
  double cos_half = 1.0;
  for (const glm::dvec3& corner : corners) cos_half = std::min(cos_half, glm::dot(axis, corner));
  return {axis, cos_half - 1e-9};
}

void CameraRays::make_batch(const double* x, const double* y, size_t count, Ray* out) const {
  // glm::normalize(forward + u right + v up) in glm's order of operations:
  // the sum left to right, a dot product as (x + y) + z, and normalize as a
  // multiplication by 1 / sqrt of it, so the rays are the bits the format's
  // glm expression gives.
  std::array<double, kBatch> dx, dy, dz;
  const glm::dvec3 f = camera_.forward, r = camera_.right, up = camera_.up;
  for (size_t q = 0; q < count; ++q) {
    const double u = (x[q] / width_ * 2.0 - 1.0) * tan_half_ * aspect_;
    const double v = (1.0 - y[q] / height_ * 2.0) * tan_half_;
    const double ex = f.x + u * r.x + v * up.x, ey = f.y + u * r.y + v * up.y, ez = f.z + u * r.z + v * up.z;
    const double scale = 1.0 / std::sqrt(ex * ex + ey * ey + ez * ez);
    dx[q] = ex * scale;
    dy[q] = ey * scale;
    dz[q] = ez * scale;
  }
  for (size_t q = 0; q < count; ++q) {
    out[q].origin = camera_.position;
    out[q].dir.x = dx[q];
    out[q].dir.y = dy[q];
    out[q].dir.z = dz[q];
  }
}

Ray camera_ray(const Camera& camera, int width, int height, int i, int j, glm::dvec2 offset) {
  return CameraRays(camera, width, height)(i, j, offset);
}

}  // namespace prism
