// The general clipped quadric
//   f(p) = A x^2 + B y^2 + C z^2 + D xy + E yz + F xz + G x + H y + I z + J = 0,
//   clip_min <= p <= clip_max,
// shared by the quadric, cylinder and cone plugins. Cylinder and cone pack a
// QuadricShape and call exactly these functions, so they give bit-identical
// t and normal to the quadric they stand for (spec, Objects).
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"

namespace prism::sdk {

// std430-compatible (a flat run of doubles, 16-byte multiple).
struct QuadricShape {
  double coef[12];  // A..J, then two unused slots
  double lo[4];     // clip_min, -inf where unbounded; w unused
  double hi[4];     // clip_max, +inf where unbounded; w unused
};
static_assert(sizeof(QuadricShape) % 16 == 0);

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
  const double* c = q.coef;
  return p.x * (c[0] * p.x + c[3] * p.y + c[5] * p.z + c[6]) + p.y * (c[1] * p.y + c[4] * p.z + c[7]) +
         p.z * (c[2] * p.z + c[8]) + c[9];
}

inline glm::dvec3 quadric_gradient(const QuadricShape& q, const glm::dvec3& p) {
  const double* c = q.coef;
  return {2.0 * c[0] * p.x + c[3] * p.y + c[5] * p.z + c[6], 2.0 * c[1] * p.y + c[3] * p.x + c[4] * p.z + c[7],
          2.0 * c[2] * p.z + c[4] * p.y + c[5] * p.x + c[8]};
}

// d^T M d: the coefficient of t^2 along direction d.
inline double quadric_quadratic_term(const QuadricShape& q, const glm::dvec3& d) {
  const double* c = q.coef;
  return d.x * (c[0] * d.x + c[3] * d.y + c[5] * d.z) + d.y * (c[1] * d.y + c[4] * d.z) + d.z * c[2] * d.z;
}

inline bool quadric_in_clip(const QuadricShape& q, const glm::dvec3& p) {
  return p.x >= q.lo[0] && p.x <= q.hi[0] && p.y >= q.lo[1] && p.y <= q.hi[1] && p.z >= q.lo[2] && p.z <= q.hi[2];
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
// point p. The origin is moved to the foot of the perpendicular from the
// local origin first, so b and c are formed from numbers of the object's
// size even for a camera 1e6 away; p is taken in that frame too, which keeps
// its error ~eps * |object| rather than eps * |origin|. Where the roots are
// close together it is moved again, to the vertex of f along the ray.
inline bool intersect_quadric(const QuadricShape& q, const glm::dvec3& o, const glm::dvec3& d, double tmin,
                              double tmax, double& t, glm::dvec3& p) {
  double tf = foot_parameter(o, d);
  glm::dvec3 of = o + tf * d;
  double a = quadric_quadratic_term(q, d);
  double b = glm::dot(quadric_gradient(q, of), d);
  double c = quadric_value(q, of);
  // When both roots lie near the vertex of f along the ray (4ac >= b^2 / 2:
  // they are within 0.71 of its distance from it, or there are none), b^2
  // and 4ac nearly cancel and the discriminant drowns in their rounding: a
  // spheroid x^2 + 1e12 y^2 + z^2 = 1 lost hits that way. Re-centred at the
  // vertex, b is ~0 and c is f's extreme value, formed directly.
  if (a != 0.0 && 4.0 * a * c >= 0.5 * b * b) {
    const double tv = -b / (2.0 * a);
    if (std::isfinite(tv)) {
      of += tv * d;
      tf += tv;
      b = glm::dot(quadric_gradient(q, of), d);
      c = quadric_value(q, of);
    }
  }
  double s[2];
  int n = solve_quadratic(a, b, c, s[0], s[1]);
  for (int i = 0; i < n; ++i) {
    double ti = tf + s[i];
    if (!(ti > tmin && ti <= tmax) || !std::isfinite(ti)) continue;
    glm::dvec3 pi = of + s[i] * d;
    if (!quadric_in_clip(q, pi)) continue;
    t = ti;
    p = pi;
    return true;
  }
  return false;
}

// Re-projects a hit point onto f = 0 with one Newton step along the gradient
// (the hit is already within rounding of the surface, so one step squares
// that error) and returns the gradient there as the outward normal, scaled
// so its largest component is 1 (tiny coefficients must not underflow it).
// Where the gradient vanishes (a cone's apex) the normal is all zeros and
// the core falls back to -dir, as the spec says.
inline void quadric_surface(const QuadricShape& q, glm::dvec3 p, glm::dvec3& point, glm::dvec3& normal) {
  glm::dvec3 g = quadric_gradient(q, p);
  double m = max_abs_component(g);
  if (m > 0.0 && std::isfinite(m)) {
    glm::dvec3 gs = g / m;
    glm::dvec3 step = (quadric_value(q, p) / m / glm::dot(gs, gs)) * gs;
    if (std::isfinite(step.x) && std::isfinite(step.y) && std::isfinite(step.z)) p -= step;
    g = quadric_gradient(q, p);
    m = max_abs_component(g);
  }
  point = p;
  normal = (m > 0.0 && std::isfinite(m)) ? g / m : glm::dvec3(0.0);
}

// The descriptor's `intersect` for any plugin whose record begins with a
// QuadricShape (quadric, cylinder, cone): one code path for all three.
inline int intersect_quadric_record(const void* record, const PrismRay* ray, double tmin, double tmax,
                                    PrismHit* hit) {
  double t = 0.0;
  glm::dvec3 p(0.0);
  if (!intersect_quadric(record_of<QuadricShape>(record), load3(ray->origin), load3(ray->dir), tmin, tmax, t, p))
    return 0;
  *hit = PrismHit{};
  hit->t = t;
  store3(p, hit->data);
  return 1;
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

// Point and normal of a hit from intersect_quadric_record (uv is the caller's).
inline void quadric_record_surface(const void* record, const PrismHit* hit, glm::dvec3& point, glm::dvec3& normal) {
  quadric_surface(record_of<QuadricShape>(record), load3(hit->data), point, normal);
}

}  // namespace prism::sdk
