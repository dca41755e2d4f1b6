// Ring plugin tests; expected values by hand or in long double.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string_view>

#include "prism/sdk/plugin_testing.hpp"

extern "C" const PrismPrimitiveDesc* prism_primitive_entry(void);

namespace {

using glm::dvec3;
using prism::sdk::kInf;
using namespace prism::sdk::testing;

Shape ring(double inner, double outer) { return Shape(prism_primitive_entry(), {inner, outer}); }

TEST(RingTest, DescriptorDefaultsInnerRadiusToZero) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_STREQ(desc.type_name, "ring");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, PRISM_PRIMITIVE_TRANSFORMABLE);
  const PrismField* inner = find_field(desc, "inner_radius");
  ASSERT_NE(inner, nullptr);
  EXPECT_EQ(inner->flags, PRISM_FIELD_LENGTH);  // >= 0, optional
  EXPECT_EQ(inner->min, 0.0);
  ASSERT_NE(inner->defaults, nullptr);
  EXPECT_EQ(inner->defaults[0], 0.0);
  const PrismField* outer = find_field(desc, "outer_radius");
  ASSERT_NE(outer, nullptr);
  EXPECT_EQ(outer->flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH);
  EXPECT_EQ(desc.record_size % 16, 0u);
}

TEST(RingTest, ValidateRejectsOuterNotAboveInner) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  auto err = validation_error(desc, {1.0, 0.5});
  ASSERT_TRUE(err);
  EXPECT_STREQ(err->field, "outer_radius");
  EXPECT_STREQ(err->message, "must be > inner_radius (1), got 0.5");
  EXPECT_TRUE(validation_error(desc, {2.0, 2.0}));
  EXPECT_EQ(validation_error(desc, {0.0, 1e-7}), std::nullopt);
}

TEST(RingTest, HitsFromBothSidesWithTheSameNormalAndSpecUv) {
  Shape s = ring(1.0, 2.0);
  for (double side : {1.0, -1.0}) {
    dvec3 o(0, 3 * side, 1.5), d(0, -side, 0);
    auto hit = s.intersect(o, d);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->t, 3.0);
    Surface surf = s.surface(o, d, *hit);
    EXPECT_EQ(surf.normal, dvec3(0, 1, 0));
    EXPECT_EQ(surf.point, dvec3(0, 0, 1.5));
    EXPECT_DOUBLE_EQ(surf.uv.x, 0.5);   // (1.5 - 1) / (2 - 1)
    EXPECT_DOUBLE_EQ(surf.uv.y, 0.75);  // 0.5 + atan2(1.5, 0)/2pi
  }
}

TEST(RingTest, HoleAndOutsideMissAndEdgesAreInclusive) {
  Shape s = ring(1.0, 2.0);
  EXPECT_FALSE(s.intersect({0.5, 1, 0}, {0, -1, 0}));
  EXPECT_FALSE(s.intersect({2.5, 1, 0}, {0, -1, 0}));
  EXPECT_TRUE(s.intersect({2, 1, 0}, {0, -1, 0}));
  EXPECT_TRUE(s.intersect({0, 1, -1}, {0, -1, 0}));
  auto hit = s.intersect({0, 1, -1}, {0, -1, 0});
  EXPECT_EQ(s.surface({0, 1, -1}, {0, -1, 0}, *hit).uv.x, 0.0);
}

TEST(RingTest, DefaultInnerRadiusGivesFullDiskThroughCentre) {
  Shape s = ring(0.0, 1.0);
  auto hit = s.intersect({0, 2, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  Surface surf = s.surface({0, 2, 0}, {0, -1, 0}, *hit);
  EXPECT_EQ(surf.uv.x, 0.0);
  EXPECT_EQ(surf.uv.y, 0.5);  // atan2(0, 0) = 0
}

TEST(RingTest, ParallelRayInPlaneOrAboveMisses) {
  Shape s = ring(0.0, 1.0);
  EXPECT_FALSE(s.intersect({-5, 0, 0}, {1, 0, 0}));
  EXPECT_FALSE(s.intersect({-5, 0.1, 0}, {1, 0, 0}));
  EXPECT_FALSE(s.intersect({0, 1, 0}, {0, -1, 0}, 0.0, 0.5));
  EXPECT_FALSE(s.intersect({0, 1, 0}, {0, -1, 0}, 1.0));
}

TEST(RingTest, ObliqueRaysFrom1e4MatchLongDoubleReference) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Shape s = ring(0.5, 1.0);
  int compared = 0;
  for (int i = 0; i < 2000; ++i) {
    dvec3 o = 1e4 * random_unit(rng);
    dvec3 d = glm::normalize(dvec3(1.2 * (2 * u01(rng) - 1), 0, 1.2 * (2 * u01(rng) - 1)) - o);
    long double t = -(long double)o.y / d.y;
    long double x = o.x + t * d.x, z = o.z + t * d.z, radius = std::sqrt(x * x + z * z);
    if (std::abs(radius - 0.5L) < 1e-9L || std::abs(radius - 1.0L) < 1e-9L) continue;  // edge band
    bool want = t > 0 && radius >= 0.5L && radius <= 1.0L;
    auto hit = s.intersect(o, d);
    ASSERT_EQ(hit.has_value(), want) << i;
    if (!hit) continue;
    EXPECT_LT(rel_err(hit->t, (double)t), 1e-13);
    // The origin itself is only known to ~eps * 1e4; the plane crossing
    // amplifies that by 1/|d.y|.
    double tol = 4e-16 * 1e4 / std::abs(d.y);
    Surface surf = s.surface(o, d, *hit);
    EXPECT_NEAR(surf.point.x, (double)x, tol);
    EXPECT_NEAR(surf.point.z, (double)z, tol);
    ++compared;
  }
  EXPECT_GT(compared, 500);
}

TEST(RingTest, BoundsAreFlatInY) {
  Shape s = ring(0.5, 3.0);
  double lo[3], hi[3];
  ASSERT_EQ(s.desc().bounds(s.record(), lo, hi), 1);
  EXPECT_EQ(dvec3(lo[0], lo[1], lo[2]), dvec3(-3, 0, -3));
  EXPECT_EQ(dvec3(hi[0], hi[1], hi[2]), dvec3(3, 0, 3));
}

TEST(RingTest, NanRayMisses) {
  Shape s = ring(0.5, 1.0);
  EXPECT_FALSE(s.intersect({NAN, 1, 0}, {0, -1, 0}));
  EXPECT_FALSE(s.intersect({0, 1, 0}, {NAN, NAN, NAN}));
}

TEST(RingTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "ring", {}), "");
}

TEST(RingTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // The ray descends to the ring's plane at 2^-20 rad from 2^-20 above it;
  // the long double origin is 2^-56 higher, so it lands at t = 1 + 2^-36.
  Shape s = ring(0.25, 2.0);
  const dvec3 d(1, -0x1p-20, 0);
  auto hit = s.intersect({-1.5, 0x1p-20, 0}, d);
  ASSERT_TRUE(hit);
  Hit polished = s.refine({-1.5, 0x1p-20L + 0x1p-56L, 0}, {d.x, d.y, d.z}, *hit);
  EXPECT_NEAR(polished.t, 1.0 + 0x1p-36, 1e-12);  // long double error / 2^-20: ~6e-14
  EXPECT_NEAR(s.surface({-1.5, 0x1p-20, 0}, d, polished).point.x, -0.5 + 0x1p-36, 1e-12);
}

}  // namespace
