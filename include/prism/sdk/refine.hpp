// Extended-precision polish of a hit, for a plugin's `refine` entry
// (primitive_abi.h).
//
// A double intersector is backward stable at best: it returns the exact hit
// of a ray perturbed by an ulp or so. Where the answer is ill-conditioned,
// an ulp matters: a ray grazing a surface at angle a moves its t by
// eps * |o| / a (1e-9 relative at a = 1e-7), and a hit 1e6 units from the
// object's origin loses eps * 1e6 to the core's move into the local frame.
// The core then hands the plugin the same ray built in long double (64-bit
// mantissa on x86-64), and a Newton step or two on the surface's implicit
// equation, evaluated in that precision from the double t, brings t to
// ~1e-19 * |o| / a. Newton from the double t converges to the double t's
// root because that t is far closer to it than to any other root (the other
// root of a grazing ray is 2 r a away, the double error eps |o| / a).
#pragma once

#include <cmath>
#include <limits>

#include "prism/primitive_abi.h"

namespace prism::sdk {

struct Vec3x {
  long double x = 0, y = 0, z = 0;
};

inline Vec3x operator+(const Vec3x& a, const Vec3x& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3x operator-(const Vec3x& a, const Vec3x& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3x operator*(long double s, const Vec3x& v) { return {s * v.x, s * v.y, s * v.z}; }
inline long double dot(const Vec3x& a, const Vec3x& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3x load3x(const long double v[3]) { return {v[0], v[1], v[2]}; }
inline Vec3x load3x(const double v[3]) { return {v[0], v[1], v[2]}; }

inline void store3(const Vec3x& v, double out[3]) {
  out[0] = static_cast<double>(v.x);
  out[1] = static_cast<double>(v.y);
  out[2] = static_cast<double>(v.z);
}

// An implicit function's value and gradient at a point; the surface is
// value = 0. Any scale works: Newton divides it out.
struct ImplicitSample {
  long double value;
  Vec3x gradient;
};

// Newton on g(origin + t dir) = 0 from hit.t. On success sets hit.t (and
// `point` to the polished local point) and returns true; returns false and
// leaves the hit alone when a step is not finite or the slope of g along the
// ray changes sign (the iteration left the root's basin for its neighbour).
template <class Implicit>
bool polish_hit(const PrismRayExt& ray, PrismHit& hit, Implicit&& g, Vec3x* point = nullptr) {
  const Vec3x o = load3x(ray.origin), d = load3x(ray.dir);
  constexpr long double kTolerance = 4 * std::numeric_limits<long double>::epsilon();
  long double t = hit.t;
  Vec3x p = o + t * d;
  ImplicitSample s = g(p);
  const long double first_slope = dot(s.gradient, d);
  for (int step = 0; step < 4; ++step) {
    const long double slope = dot(s.gradient, d);
    if (!(slope != 0) || std::signbit(slope) != std::signbit(first_slope)) return false;
    const long double dt = s.value / slope;
    if (!std::isfinite(dt)) return false;
    t -= dt;
    p = o + t * d;
    if (std::fabs(dt) <= kTolerance * std::fabs(t)) break;
    s = g(p);
  }
  if (std::signbit(dot(g(p).gradient, d)) != std::signbit(first_slope)) return false;
  hit.t = static_cast<double>(t);
  if (point) *point = p;
  return true;
}

// The implicit function of the quadric with coefficients A..J (quadric_math.hpp's order).
inline ImplicitSample quadric_implicit(const long double c[10], const Vec3x& p) {
  return {p.x * (c[0] * p.x + c[3] * p.y + c[5] * p.z + c[6]) + p.y * (c[1] * p.y + c[4] * p.z + c[7]) +
              p.z * (c[2] * p.z + c[8]) + c[9],
          {2 * c[0] * p.x + c[3] * p.y + c[5] * p.z + c[6], 2 * c[1] * p.y + c[3] * p.x + c[4] * p.z + c[7],
           2 * c[2] * p.z + c[4] * p.y + c[5] * p.x + c[8]}};
}

}  // namespace prism::sdk
