// The general clipped quadric
//   f(p) = A x^2 + B y^2 + C z^2 + D xy + E yz + F xz + G x + H y + I z + J = 0,
//   clip_min <= p <= clip_max,
// shared by the quadric, cylinder and cone plugins. Cylinder and cone pack a
// QuadricShape and call exactly these functions, so they give bit-identical
// t and normal to the quadric they stand for (spec, Objects). The maths is
// written once, for the CPU and the GPU, in
// prism/sdk/modules/quadric.shared.glsl (the method is described there);
// these are its double instantiations (prism::sdk::f64) on QuadricShape.
#pragma once

#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/shared_plugin.hpp"

#define PRISM_SHARED_SOURCE "prism/sdk/modules/quadric.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace prism::sdk {

// std430-compatible (a flat run of doubles, 16-byte multiple).
struct QuadricShape {
  double coef[12];  // A..J, then two unused slots
  double lo[4];     // clip_min, -inf where unbounded; w unused
  double hi[4];     // clip_max, +inf where unbounded; w unused
};
static_assert(sizeof(QuadricShape) % 16 == 0);
static_assert(PRISM_QUADRIC_COEF == offsetof(QuadricShape, coef) / sizeof(double));
static_assert(PRISM_QUADRIC_LO == offsetof(QuadricShape, lo) / sizeof(double));
static_assert(PRISM_QUADRIC_HI == offsetof(QuadricShape, hi) / sizeof(double));

// The shared code's view of a QuadricShape.
inline f64::PrismQuadric shared_quadric(const QuadricShape& q) { return f64::prism_quadric_load(f64::prism_record_at(&q)); }

inline QuadricShape make_quadric(const double coef[10], const double lo[3], const double hi[3]) {
  QuadricShape q{};
  for (int i = 0; i < 10; ++i) q.coef[i] = coef[i];
  for (int i = 0; i < 3; ++i) {
    q.lo[i] = lo[i];
    q.hi[i] = hi[i];
  }
  return q;
}

inline double quadric_value(const QuadricShape& q, const glm::dvec3& p) {
  return f64::prism_quadric_value(shared_quadric(q), p);
}

inline glm::dvec3 quadric_gradient(const QuadricShape& q, const glm::dvec3& p) {
  return f64::prism_quadric_gradient(shared_quadric(q), p);
}

// Local AABB: the clip box when it is finite on all three axes, else none.
inline bool quadric_bounds(const QuadricShape& q, double lo[3], double hi[3]) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(q.lo[i]) || !std::isfinite(q.hi[i])) return false;
  for (int i = 0; i < 3; ++i) {
    lo[i] = q.lo[i];
    hi[i] = q.hi[i];
  }
  return true;
}

// Smallest root t with tmin < t <= tmax whose point lies in the clip box (the
// far root when the near one is clipped away); fills t and the local hit
// point p (t untouched and p zero on a miss).
inline bool intersect_quadric(const QuadricShape& q, const glm::dvec3& o, const glm::dvec3& d, double tmin,
                              double tmax, double& t, glm::dvec3& p) {
  p = glm::dvec3(0.0);
  return f64::prism_quadric_hit(shared_quadric(q), o, d, tmin, tmax, t, p);
}

// Re-projects a hit point onto f = 0 (one Newton step) and gives the outward
// normal there, scaled so its largest component is 1; all zeros where the
// gradient vanishes.
inline void quadric_surface(const QuadricShape& q, glm::dvec3 p, glm::dvec3& point, glm::dvec3& normal) {
  f64::prism_quadric_project(shared_quadric(q), p, point, normal);
}

// The descriptor's `intersect` for any plugin whose record begins with a
// QuadricShape (quadric, cylinder, cone): one code path for all three.
inline int intersect_quadric_record(const void* record, const PrismRay* ray, double tmin, double tmax,
                                    PrismHit* hit) {
  return f64::abi_intersect<f64::prism_quadric_intersect>(record, ray, tmin, tmax, hit);
}

// Polishes a hit from intersect_quadric_record on the quadric with
// coefficients `coef` (A..J) in long double (see refine.hpp).
inline void polish_quadric_hit(const long double coef[10], const PrismRayExt* ray, PrismHit* hit) {
  Vec3x p;
  if (polish_hit(*ray, *hit, [coef](const Vec3x& q) { return quadric_implicit(coef, q); }, &p)) store3(p, hit->data);
}

// The descriptor's `refine` for the quadric plugin: its own coefficients,
// which are the file's numbers unrounded.
inline void refine_quadric_record(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  long double coef[10];
  for (int i = 0; i < 10; ++i) coef[i] = record_of<QuadricShape>(record).coef[i];
  polish_quadric_hit(coef, ray, hit);
}

}  // namespace prism::sdk
