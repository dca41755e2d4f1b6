// Cone plugin tests: hand-derived hits (x = +-k y on the xy cross-section),
// the apex, generator-parallel rays, and bit-identity with the quadric the
// spec says it stands for.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string_view>

#include "prism/sdk/plugin_testing.hpp"
#include "prism/sdk/quadric_math.hpp"

extern "C" const PrismPrimitiveDesc* prism_primitive_entry(void);

namespace {

using glm::dvec3;
using prism::sdk::kInf;
using namespace prism::sdk::testing;
using ld = long double;

Shape cone(double radius, double height) { return Shape(prism_primitive_entry(), {radius, height}); }

TEST(ConeTest, DescriptorDeclaresRadiusAndHeight) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_STREQ(desc.type_name, "cone");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, PRISM_PRIMITIVE_TRANSFORMABLE);
  ASSERT_EQ(desc.field_count, 2u);
  for (const char* name : {"radius", "height"})
    EXPECT_EQ(find_field(desc, name)->flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH);
  EXPECT_EQ(desc.record_size % 16, 0u);
}

TEST(ConeTest, SideHitFromOutsideGivesGradientNormalAndUv) {
  Shape s = cone(1.0, 2.0);  // x^2 + z^2 = y^2 / 4
  auto hit = s.intersect({0, 1, -5}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 4.5);
  Surface surf = s.surface({0, 1, -5}, {0, 0, 1}, *hit);
  EXPECT_EQ(surf.normal, dvec3(0, -0.5, -1));  // grad (2x, -y/2, 2z) at (0, 1, -0.5)
  EXPECT_DOUBLE_EQ(surf.uv.x, 0.25);
  EXPECT_DOUBLE_EQ(surf.uv.y, 0.5);
}

TEST(ConeTest, RayDownThroughOpenEndHitsInnerWall) {
  Shape s = cone(1.0, 2.0);
  auto hit = s.intersect({0.2, 5, 0}, {0, -1, 0});  // x = y/2 at y = 0.4
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.6, 1e-15);
  Surface surf = s.surface({0.2, 5, 0}, {0, -1, 0}, *hit);
  EXPECT_NEAR(surf.normal.x, 1.0, 1e-15);  // grad (0.4, -0.2, 0) scaled to max 1
  EXPECT_NEAR(surf.normal.y, -0.5, 1e-15);
  EXPECT_NEAR(surf.uv.y, 0.2, 1e-15);
}

TEST(ConeTest, ApexHitAlongAxisHasZeroNormal) {
  Shape s = cone(1.0, 2.0);
  auto hit = s.intersect({0, -1, 0}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 1.0);
  EXPECT_EQ(s.surface({0, -1, 0}, {0, 1, 0}, *hit).normal, dvec3(0.0));
  hit = s.intersect({0, 5, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 5.0);
  EXPECT_EQ(s.surface({0, 5, 0}, {0, -1, 0}, *hit).normal, dvec3(0.0));
}

TEST(ConeTest, LowerNappeAndAboveHeightAreClipped) {
  Shape s = cone(1.0, 2.0);
  EXPECT_FALSE(s.intersect({-5, -1, 0}, {1, 0, 0}));
  EXPECT_FALSE(s.intersect({-5, 3, 0}, {1, 0, 0}));
}

TEST(ConeTest, RayParallelToGeneratorSolvesLinearly) {
  // d = normalize(0.5, 1, 0) has dx = dy/2 exactly, so a = dx^2 - dy^2/4 == 0.
  // The remaining root is on x = -y/2: t = (-oy/2 - ox) / (dx + dy/2).
  Shape s = cone(1.0, 2.0);
  dvec3 o(-1, 0.5, 0), d = glm::normalize(dvec3(0.5, 1, 0));
  ASSERT_EQ(d.x * d.x - 0.25 * (d.y * d.y), 0.0);
  auto hit = s.intersect(o, d);
  ASSERT_TRUE(hit);
  ld want = (-0.25L + 1.0L) / ((ld)d.x + 0.5L * d.y);
  EXPECT_LT(rel_err(hit->t, (double)want), 1e-15);
}

TEST(ConeTest, NearlyGeneratorParallelRayKeepsNearRoot) {
  // Tiny a ~ 1e-9: the far root runs off to ~1e9 (clipped); the near one stays exact.
  Shape s = cone(1.0, 2.0);
  dvec3 o(-1, 0.5, 0), d = glm::normalize(dvec3(0.5 + 1e-9, 1, 0));
  auto hit = s.intersect(o, d);
  ASSERT_TRUE(hit);
  ld want = (-0.25L + 1.0L) / ((ld)d.x + 0.5L * d.y);
  EXPECT_LT(rel_err(hit->t, (double)want), 1e-14);
  EXPECT_FALSE(s.intersect(o, d, hit->t));
}

TEST(ConeTest, BitIdenticalToEquivalentQuadricOnRandomRays) {
  std::mt19937_64 rng(51);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int hits = 0;
  for (int k = 0; k < 6; ++k) {
    double radius = std::pow(10.0, -2 + 4 * u01(rng)), height = std::pow(10.0, -2 + 4 * u01(rng));
    Shape s = cone(radius, height);
    double slope = radius / height;
    const double coef[10] = {1, -(slope * slope), 1, 0, 0, 0, 0, 0, 0, 0};
    const double lo[3] = {-kInf, 0, -kInf}, hi[3] = {kInf, height, kInf};
    prism::sdk::QuadricShape q = prism::sdk::make_quadric(coef, lo, hi);
    for (int i = 0; i < 60; ++i) {
      dvec3 o = (radius + height) * std::pow(10.0, 3 * u01(rng)) * random_unit(rng);
      dvec3 d = glm::normalize(dvec3(radius, height, radius) * random_unit(rng) - o);
      double tmin = i % 4 == 0 ? 0.5 * glm::length(o) : 0.0, t = 0;
      dvec3 p, point, normal;
      bool want = prism::sdk::intersect_quadric(q, o, d, tmin, kInf, t, p);
      auto hit = s.intersect(o, d, tmin);
      ASSERT_EQ(hit.has_value(), want);
      if (!hit) continue;
      ++hits;
      EXPECT_EQ(hit->t, t);
      prism::sdk::quadric_surface(q, p, point, normal);
      Surface surf = s.surface(o, d, *hit);
      EXPECT_EQ(surf.point, point);
      EXPECT_EQ(surf.normal, normal);
    }
  }
  EXPECT_GT(hits, 100);
}

TEST(ConeTest, BoundsAreTheOpenEndBox) {
  Shape s = cone(0.5, 3.0);
  double lo[3], hi[3];
  ASSERT_EQ(s.desc().bounds(s.record(), lo, hi), 1);
  EXPECT_EQ(dvec3(lo[0], lo[1], lo[2]), dvec3(-0.5, 0, -0.5));
  EXPECT_EQ(dvec3(hi[0], hi[1], hi[2]), dvec3(0.5, 3, 0.5));
}

TEST(ConeTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "cone", {"quadric"}), "");
}

TEST(ConeTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // The ray's origin.x carries 2^-58 more in long double than a double can hold;
  // where it grazes the surface that moves t by ~2e-12 relative, which only a
  // polish of the long double ray can see (to ~1e-19 / 1.7e-7 rad, a few
  // 1e-14 relative). Expected t: mpmath at 300 bits.
  // The slope (1/3)^2 is not a double: the polish forms it in long double.
  Shape s = cone(1.0, 3.0);  // radius 0.5 at y = 1.5
  const double c = 0.5 - 0x1p-47;
  auto hit = s.intersect({c, 1.5, -10}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(s.refine({c + 0x1p-58L, 1.5, -10}, {0, 0, 1}, *hit).t, 9.999999915726885006848134), 1e-13);
}

}  // namespace
