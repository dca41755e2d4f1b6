// Directions read from input files (a scene's camera and lights, the rays of
// `prism trace`) come with any magnitude a double holds; |v|^2 overflows
// beyond ~1e154 and loses bits (or vanishes) below ~1e-154.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace prism {

// `v` times the power of two that brings its largest component into [1, 2);
// zero and non-finite vectors come back unchanged. The scaling is exact, so
// glm::normalize(rescaled(v)) gives the same bits as glm::normalize(v) for
// every v whose |v|^2 neither overflows nor underflows, and a unit vector
// for the others.
inline glm::dvec3 rescaled(const glm::dvec3& v) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(largest > 0) || !std::isfinite(largest)) return v;
  const int exponent = std::ilogb(largest);
  return {std::ldexp(v.x, -exponent), std::ldexp(v.y, -exponent), std::ldexp(v.z, -exponent)};
}

}  // namespace prism
