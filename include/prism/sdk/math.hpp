// Numeric building blocks shared by the primitive plugins (and the core).
//
// Everything here is double precision and free of absolute epsilons: the
// only exact-zero tests are the ones the spec asks for (a quadratic whose t^2
// coefficient is exactly 0 is linear). See docs/numerics.md for why
// each form was chosen. The functions shared with the GPU are written once,
// in prism/sdk/modules/library.shared.glsl; these are their double
// instantiations (prism::sdk::f64) under the C++ SDK's names.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "prism/sdk/library.hpp"

#define PRISM_SHARED_SOURCE "prism/sdk/modules/roots.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace prism::sdk {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

// The spec's clamped domains: asin/acos/sqrt never see an argument that
// rounding pushed just outside their domain.
inline double safe_sqrt(double x) { return std::sqrt(std::max(x, 0.0)); }
inline double safe_asin(double x) { return std::asin(std::clamp(x, -1.0, 1.0)); }
inline double safe_acos(double x) { return std::acos(std::clamp(x, -1.0, 1.0)); }

// std::atan2 already returns 0 for atan2(0, 0) (and +-0/+-pi for signed
// zeros); named so that call sites read as the spec does.
inline double atan2_spec(double y, double x) { return std::atan2(y, x); }

// The spec's azimuth texture coordinate: 0.5 + atan2(y, x) / 2pi, in [0, 1].
inline double turn_fraction(double y, double x) { return f64::prism_turn_fraction(y, x); }

// a*b - c*d with one rounding (Kahan's algorithm via fma).
inline double difference_of_products(double a, double b, double c, double d) {
  return f64::prism_difference_of_products(a, b, c, d);
}

// Real roots of a t^2 + b t + c = 0 in ascending order; returns how many
// (0, 1 or 2; a double root is reported twice; library.shared.glsl says how).
inline int solve_quadratic(double a, double b, double c, double& t0, double& t1) {
  return f64::prism_solve_quadratic(a, b, c, t0, t1);
}

// Safeguarded Newton-bisection for a root of fn in [a, b], given fa = fn(a)
// and fb = fn(b) on opposite sides of zero (fa > 0 != fb > 0). fn(s, f, df)
// fills the value and the derivative. It starts from the secant point and
// bisects whenever a Newton step would leave the current bracket (or the
// derivative is 0 or NaN), so the result always lies in [a, b]. It stops
// after a Newton step shorter than `tol` (which leaves an error ~tol^2) or
// once the bracket itself is narrower than `tol`.
// The steps are prism/sdk/modules/roots.shared.glsl's, which the GPU runs too.
template <class Fn>
double solve_bracketed(const Fn& fn, double a, double b, double fa, double fb, double tol) {
  f64::PrismBracket bracket = f64::prism_bracket_start(a, b, fa, fb, tol);
  for (int i = 0; i < PRISM_BRACKET_MAX_STEPS; ++i) {
    double f = 0.0, df = 0.0;
    fn(bracket.s, f, df);
    if (f64::prism_bracket_step(bracket, f, df)) break;
  }
  return bracket.s;
}

// Unit vector along v without underflow or overflow of |v|^2.
inline glm::dvec3 safe_normalize(const glm::dvec3& v) { return f64::prism_safe_normalize(v); }

inline double max_abs_component(const glm::dvec3& v) { return f64::prism_max_abs_component(v); }

// Parameter of the foot of the perpendicular from the local origin to the
// ray (d unit), where a far ray origin is moved before solving.
inline double foot_parameter(const glm::dvec3& o, const glm::dvec3& d) { return f64::prism_foot_parameter(o, d); }

}  // namespace prism::sdk
