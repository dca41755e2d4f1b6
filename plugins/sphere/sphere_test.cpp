// Sphere plugin tests. Expected values are worked out by hand or in long
// double with the textbook formula (different algebra from the plugin's
// re-centred robust discriminant).
#include <gtest/gtest.h>

#include <string_view>

#include <cmath>
#include <random>

#include "prism/sdk/plugin_testing.hpp"
#include "prism/sdk/sphere_math.hpp"

extern "C" const PrismPrimitiveDesc* prism_primitive_entry(void);

namespace {

using glm::dvec3;
using prism::sdk::kInf;
using namespace prism::sdk::testing;

Shape sphere(double radius) { return Shape(prism_primitive_entry(), {radius}); }

// Textbook |o + t d|^2 = r^2 in long double: the first root > tmin, or -1.
long double reference_t(const dvec3& o, const dvec3& d, double r, long double tmin = 0) {
  long double b = 0, c = -(long double)r * r, dd = 0;
  for (int i = 0; i < 3; ++i) {
    b += (long double)o[i] * d[i];
    c += (long double)o[i] * o[i];
    dd += (long double)d[i] * d[i];
  }
  long double disc = b * b - dd * c;
  if (disc < 0) return -1;
  long double t0 = (-b - std::sqrt(disc)) / dd, t1 = (-b + std::sqrt(disc)) / dd;
  return t0 > tmin ? t0 : (t1 > tmin ? t1 : -1);
}

void expect_vec_near(const dvec3& got, const dvec3& want, double tol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

TEST(SphereTest, DescriptorDeclaresOnlyRadiusAndIsTransformable) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_EQ(desc.abi_version, PRISM_PRIMITIVE_ABI_VERSION);
  EXPECT_EQ(desc.desc_size, sizeof(PrismPrimitiveDesc));
  EXPECT_STREQ(desc.type_name, "sphere");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, PRISM_PRIMITIVE_TRANSFORMABLE);
  ASSERT_EQ(desc.field_count, 1u);
  const PrismField* radius = find_field(desc, "radius");
  ASSERT_NE(radius, nullptr);
  EXPECT_EQ(radius->flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH);
  EXPECT_EQ(radius->min, 0.0);
  EXPECT_EQ(find_field(desc, "center"), nullptr);
  EXPECT_EQ(desc.record_size % 16, 0u);
  EXPECT_EQ(validation_error(desc, {1.0}), std::nullopt);
}

TEST(SphereTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "sphere", {}), "");
}

TEST(SphereTest, HitFromOutsideGivesNearSideNormalAndUv) {
  Shape s = sphere(1.0);
  auto hit = s.intersect({0, 0, -5}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 4.0);
  Surface surf = s.surface({0, 0, -5}, {0, 0, 1}, *hit);
  expect_vec_near(surf.point, {0, 0, -1}, 1e-15);
  expect_vec_near(glm::normalize(surf.normal), {0, 0, -1}, 1e-15);
  EXPECT_NEAR(surf.uv.x, 0.25, 1e-15);  // 0.5 + atan2(-1, 0)/2pi
  EXPECT_NEAR(surf.uv.y, 0.5, 1e-15);
}

TEST(SphereTest, HitFromInsideGivesFarSideWithOutwardNormal) {
  Shape s = sphere(2.0);
  auto hit = s.intersect({0, 0, 0}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 2.0);
  Surface surf = s.surface({0, 0, 0}, {1, 0, 0}, *hit);
  expect_vec_near(glm::normalize(surf.normal), {1, 0, 0}, 1e-15);
  EXPECT_NEAR(surf.uv.x, 0.5, 1e-15);
  EXPECT_NEAR(surf.uv.y, 0.5, 1e-15);
}

TEST(SphereTest, UvAtKnownLatitudeAndLongitude) {
  Shape s = sphere(1.0);
  // p = (0, sin 30deg, -cos 30deg): u = 0.5 - 1/4, v = 0.5 - (pi/6)/pi = 1/3.
  dvec3 p(0.0, 0.5, -std::sqrt(3.0) / 2.0);
  auto hit = s.intersect(5.0 * p, -p);
  ASSERT_TRUE(hit);
  Surface surf = s.surface(5.0 * p, -p, *hit);
  EXPECT_NEAR(surf.uv.x, 0.25, 1e-14);
  EXPECT_NEAR(surf.uv.y, 1.0 / 3.0, 1e-14);
  // p = (1, 0, 1)/sqrt 2: u = 0.5 + (pi/4)/(2pi) = 0.625.
  dvec3 q = glm::normalize(dvec3(1, 0, 1));
  hit = s.intersect(5.0 * q, -q);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(s.surface(5.0 * q, -q, *hit).uv.x, 0.625, 1e-14);
}

TEST(SphereTest, NorthPoleHasAtan2ZeroZeroAndTopRow) {
  Shape s = sphere(1.0);
  auto hit = s.intersect({0, 5, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  Surface surf = s.surface({0, 5, 0}, {0, -1, 0}, *hit);
  EXPECT_EQ(surf.uv.x, 0.5);
  EXPECT_EQ(surf.uv.y, 0.0);
}

TEST(SphereTest, MissesWhenRayPassesBeside) {
  Shape s = sphere(1.0);
  EXPECT_FALSE(s.intersect({0, 1.5, -5}, {0, 0, 1}));
  EXPECT_FALSE(s.intersect({0, 0, -5}, {0, 0, -1}));  // sphere behind the ray
}

TEST(SphereTest, RespectsTminAndTmax) {
  Shape s = sphere(1.0);
  EXPECT_FALSE(s.intersect({0, 0, -5}, {0, 0, 1}, 0.0, 3.9));
  auto at_tmax = s.intersect({0, 0, -5}, {0, 0, 1}, 0.0, 4.0);  // t <= tmax is inclusive
  ASSERT_TRUE(at_tmax);
  EXPECT_EQ(at_tmax->t, 4.0);
  auto far = s.intersect({0, 0, -5}, {0, 0, 1}, 4.0);  // t > tmin is exclusive
  ASSERT_TRUE(far);
  EXPECT_EQ(far->t, 6.0);
  EXPECT_FALSE(s.intersect({0, 0, -5}, {0, 0, 1}, 6.0));
}

TEST(SphereTest, GrazingRayHitsAtTheShortChord) {
  Shape s = sphere(1.0);
  double c = 1.0 - 1e-9;
  auto hit = s.intersect({0, c, -10}, {0, 0, 1});
  ASSERT_TRUE(hit);
  long double half = std::sqrt((1.0L - c) * (1.0L + c));
  EXPECT_LT(rel_err(hit->t, (double)(10.0L - half)), 1e-12);
  EXPECT_FALSE(s.intersect({0, 1.0 + 1e-12, -10}, {0, 0, 1}));
}

TEST(SphereTest, OriginsFrom1e4To1e6MatchLongDoubleReference) {
  Shape s = sphere(1.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 0.9);
  for (double dist : {1e4, 1e5, 1e6}) {
    for (int i = 0; i < 200; ++i) {
      dvec3 target = u01(rng) * random_unit(rng);
      dvec3 o = target - dist * random_unit(rng);
      dvec3 d = glm::normalize(target - o);
      auto hit = s.intersect(o, d);
      ASSERT_TRUE(hit) << "dist " << dist;
      EXPECT_LT(rel_err(hit->t, (double)reference_t(o, d, 1.0)), 1e-12) << "dist " << dist;
      Surface surf = s.surface(o, d, *hit);
      EXPECT_NEAR(glm::length(surf.point), 1.0, 1e-15);
    }
  }
}

TEST(SphereTest, RandomRaysAcrossScalesMatchLongDoubleReference) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int compared = 0;
  for (int i = 0; i < 3000; ++i) {
    double r = std::pow(10.0, -3.0 + 9.0 * u01(rng));
    Shape s = sphere(r);
    dvec3 o = r * std::pow(10.0, -1.0 + 5.0 * u01(rng)) * random_unit(rng);
    dvec3 d = glm::normalize(r * random_unit(rng) * u01(rng) - o);
    // Skip the ambiguous band around the silhouette (relative miss distance < 1e-6).
    dvec3 perp = o - glm::dot(o, d) * d;
    if (std::abs(glm::length(perp) / r - 1.0) < 1e-6) continue;
    long double want = reference_t(o, d, r);
    auto hit = s.intersect(o, d);
    ASSERT_EQ(hit.has_value(), want > 0) << "r " << r << " i " << i;
    if (hit) {
      EXPECT_LT(rel_err(hit->t, (double)want), 1e-9);
      ++compared;
    }
  }
  EXPECT_GT(compared, 2000);
}

TEST(SphereTest, SecondaryRaysNeverReHitTheConvexSphere) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int k = 0; k < 30; ++k) {
    double r = std::pow(10.0, -4.0 + 11.0 * u01(rng));
    Shape s = sphere(r);
    dvec3 o = r * std::pow(10.0, 0.1 + 4.0 * u01(rng)) * random_unit(rng);
    dvec3 d = glm::normalize(0.99 * r * random_unit(rng) - o);
    auto hit = s.intersect(o, d);
    ASSERT_TRUE(hit);
    Surface surf = s.surface(o, d, *hit);
    dvec3 n = glm::normalize(surf.normal);
    EXPECT_EQ(count_reintersections(s, surf.point, n, spec_offset(surf.point), 1000, rng), 0) << "r " << r;
    // A thousand times tighter than the spec still holds: P is well inside eps.
    EXPECT_EQ(count_reintersections(s, surf.point, n, 1e-7 * (1 + r), 1000, rng), 0) << "r " << r;
  }
}

TEST(SphereTest, BoundsAreTheRadiusCube) {
  Shape s = sphere(2.5);
  double lo[3], hi[3];
  ASSERT_EQ(s.desc().bounds(s.record(), lo, hi), 1);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(lo[i], -2.5);
    EXPECT_EQ(hi[i], 2.5);
  }
}

TEST(SphereTest, BatchAgreesWithSingleRayQueries) {
  Shape s = sphere(1.0);
  std::mt19937_64 rng(5);
  std::vector<PrismRay> rays;
  std::vector<double> tmin, tmax;
  for (int i = 0; i < 64; ++i) {
    dvec3 o = 3.0 * random_unit(rng);
    rays.push_back(Shape::make_ray(o, glm::normalize(0.8 * random_unit(rng) - o)));
    tmin.push_back(i % 3 == 0 ? 1.0 : 0.0);
    tmax.push_back(kInf);
  }
  std::vector<PrismHit> hits(rays.size());
  std::vector<uint8_t> found(rays.size());
  s.desc().intersect_batch(s.record(), rays.size(), rays.data(), tmin.data(), tmax.data(), hits.data(),
                           found.data());
  for (size_t i = 0; i < rays.size(); ++i) {
    PrismHit one{};
    int got = s.desc().intersect(s.record(), &rays[i], tmin[i], tmax[i], &one);
    ASSERT_EQ(found[i], got);
    if (got) {
      EXPECT_EQ(hits[i].t, one.t);
    }
  }
}

TEST(SphereTest, NanRayMissesWithoutCrashing) {
  Shape s = sphere(1.0);
  EXPECT_FALSE(s.intersect({NAN, 0, -5}, {0, 0, 1}));
  EXPECT_FALSE(s.intersect({0, 0, -5}, {NAN, NAN, NAN}));
}

TEST(SphereTest, SdkIntersectSphereTakesOriginRelativeToCentre) {
  // The core calls this for light spheres with o = origin - centre.
  dvec3 centre(148376.0, 1234.0, -223423.0);
  dvec3 origin = centre + dvec3(0.25, 0.0, -3.0);
  double t = 0.0;
  ASSERT_TRUE(prism::sdk::intersect_sphere(origin - centre, {0, 0, 1}, 0.5, 0.0, kInf, t));
  EXPECT_NEAR(t, 3.0 - std::sqrt(0.25 - 0.0625), 1e-12);
}

TEST(SphereTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // The ray's origin.y carries 2^-58 more in long double than a double can hold;
  // where it grazes the surface that moves t by ~2e-12 relative, which only a
  // polish of the long double ray can see (to ~1e-19 / 1.7e-7 rad, a few
  // 1e-14 relative). Expected t: mpmath at 300 bits.
  Shape s = sphere(1.0);
  const double c = 1.0 - 0x1p-46;
  auto hit = s.intersect({0, c, -10}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(s.refine({0, c + 0x1p-58L, -10}, {0, 0, 1}, *hit).t, 9.999999831433186728526251), 1e-13);
}


// The float entry (ABI 4): the ray rounded to float, the float instantiation
// of the same source. Hand-derived: float spacing between 2^26 and 2^27 is 8.
std::optional<double> float_entry_t(const Shape& s, const dvec3& o, const dvec3& d, double tmin, double tmax) {
  PrismRay ray{{o.x, o.y, o.z}, {d.x, d.y, d.z}};
  PrismHit hit{};
  if (!s.desc().intersect_float(s.record(), &ray, tmin, tmax, &hit)) return std::nullopt;
  return hit.t;
}

TEST(SphereTest, FloatEntryComputesInFloat) {
  const Shape s = sphere(1.0);
  ASSERT_NE(s.desc().intersect_float, s.desc().intersect);
  // Every step exact in float: foot at t = 5, disc = 1, t = 5 - 1.
  EXPECT_EQ(float_entry_t(s, {0, 0, -5}, {0, 0, 1}, 0.0, kInf), 4.0);
  // -100000000.5 rounds to -1e8 in float (a multiple of 8): foot at 1e8,
  // t = 1e8 - 1 = 99999999, which rounds to 1e8. Double keeps the half.
  EXPECT_EQ(float_entry_t(s, {0, 0, -100000000.5}, {0, 0, 1}, 0.0, kInf), 100000000.0);
  EXPECT_EQ(s.intersect({0, 0, -100000000.5}, {0, 0, 1})->t, 99999999.5);
}

TEST(SphereTest, FloatEntryKeepsTheDoubleBounds) {
  const Shape s = sphere(1.0);
  // tmax just below 4 rounds down to the float below 4: the hit at 4 is out.
  EXPECT_EQ(float_entry_t(s, {0, 0, -5}, {0, 0, 1}, 0.0, 3.9999999), std::nullopt);
  // tmin just below 4 rounds up to 4 itself, so (tmin, tmax] in float lies
  // inside the double one: the far root, 6, is the answer.
  EXPECT_EQ(float_entry_t(s, {0, 0, -5}, {0, 0, 1}, 3.9999999, kInf), 6.0);
  EXPECT_EQ(float_entry_t(s, {0, 0, -5}, {0, 0, 1}, 0.0, 4.0000001), 4.0);
}

}  // namespace
