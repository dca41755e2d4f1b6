// Ray-sphere intersection shared by the sphere plugin and the core's visible
// light spheres, so that both give the same t for the same sphere.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace prism::sdk {

// Smallest root t with tmin < t <= tmax of |o + t d| = r, where o is the ray
// origin relative to the sphere centre and d is unit length.
//
// The origin is first moved to the foot of the perpendicular from the centre
// (t_f = -o.d), so a camera 1e6 away works with numbers of the sphere's size.
// The discriminant is the robust r^2 - |f - (f.d) d|^2 (Ray Tracing Gems
// ch. 7) rather than b^2 - 4ac, which cancels for far or small spheres. After
// re-centring the linear coefficient b = f.d is only a rounding residual, so
// the roots t_f - b -+ sqrt(disc) carry no cancellation.
inline bool intersect_sphere(const glm::dvec3& o, const glm::dvec3& d, double r, double tmin, double tmax,
                             double& t) {
  double tf = -glm::dot(o, d);
  glm::dvec3 f = o + tf * d;
  double b = glm::dot(f, d);
  glm::dvec3 perp = f - b * d;
  double disc = r * r - glm::dot(perp, perp);
  if (!(disc >= 0.0)) return false;  // also rejects NaN rays
  double h = std::sqrt(disc);
  double mid = tf - b;
  double t0 = mid - h, t1 = mid + h;
  if (t0 > tmin && t0 <= tmax) {
    t = t0;
    return true;
  }
  if (t1 > tmin && t1 <= tmax) {
    t = t1;
    return true;
  }
  return false;
}

}  // namespace prism::sdk
