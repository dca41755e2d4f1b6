// Ray-sphere intersection shared by the sphere plugin and the core's visible
// light spheres, so that both give the same t for the same sphere. Written
// once, for the CPU and the GPU, as prism_intersect_sphere in
// prism/sdk/modules/library.shared.glsl (the method is described there).
#pragma once

#include <glm/glm.hpp>

#include "prism/sdk/library.hpp"

namespace prism::sdk {

// Smallest root t with tmin < t <= tmax of |o + t d| = r, where o is the ray
// origin relative to the sphere centre and d is unit length.
inline bool intersect_sphere(const glm::dvec3& o, const glm::dvec3& d, double r, double tmin, double tmax,
                             double& t) {
  return f64::prism_intersect_sphere(o, d, r, tmin, tmax, t);
}

}  // namespace prism::sdk
