// highlight_vanishes (prism/phong_bound.hpp) against what it claims: where
// it says the Phong term vanishes, adding specular * pow(highlight,
// shininess) leaves every diffuse channel bit for bit as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "prism/phong_bound.hpp"

namespace prism {
namespace {

TEST(PhongBound, ATermItCallsVanishingChangesNoChannel) {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int vanished = 0;
  for (int i = 0; i < 200000; ++i) {
    const double specular = std::ldexp(unit(rng) + 0.5, -int(rng() % 8));
    const double highlight = unit(rng) < 0.5 ? unit(rng) : 1.0 - std::ldexp(unit(rng), -int(rng() % 40));
    const double shininess = 1.0 + unit(rng) * (unit(rng) < 0.5 ? 300.0 : 3000.0);
    const glm::dvec3 diffuse(std::ldexp(unit(rng) + 0.5, -int(rng() % 60)), unit(rng) + 1e-3,
                             std::ldexp(unit(rng) + 0.5, -int(rng() % 20)));
    if (!highlight_vanishes(specular, highlight, shininess, diffuse)) continue;
    ++vanished;
    const double phong = specular * std::pow(highlight, shininess);
    for (int c = 0; c < 3; ++c) ASSERT_EQ(diffuse[c] + phong, diffuse[c]) << specular << " " << highlight << " " << shininess;
  }
  EXPECT_GT(vanished, 20000);  // the test exercises the claim, not only its refusals
}

TEST(PhongBound, HandWorkedCases) {
  // 0.4^64 < 2^-64: specular 1 (exponent_above 1), diffuse 0.5 (>= 2^-1): 1 - 2 * 64 <= -1 - 55.
  EXPECT_TRUE(highlight_vanishes(1.0, 0.4, 64.0, glm::dvec3(0.5)));
  // 0.6^64 ~ 6e-15 is far above 0.5 * 2^-54 ~ 2.8e-17, and the exponent bound says 1: no.
  EXPECT_FALSE(highlight_vanishes(1.0, 0.6, 64.0, glm::dvec3(0.5)));
  // A channel of 0 (a black texel) takes any term: never vanishes.
  EXPECT_FALSE(highlight_vanishes(1.0, 1e-300, 1000.0, glm::dvec3(0.5, 0.0, 0.5)));
  // A highlight of 1 or more, or NaN anywhere, is left to pow.
  EXPECT_FALSE(highlight_vanishes(1.0, 1.0, 64.0, glm::dvec3(0.5)));
  EXPECT_FALSE(highlight_vanishes(1.0, 0.1, 64.0, glm::dvec3(std::nan(""))));
}

}  // namespace
}  // namespace prism
