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
  // The ray through pixel (i, j) at offset `offset` within it. Inline: a
  // frame makes one per camera sample, in a loop of its own (render_cpu).
  Ray operator()(int i, int j, glm::dvec2 offset) const {
    Ray ray;
    make(i, j, offset, ray);
    return ray;
  }
  // The same ray written into `out` field by field. Returned and copied, it
  // went through the stack: stored as its direction's 16 + 8 bytes and
  // read back in 16-byte pieces across them, the copy waited for the
  // stores (a store-forwarding stall, ~2 % of a showcase frame by perf).
  void make(int i, int j, glm::dvec2 offset, Ray& out) const {
    const double u = ((i + offset.x) / width_ * 2.0 - 1.0) * tan_half_ * aspect_;
    const double v = (1.0 - (j + offset.y) / height_ * 2.0) * tan_half_;
    const glm::dvec3 dir = glm::normalize(camera_.forward + u * camera_.right + v * camera_.up);
    out.origin = camera_.position;
    out.dir.x = dir.x;
    out.dir.y = dir.y;
    out.dir.z = dir.z;
  }
  // The rays through the points (x[q], y[q]) of the image plane, in pixels
  // (a pixel's corner plus its sample's offset), q < count <= kBatch: each
  // the ray make() gives, bit for bit. Made stage by stage over the batch,
  // each stage a loop the compiler runs four rays wide, so that the
  // divisions and square roots of four rays share an instruction (one at a
  // time they took ~2 % of a showcase frame by perf).
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
