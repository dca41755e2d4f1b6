// Plane plugin tests. The tangent frames below were worked out by hand from
// the spec's formula (see each test's comment).
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

Shape plane(dvec3 point, dvec3 normal, double uv_scale = 1.0) {
  return Shape(prism_primitive_entry(), {point.x, point.y, point.z, normal.x, normal.y, normal.z, uv_scale});
}

TEST(PlaneTest, DescriptorIsNotTransformableAndDefaultsUvScaleToOne) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_STREQ(desc.type_name, "plane");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, 0u);
  ASSERT_EQ(desc.field_count, 3u);
  EXPECT_EQ(find_field(desc, "point")->flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_LENGTH);
  EXPECT_EQ(find_field(desc, "normal")->flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_NONZERO);
  const PrismField* scale = find_field(desc, "uv_scale");
  EXPECT_EQ(scale->flags, PRISM_FIELD_MIN_EXCLUSIVE);
  EXPECT_EQ(scale->min, 0.0);
  ASSERT_NE(scale->defaults, nullptr);
  EXPECT_EQ(scale->defaults[0], 1.0);
  EXPECT_EQ(desc.record_size % 16, 0u);
  EXPECT_EQ(validation_error(desc, {0, 0, 0, 0, 1, 0, 1}), std::nullopt);
}

TEST(PlaneTest, BothSidesHitAndNormalIsTheGivenOne) {
  Shape s = plane({0, 1, 0}, {0, 2, 0});
  for (dvec3 o : {dvec3(0, 5, 0), dvec3(0, -3, 0)}) {
    dvec3 d(0, o.y > 1 ? -1 : 1, 0);
    auto hit = s.intersect(o, d);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->t, 4.0);
    Surface surf = s.surface(o, d, *hit);
    EXPECT_EQ(glm::normalize(surf.normal), dvec3(0, 1, 0));  // not the facing normal
    EXPECT_EQ(surf.point.y, 1.0);
  }
}

TEST(PlaneTest, UvUsesXAxisHelperWhenNormalIsAlongY) {
  // m = (0,1,0): helper (1,0,0), t1 = (0,0,1), t2 = (1,0,0).
  Shape s = plane({1, 0, 2}, {0, 1, 0}, 0.5);
  auto hit = s.intersect({4, 3, -1}, {0, -1, 0});
  ASSERT_TRUE(hit);
  Surface surf = s.surface({4, 3, -1}, {0, -1, 0}, *hit);
  EXPECT_DOUBLE_EQ(surf.uv.x, -1.5);  // dot((3,0,-3), t1) * 0.5
  EXPECT_DOUBLE_EQ(surf.uv.y, 1.5);   // dot((3,0,-3), t2) * 0.5
}

TEST(PlaneTest, UvUsesYAxisHelperWhenNormalIsAlongMinusZ) {
  // m = (0,0,-1): t1 = cross((0,1,0), m) = (-1,0,0), t2 = cross(m, t1) = (0,1,0).
  Shape s = plane({0, 0, 5}, {0, 0, -3});
  auto hit = s.intersect({2, 3, 0}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 5.0);
  Surface surf = s.surface({2, 3, 0}, {0, 0, 1}, *hit);
  EXPECT_DOUBLE_EQ(surf.uv.x, -2.0);
  EXPECT_DOUBLE_EQ(surf.uv.y, 3.0);
}

TEST(PlaneTest, UvOnTiltedPlaneFollowsHandDerivedFrame) {
  // m = (1,2,2)/3: t1 = (2,0,-1)/sqrt5, t2 = (-2,5,-4)/(3 sqrt5).
  dvec3 m = dvec3(1, 2, 2) / 3.0;
  dvec3 t1 = dvec3(2, 0, -1) / std::sqrt(5.0), t2 = dvec3(-2, 5, -4) / (3.0 * std::sqrt(5.0));
  dvec3 point(0.5, -1, 2);
  Shape s = plane(point, {1, 2, 2}, 2.0);
  dvec3 target = point + 2.0 * t1 + 3.0 * t2;
  auto hit = s.intersect(target + 7.0 * m, -m);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 7.0, 1e-14);
  Surface surf = s.surface(target + 7.0 * m, -m, *hit);
  EXPECT_NEAR(surf.uv.x, 4.0, 1e-14);
  EXPECT_NEAR(surf.uv.y, 6.0, 1e-14);
}

TEST(PlaneTest, ParallelAndRecedingRaysMiss) {
  Shape s = plane({0, 0, 0}, {0, 1, 0});
  EXPECT_FALSE(s.intersect({0, 1, 0}, {1, 0, 0}));  // parallel above
  EXPECT_FALSE(s.intersect({0, 0, 0}, {0, 0, 1}));  // inside the plane
  EXPECT_FALSE(s.intersect({0, 1, 0}, {0, 1, 0}));  // moving away
  EXPECT_FALSE(s.intersect({0, 1, 0}, {0, -1, 0}, 0.0, 0.5));
  EXPECT_FALSE(s.intersect({0, 1, 0}, {0, -1, 0}, 1.0));
}

TEST(PlaneTest, OriginsFrom1e6KeepRelativeTAndProjectOntoPlane) {
  std::mt19937_64 rng(2);
  dvec3 point(3, -2, 1), n = glm::normalize(dvec3(0.3, 1, -0.2));
  Shape s = plane(point, n);
  for (int i = 0; i < 500; ++i) {
    dvec3 t1 = glm::normalize(glm::cross(n, random_unit(rng)));
    dvec3 target = point + 10.0 * t1;
    dvec3 d = -random_in_hemisphere(rng, n);
    if (glm::dot(d, n) > -1e-3) continue;
    dvec3 o = target - 1e6 * d;
    auto hit = s.intersect(o, d);
    ASSERT_TRUE(hit);
    // o was rounded near 1e6: t is exact to ~eps * 1e6 in absolute terms.
    EXPECT_LT(rel_err(hit->t, 1e6), 1e-12);
    Surface surf = s.surface(o, d, *hit);
    EXPECT_LT(std::abs(glm::dot(surf.point - point, n)), 1e-13);
  }
}

TEST(PlaneTest, DenormalSizedNormalStillDefinesThePlane) {
  Shape s = plane({2, 0, 0}, {1e-300, 0, 0});
  auto hit = s.intersect({0, 0, 0}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 2.0);
  EXPECT_EQ(glm::normalize(s.surface({0, 0, 0}, {1, 0, 0}, *hit).normal), dvec3(1, 0, 0));
}

TEST(PlaneTest, SecondaryRaysFromEitherSideNeverReHit) {
  std::mt19937_64 rng(9);
  Shape s = plane({1e4, 0.5, -3}, {0.2, 1, 0.1});
  for (int k = 0; k < 20; ++k) {
    dvec3 o = 1e3 * random_unit(rng);
    dvec3 d = glm::normalize(dvec3(1e4, 0.5, -3) + 100.0 * random_unit(rng) - o);
    auto hit = s.intersect(o, d);
    if (!hit) continue;
    Surface surf = s.surface(o, d, *hit);
    dvec3 n = glm::normalize(surf.normal);
    if (glm::dot(n, d) > 0) n = -n;  // the side the ray came from
    EXPECT_EQ(count_reintersections(s, surf.point, n, spec_offset(surf.point), 1000, rng), 0);
  }
}

TEST(PlaneTest, BoundsReportUnbounded) {
  Shape s = plane({0, 0, 0}, {0, 1, 0});
  double lo[3], hi[3];
  EXPECT_EQ(s.desc().bounds(s.record(), lo, hi), 0);
}

TEST(PlaneTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "plane", {}), "");
}

TEST(PlaneTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // As the ring's: the plane y = 0 given with normal (0, 2, 0), a ray
  // descending at 2^-20 rad from 2^-20 (+2^-56 in long double) above it.
  Shape s = plane({0, 0, 0}, {0, 2, 0});
  const dvec3 d(1, -0x1p-20, 0);
  auto hit = s.intersect({-1.5, 0x1p-20, 0}, d);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(s.refine({-1.5, 0x1p-20L + 0x1p-56L, 0}, {d.x, d.y, d.z}, *hit).t, 1.0 + 0x1p-36, 1e-12);
}

}  // namespace
