// Box plugin tests. The random-ray oracle intersects the six face
// rectangles one by one in long double (not the slab method).
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

Shape box(dvec3 h) { return Shape(prism_primitive_entry(), {h.x, h.y, h.z}); }

// First t > 0 where the ray crosses one of the six closed face rectangles, or -1.
long double reference_t(const dvec3& o, const dvec3& d, const dvec3& h) {
  long double best = -1;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) continue;
    for (double side : {-1.0, 1.0}) {
      long double t = ((long double)side * h[a] - o[a]) / d[a];
      if (t <= 0 || (best > 0 && t >= best)) continue;
      bool inside = true;
      for (int i = 0; i < 3; ++i)
        if (i != a) inside = inside && std::abs(o[i] + t * (long double)d[i]) <= h[i];
      if (inside) best = t;
    }
  }
  return best;
}

// Whether p lies within `rel` (relative to h) of two face planes at once.
bool near_an_edge(const dvec3& p, const dvec3& h, double rel) {
  int planes = 0;
  for (int a = 0; a < 3; ++a) planes += std::abs(std::abs(p[a]) - h[a]) < rel * h[a];
  return planes > 1;
}

struct FaceCase {
  dvec3 point, normal;
  double u, v;
};

TEST(BoxTest, DescriptorHasHalfSizeOnly) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_STREQ(desc.type_name, "box");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, PRISM_PRIMITIVE_TRANSFORMABLE);
  ASSERT_EQ(desc.field_count, 1u);
  const PrismField* h = find_field(desc, "half_size");
  EXPECT_EQ(h->kind, PRISM_FIELD_ARRAY);
  EXPECT_EQ(h->count, 3u);
  EXPECT_EQ(h->flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH);
  EXPECT_EQ(desc.record_size % 16, 0u);
}

TEST(BoxTest, EachFaceGivesSpecNormalAndUv) {
  // half_size (1, 2, 3); uv worked out by hand from the spec table.
  const FaceCase cases[] = {
      {{1, 0.5, -1.5}, {1, 0, 0}, 0.25, 0.375},     // +x: ((z+3)/6, (2-y)/4)
      {{-1, -1, 1.5}, {-1, 0, 0}, 0.75, 0.75},      // -x
      {{0.5, 2, -1.5}, {0, 1, 0}, 0.75, 0.25},      // +y: ((x+1)/2, (z+3)/6)
      {{0.5, -2, 1.5}, {0, -1, 0}, 0.75, 0.75},     // -y
      {{-0.5, 1, 3}, {0, 0, 1}, 0.25, 0.25},        // +z: ((x+1)/2, (2-y)/4)
      {{0.5, -1, -3}, {0, 0, -1}, 0.75, 0.75},      // -z
  };
  Shape s = box({1, 2, 3});
  for (const FaceCase& c : cases) {
    dvec3 d = glm::normalize(-c.normal + 0.3 * dvec3(c.normal.z, c.normal.x, c.normal.y));
    dvec3 o = c.point - 5.0 * d;
    auto hit = s.intersect(o, d);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5.0, 1e-14);
    Surface surf = s.surface(o, d, *hit);
    EXPECT_EQ(surf.normal, c.normal);
    EXPECT_NEAR(surf.uv.x, c.u, 1e-15);
    EXPECT_NEAR(surf.uv.y, c.v, 1e-15);
  }
}

TEST(BoxTest, HitFromInsideLeavesThroughOutwardFace) {
  Shape s = box({1, 2, 3});
  auto hit = s.intersect({0.2, 0.1, 0}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 1.9);
  EXPECT_EQ(s.surface({0.2, 0.1, 0}, {0, 1, 0}, *hit).normal, dvec3(0, 1, 0));
}

TEST(BoxTest, EdgeHitsBreakTiesTowardLowerAxis) {
  Shape s = box({1, 1, 1});
  dvec3 d = glm::normalize(dvec3(-1, -1, 0));
  auto hit = s.intersect({2, 2, 0}, d);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, std::sqrt(2.0), 1e-15);
  EXPECT_EQ(s.surface({2, 2, 0}, d, *hit).normal, dvec3(1, 0, 0));
  d = glm::normalize(dvec3(0, -1, -1));
  hit = s.intersect({0, 2, 2}, d);
  ASSERT_TRUE(hit);
  EXPECT_EQ(s.surface({0, 2, 2}, d, *hit).normal, dvec3(0, 1, 0));
}

TEST(BoxTest, AxisParallelRaysInsideSlabHitAndOutsideMiss) {
  Shape s = box({1, 2, 3});
  auto hit = s.intersect({-5, 0.5, 0}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 4.0);
  EXPECT_EQ(s.surface({-5, 0.5, 0}, {1, 0, 0}, *hit).normal, dvec3(-1, 0, 0));
  EXPECT_FALSE(s.intersect({-5, 2.5, 0}, {1, 0, 0}));
  EXPECT_FALSE(s.intersect({-5, 0, 0}, glm::normalize(dvec3(1, 1, 1))));
}

TEST(BoxTest, TminSkipsEntryAndTmaxCutsBeforeIt) {
  Shape s = box({1, 1, 1});
  auto exit = s.intersect({0, 0, -5}, {0, 0, 1}, 4.0);
  ASSERT_TRUE(exit);
  EXPECT_EQ(exit->t, 6.0);
  EXPECT_EQ(s.surface({0, 0, -5}, {0, 0, 1}, *exit).normal, dvec3(0, 0, 1));
  EXPECT_FALSE(s.intersect({0, 0, -5}, {0, 0, 1}, 0.0, 3.5));
  EXPECT_FALSE(s.intersect({0, 0, -5}, {0, 0, 1}, 6.0));
}

TEST(BoxTest, NearGrazingRayFrom1e4EntersThroughSideFace) {
  Shape s = box({1, 1, 1});
  dvec3 o(-1e4, 1.0 + 5e-5, 0.25), d = glm::normalize(dvec3(1, -1e-8, 0));
  auto hit = s.intersect(o, d);
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(hit->t, (double)reference_t(o, d, {1, 1, 1})), 1e-13);
  EXPECT_EQ(s.surface(o, d, *hit).normal, dvec3(-1, 0, 0));
  // The same ray 1e-4 higher passes above the box.
  EXPECT_FALSE(s.intersect(o + dvec3(0, 1e-4, 0), d));
}

TEST(BoxTest, RandomRaysFromUpTo1e6MatchFaceByFaceReference) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int compared = 0;
  for (int i = 0; i < 4000; ++i) {
    auto size = [&] { return std::pow(10.0, -2 + 4 * u01(rng)); };
    double hx = size(), hy = size(), hz = size();  // in order: argument order is unspecified
    dvec3 h(hx, hy, hz);
    Shape s = box(h);
    dvec3 o = glm::length(h) * std::pow(10.0, -1 + 7 * u01(rng)) * random_unit(rng);
    dvec3 d = glm::normalize(1.2 * h * random_unit(rng) - o);
    long double want = reference_t(o, d, h);
    auto hit = s.intersect(o, d);
    if (want > 0 && near_an_edge(o + (double)want * d, h, 1e-9 * (1 + 1e-6 * glm::length(o) / glm::length(h)))) {
      continue;  // the ambiguous band: two correct slab tests may disagree there
    }
    ASSERT_EQ(hit.has_value(), want > 0) << i;
    if (!hit) continue;
    EXPECT_LT(rel_err(hit->t, (double)want), 1e-12) << i;
    ++compared;
  }
  EXPECT_GT(compared, 1000);
}

TEST(BoxTest, SecondaryRaysNeverReHitTheConvexBox) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int k = 0; k < 30; ++k) {
    auto size = [&] { return std::min(std::pow(10.0, -4 + 11 * u01(rng)), 1e7); };
    double hx = size(), hy = size(), hz = size();  // in order: argument order is unspecified
    dvec3 h(hx, hy, hz);
    Shape s = box(h);
    dvec3 o = 3.0 * glm::length(h) * random_unit(rng);
    dvec3 d = glm::normalize(0.9 * h * random_unit(rng) - o);
    auto hit = s.intersect(o, d);
    ASSERT_TRUE(hit);
    Surface surf = s.surface(o, d, *hit);
    EXPECT_EQ(count_reintersections(s, surf.point, surf.normal, spec_offset(surf.point), 1000, rng), 0);
    EXPECT_EQ(count_reintersections(s, surf.point, surf.normal, 1e-12 * (1 + glm::length(h)), 1000, rng), 0);
  }
}

TEST(BoxTest, BoundsAreTheHalfSizes) {
  Shape s = box({1, 2, 3});
  double lo[3], hi[3];
  ASSERT_EQ(s.desc().bounds(s.record(), lo, hi), 1);
  EXPECT_EQ(dvec3(lo[0], lo[1], lo[2]), dvec3(-1, -2, -3));
  EXPECT_EQ(dvec3(hi[0], hi[1], hi[2]), dvec3(1, 2, 3));
}

TEST(BoxTest, NanRayMisses) {
  Shape s = box({1, 1, 1});
  EXPECT_FALSE(s.intersect({NAN, 0, -5}, {0, 0, 1}));
  EXPECT_FALSE(s.intersect({0, 0, -5}, {NAN, NAN, NAN}));
}

TEST(BoxTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "box", {}), "");
}

TEST(BoxTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // The ray meets the -x face at 2^-20 rad from 2^-20 in front of it; the
  // long double origin is 2^-56 further, so the face is at t = 1 + 2^-36
  // (the double ray's t is 1), and the polished hit point moves with it.
  Shape s = box({1, 1, 1});
  const double x = -1.0 - 0x1p-20;
  const dvec3 d(0x1p-20, 0, 1);
  auto hit = s.intersect({x, 0.25, -0.5}, d);
  ASSERT_TRUE(hit);
  Hit polished = s.refine({x - 0x1p-56L, 0.25, -0.5}, {d.x, d.y, d.z}, *hit);
  EXPECT_NEAR(polished.t, 1.0 + 0x1p-36, 1e-12);  // long double error / 2^-20: ~6e-14
  EXPECT_NEAR(s.surface({x, 0.25, -0.5}, d, polished).point.z, 0.5 + 0x1p-36, 1e-12);
}

}  // namespace
