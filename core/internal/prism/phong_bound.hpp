// When the Phong term cannot change a shaded colour, so that pow() need not
// run (core/src/shading.cpp; tests/core/phong_bound_test.cpp).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

namespace prism {

// The k for which x < 2^k, for a finite x > 0, read from its exponent bits
// (a subnormal x gives -1022: it is below 2^-1022).
inline int exponent_above(double x) { return int((std::bit_cast<uint64_t>(x) >> 52) & 0x7ffu) - 1022; }

// Whether the Phong term specular * highlight^shininess (specular > 0,
// highlight > 0, shininess >= 1), added to every channel of the diffuse
// term, leaves each of them as it is. A normal a > 0 has an ulp above
// a * 2^-53, so a + x rounds back to a for 0 <= x < a * 2^-54; the bound
// below puts x under 2^(floor(log2 a) - 55), a factor 2 to spare for the
// rounding of pow, of the product and of exponent * shininess. Only a
// narrow highlight seen from well off its axis passes (highlight < 1/2
// gives x < specular * 2^-shininess).
inline bool highlight_vanishes(double specular, double highlight, double shininess, const glm::dvec3& diffuse) {
  const double least = std::min(std::min(diffuse.x, diffuse.y), diffuse.z);
  if (!(least >= std::numeric_limits<double>::min()) || !(highlight < 1.0)) return false;
  const int least_exponent = exponent_above(least) - 1;  // least >= 2^least_exponent (least is normal)
  return exponent_above(specular) + exponent_above(highlight) * shininess <= least_exponent - 55;
}

}  // namespace prism
