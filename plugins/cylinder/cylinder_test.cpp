// Cylinder plugin tests: hand-derived hits and uv, and bit-identity with the
// quadric the spec says it stands for.
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

Shape cylinder(double radius, double height) { return Shape(prism_primitive_entry(), {radius, height}); }

TEST(CylinderTest, DescriptorDeclaresRadiusAndHeight) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_STREQ(desc.type_name, "cylinder");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, PRISM_PRIMITIVE_TRANSFORMABLE);
  ASSERT_EQ(desc.field_count, 2u);
  for (const char* name : {"radius", "height"})
    EXPECT_EQ(find_field(desc, name)->flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH);
  EXPECT_EQ(desc.record_size % 16, 0u);
}

TEST(CylinderTest, SideHitFromOutsideGivesGradientNormalAndUv) {
  Shape s = cylinder(1.0, 2.0);
  auto hit = s.intersect({0, 1, -5}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 4.0);
  Surface surf = s.surface({0, 1, -5}, {0, 0, 1}, *hit);
  EXPECT_EQ(surf.normal, dvec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(surf.uv.x, 0.25);  // 0.5 + atan2(-1, 0)/2pi
  EXPECT_DOUBLE_EQ(surf.uv.y, 0.5);   // y / height
}

TEST(CylinderTest, UvAtFortyFiveDegrees) {
  Shape s = cylinder(2.0, 4.0);
  dvec3 n = glm::normalize(dvec3(1, 0, 1));
  dvec3 o = dvec3(0, 3, 0) + 5.0 * n;
  auto hit = s.intersect(o, -n);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 3.0, 1e-15);
  Surface surf = s.surface(o, -n, *hit);
  EXPECT_NEAR(surf.uv.x, 0.625, 1e-15);
  EXPECT_NEAR(surf.uv.y, 0.75, 1e-15);
}

TEST(CylinderTest, HitFromInsideHasOutwardNormal) {
  Shape s = cylinder(1.0, 2.0);
  auto hit = s.intersect({0, 1, 0}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 1.0);
  Surface surf = s.surface({0, 1, 0}, {1, 0, 0}, *hit);
  EXPECT_EQ(surf.normal, dvec3(1, 0, 0));
  EXPECT_EQ(surf.uv.x, 0.5);
}

TEST(CylinderTest, OpenEndsLetRaysThroughAndClipAboveAndBelow) {
  Shape s = cylinder(1.0, 2.0);
  EXPECT_FALSE(s.intersect({0.5, 5, 0}, {0, -1, 0}));  // along the axis: a == 0 and b == 0
  EXPECT_FALSE(s.intersect({0, 3, -5}, {0, 0, 1}));
  EXPECT_FALSE(s.intersect({0, -0.5, -5}, {0, 0, 1}));
  dvec3 d = glm::normalize(dvec3(1, -1, 0));
  auto hit = s.intersect({0, 2.5, 0}, d);  // in through the top, onto the inner wall
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, std::sqrt(2.0), 1e-15);
}

TEST(CylinderTest, NearRootBelowBaseFallsThroughToInnerWall) {
  Shape s = cylinder(1.0, 2.0);
  dvec3 d = glm::normalize(dvec3(1, 1, 0));
  auto hit = s.intersect({-2, -1.5, 0}, d);  // x = -1 at y = -0.5 (clipped), x = 1 at y = 1.5
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 3.0 * std::sqrt(2.0), 1e-14);
  EXPECT_EQ(s.surface({-2, -1.5, 0}, d, *hit).normal, dvec3(1, 0, 0));
}

TEST(CylinderTest, NearTangentRayFrom1e4) {
  Shape s = cylinder(1.0, 2.0);
  double c = 1.0 - 1e-10;
  auto hit = s.intersect({-1e4, 1, c}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(hit->t, (double)(1e4L - std::sqrt((1.0L - c) * (1.0L + c)))), 1e-12);
  EXPECT_FALSE(s.intersect({-1e4, 1, 1.0 + 1e-10}, {1, 0, 0}));
}

TEST(CylinderTest, BitIdenticalToEquivalentQuadricOnRandomRays) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int hits = 0;
  for (int k = 0; k < 6; ++k) {
    double radius = std::pow(10.0, -2 + 4 * u01(rng)), height = std::pow(10.0, -2 + 4 * u01(rng));
    Shape s = cylinder(radius, height);
    const double coef[10] = {1, 0, 1, 0, 0, 0, 0, 0, 0, -(radius * radius)};
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

TEST(CylinderTest, BoundsAreTheTubeBox) {
  Shape s = cylinder(0.5, 3.0);
  double lo[3], hi[3];
  ASSERT_EQ(s.desc().bounds(s.record(), lo, hi), 1);
  EXPECT_EQ(dvec3(lo[0], lo[1], lo[2]), dvec3(-0.5, 0, -0.5));
  EXPECT_EQ(dvec3(hi[0], hi[1], hi[2]), dvec3(0.5, 3, 0.5));
}

TEST(CylinderTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "cylinder", {"quadric"}), "");
}

TEST(CylinderTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // The ray's origin.x carries 2^-58 more in long double than a double can hold;
  // where it grazes the surface that moves t by ~2e-12 relative, which only a
  // polish of the long double ray can see (to ~1e-19 / 1.7e-7 rad, a few
  // 1e-14 relative). Expected t: mpmath at 300 bits.
  Shape s = cylinder(1.0, 2.0);
  const double c = 1.0 - 0x1p-46;
  auto hit = s.intersect({c, 1, -10}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(s.refine({c + 0x1p-58L, 1, -10}, {0, 0, 1}, *hit).t, 9.999999831433186728526251), 1e-13);
}

}  // namespace
