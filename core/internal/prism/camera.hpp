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
  // A cone from the camera's position that holds every ray through the
  // pixels [x0, x1) x [y0, y1), at any offsets: its unit axis and the
  // cosine of its half-angle (made a little wider than the corner rays
  // need, for their rounding).
  struct Cone {
    glm::dvec3 axis;
    double cos_half;
  };
  Cone cone(int x0, int y0, int x1, int y1) const;
  const glm::dvec3& position() const { return camera_.position; }
  // The ray through pixel (i, j) at offset `offset` within it.
  Ray operator()(int i, int j, glm::dvec2 offset) const {
    const double x = i + offset.x, y = j + offset.y;
    Ray ray;
    make_batch(&x, &y, 1, &ray);
    return ray;
  }
  // The rays through the points (x[q], y[q]) of the image plane, in pixels
  // (a pixel's corner plus its sample's offset), q < count <= kBatch, written
  // into out[q] field by field. Made stage by stage over the batch, each
  // stage a loop the compiler runs four rays wide, so that the divisions
  // and square roots of four rays share an instruction (one at a time they
  // took ~2 % of a showcase frame by perf); every ray is the same bits
  // whatever the batch it is made in.
  static constexpr size_t kBatch = 256;
  void make_batch(const double* x, const double* y, size_t count, Ray* out) const;

 private:
  Camera camera_;
  double width_, height_;
  double tan_half_, aspect_;
};

// Camera ray through pixel (i, j) of a width x height image at offset `offset`.
Ray camera_ray(const Camera& camera, int width, int height, int i, int j, glm::dvec2 offset);

}  // namespace prism
