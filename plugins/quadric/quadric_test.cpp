// Quadric plugin tests. References: geometry by hand, factorised or
// fixed-point solutions in long double, and the textbook quadratic in long
// double without re-centring, Newton-polished on f itself (unlike the
// plugin's re-centred stable form).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string_view>

#include "prism/sdk/plugin_testing.hpp"
#include "prism/sdk/quadric_math.hpp"

extern "C" const PrismPrimitiveDesc* prism_primitive_entry(void);

namespace {

using glm::dvec3;
using prism::sdk::kInf;
using namespace prism::sdk::testing;
using Coefs = std::array<double, 10>;
using ld = long double;

const Coefs kUnitSphere = {1, 1, 1, 0, 0, 0, 0, 0, 0, -1};

std::vector<double> values(const Coefs& c, dvec3 lo = dvec3(-kInf), dvec3 hi = dvec3(kInf)) {
  std::vector<double> v(c.begin(), c.end());
  for (dvec3 corner : {lo, hi}) v.insert(v.end(), {corner.x, corner.y, corner.z});
  return v;
}

Shape quadric(const Coefs& c, dvec3 lo = dvec3(-kInf), dvec3 hi = dvec3(kInf)) {
  return Shape(prism_primitive_entry(), values(c, lo, hi));
}

ld quadric_at(const Coefs& k, const dvec3& o, const dvec3& d, ld t) {
  ld x = o.x + t * d.x, y = o.y + t * d.y, z = o.z + t * d.z;
  return k[0] * x * x + k[1] * y * y + k[2] * z * z + k[3] * x * y + k[4] * y * z + k[5] * x * z + k[6] * x +
         k[7] * y + k[8] * z + k[9];
}

// Textbook roots (-b -+ sqrt(b^2 - 4ac)) / 2a in long double, no re-centring,
// each polished by Newton on f(o + t d) evaluated directly: the first root
// > 0 inside the clip box, or -1.
ld reference_t(const Coefs& k, const dvec3& o, const dvec3& d, dvec3 lo, dvec3 hi) {
  ld c = quadric_at(k, o, d, 0), fp = quadric_at(k, o, d, 1), fm = quadric_at(k, o, d, -1);
  ld a = (fp + fm) / 2 - c, b = (fp - fm) / 2;  // exact for a quadratic
  ld disc = b * b - 4 * a * c;
  if (disc < 0) return -1;
  ld roots[2] = {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)};
  if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  for (ld t : roots) {
    for (int i = 0; i < 4; ++i) t -= quadric_at(k, o, d, t) / (2 * a * t + b);
    ld p[3] = {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
    bool in = p[0] >= lo.x && p[0] <= hi.x && p[1] >= lo.y && p[1] <= hi.y && p[2] >= lo.z && p[2] <= hi.z;
    if (t > 0 && in) return t;
  }
  return -1;
}

TEST(QuadricTest, DescriptorHasCoefficientsAndNullableClipBox) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_STREQ(desc.type_name, "quadric");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, PRISM_PRIMITIVE_TRANSFORMABLE);
  const PrismField* coefs = find_field(desc, "coefficients");
  ASSERT_NE(coefs, nullptr);
  EXPECT_EQ(coefs->count, 10u);
  EXPECT_EQ(coefs->flags, PRISM_FIELD_REQUIRED);  // not lengths
  for (const char* name : {"clip_min", "clip_max"}) {
    const PrismField* clip = find_field(desc, name);
    ASSERT_NE(clip, nullptr);
    EXPECT_EQ(clip->kind, PRISM_FIELD_ARRAY_OR_NULL);
    EXPECT_EQ(clip->count, 3u);
    EXPECT_EQ(clip->flags, PRISM_FIELD_LENGTH);  // numbers only: nulls bypass the core's range check
    double unbounded = std::strcmp(name, "clip_min") == 0 ? -kInf : kInf;
    EXPECT_EQ(clip->null_value, unbounded);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(clip->defaults[i], unbounded);
  }
  EXPECT_EQ(desc.record_size % 16, 0u);
}

TEST(QuadricTest, ValidateRejectsDegenerateCoefficientsAndInvertedClip) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  auto err = validation_error(desc, values({0, 0, 0, 0, 0, 0, 0, 0, 0, 5}));
  ASSERT_TRUE(err);
  EXPECT_STREQ(err->field, "coefficients");
  err = validation_error(desc, values(kUnitSphere, {-1, 2, -1}, {1, 1, 1}));
  ASSERT_TRUE(err);
  EXPECT_STREQ(err->field, "clip_max");
  EXPECT_STREQ(err->message, "entry 1 must be >= clip_min (2), got 1");
  EXPECT_EQ(validation_error(desc, values({0, 0, 0, 0, 0, 0, 0, 1e-300, 0, 0})), std::nullopt);
  EXPECT_EQ(validation_error(desc, values(kUnitSphere, {1, -kInf, 1}, {1, kInf, 1})), std::nullopt);
}

TEST(QuadricTest, UnitSphereHitsLikeASphereAndNegationFlipsNormal) {
  Shape s = quadric(kUnitSphere);
  auto hit = s.intersect({0, 0, -5}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 4.0);
  Surface surf = s.surface({0, 0, -5}, {0, 0, 1}, *hit);
  EXPECT_EQ(surf.normal, dvec3(0, 0, -1));  // grad = 2p, scaled to max component 1
  EXPECT_EQ(surf.uv, glm::dvec2(0.0));
  Shape flipped = quadric({-1, -1, -1, 0, 0, 0, 0, 0, 0, 1});
  EXPECT_EQ(flipped.surface({0, 0, -5}, {0, 0, 1}, *flipped.intersect({0, 0, -5}, {0, 0, 1})).normal,
            dvec3(0, 0, 1));
}

TEST(QuadricTest, ClippedNearRootFallsThroughToFarRoot) {
  Shape s = quadric(kUnitSphere, {-kInf, 0, -kInf}, dvec3(kInf));  // upper hemisphere
  auto hit = s.intersect({0.6, -5, 0}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5.8, 1e-15);  // y = +0.8 on the inside of the dome
  Surface surf = s.surface({0.6, -5, 0}, {0, 1, 0}, *hit);
  EXPECT_NEAR(surf.normal.x, 0.75, 1e-15);  // (0.6, 0.8, 0) scaled to max 1
  EXPECT_NEAR(surf.normal.y, 1.0, 1e-15);
  EXPECT_FALSE(s.intersect({0.6, -5, 0}, {0, 1, 0}, 0.0, 5.7));
}

TEST(QuadricTest, ZeroQuadraticTermSolvesLinearly) {
  Shape plane = quadric({0, 0, 0, 0, 0, 0, 0, 1, 0, 0});  // y = 0
  auto hit = plane.intersect({0.3, 2, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 2.0);
  EXPECT_EQ(plane.surface({0.3, 2, 0}, {0, -1, 0}, *hit).normal, dvec3(0, 1, 0));
  EXPECT_FALSE(plane.intersect({0, 2, 0}, {1, 0, 0}));
  // Cone x^2 - y^2 + z^2 along its generator direction (1,1,0)/sqrt2: a == 0
  // exactly; (x - y)(x + y) = 0 with x - y = -1.5 gives t = 0.25 * sqrt 2.
  Shape cone = quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, 0});
  hit = cone.intersect({-1, 0.5, 0}, glm::normalize(dvec3(1, 1, 0)));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 0.25 * std::sqrt(2.0), 1e-15);
}

TEST(QuadricTest, TinyQuadraticTermKeepsNearRootAccurate) {
  // Paraboloid y = x^2 and a ray almost along y: a = dx^2 ~ 1e-18. The near
  // root by fixed-point iteration t = (1 + x(t)^2) / dy in long double.
  Shape s = quadric({1, 0, 0, 0, 0, 0, 0, -1, 0, 0});
  dvec3 o(0.5, -1, 0), d = glm::normalize(dvec3(1e-9, 1, 0));
  ld t = 0;
  for (int i = 0; i < 20; ++i) {
    ld x = o.x + t * d.x;
    t = (1 + x * x) / d.y;
  }
  auto hit = s.intersect(o, d);
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(hit->t, (double)t), 1e-15);
  auto far = s.intersect(o, d, hit->t);  // the other root is near 1 / a ~ 1e18
  ASSERT_TRUE(far);
  EXPECT_GT(far->t, 1e17);
}

TEST(QuadricTest, NearTangentRayFrom1e4OnCylinderQuadric) {
  Shape s = quadric({1, 0, 1, 0, 0, 0, 0, 0, 0, -1});
  double c = 1.0 - 1e-10;
  auto hit = s.intersect({-1e4, 0.5, c}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(hit->t, (double)(1e4L - std::sqrt((1.0L - c) * (1.0L + c)))), 1e-12);
  EXPECT_FALSE(s.intersect({-1e4, 0.5, 1.0 + 1e-10}, {1, 0, 0}));
}

TEST(QuadricTest, ConeApexHitHasZeroNormal) {
  Shape s = quadric({1, -1, 1, 0, 0, 0, 0, 0, 0, 0}, {-kInf, 0, -kInf}, {kInf, 1, kInf});
  auto hit = s.intersect({0, -1, 0}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 1.0);
  EXPECT_EQ(s.surface({0, -1, 0}, {0, 1, 0}, *hit).normal, dvec3(0.0));
}

TEST(QuadricTest, SphereQuadricFrom1e6MatchesGeometricReference) {
  Shape s = quadric(kUnitSphere);
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u01(0.0, 0.9);
  for (int i = 0; i < 500; ++i) {
    dvec3 target = u01(rng) * random_unit(rng), o = target - 1e6 * random_unit(rng);
    dvec3 d = glm::normalize(target - o);
    ld b = 0, oo = 0, dd = 0;  // |d| = 1 only to rounding, which matters at 1e6
    for (int k = 0; k < 3; ++k) b += (ld)o[k] * d[k], oo += (ld)o[k] * o[k], dd += (ld)d[k] * d[k];
    ld want = (-b - std::sqrt(b * b - dd * (oo - 1))) / dd;
    auto hit = s.intersect(o, d);
    ASSERT_TRUE(hit);
    EXPECT_LT(rel_err(hit->t, (double)want), 1e-12);
    Surface surf = s.surface(o, d, *hit);
    EXPECT_NEAR(glm::length(surf.point), 1.0, 1e-15);
  }
}

TEST(QuadricTest, RandomClippedQuadricsMatchLongDoubleTextbook) {
  const Coefs shapes[] = {
      {1, -1, 1, 0, 0, 0, 0, 0, 0, -0.25},        // hyperboloid of one sheet
      {1, 2, 0.5, 0.3, -0.2, 0.1, 0.1, 0, 0, -1},  // tilted ellipsoid
      {1, 0, 1, 0, 0, 0, 0, -1, 0, 0},             // paraboloid y = x^2 + z^2
      {1, -1, 0, 0, 0, 0, 0, 0, 1, 0},             // saddle z = y^2 - x^2
  };
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int compared = 0;
  for (const Coefs& k : shapes) {
    dvec3 lo(-1.5, -1, -kInf), hi(1.5, 1.2, kInf);
    Shape s = quadric(k, lo, hi);
    for (int i = 0; i < 500; ++i) {
      dvec3 o = std::pow(10.0, 4 * u01(rng)) * random_unit(rng);
      dvec3 d = glm::normalize(1.5 * random_unit(rng) - o);
      ld want = reference_t(k, o, d, lo, hi);
      auto hit = s.intersect(o, d);
      if (want > 0) {  // skip the band where the reference point is within 1e-9 of a clip plane
        dvec3 p = o + (double)want * d;
        if (std::abs(std::abs(p.x) - 1.5) < 1e-9 || std::abs(p.y + 1) < 1e-9 || std::abs(p.y - 1.2) < 1e-9) continue;
      }
      if (hit.has_value() != (want > 0)) {
        // Only a near-tangent ray may disagree: |grad f . d| small at the hit.
        double t = hit ? hit->t : (double)want;
        prism::sdk::QuadricShape q = prism::sdk::make_quadric(k.data(), &lo.x, &hi.x);
        dvec3 g = prism::sdk::quadric_gradient(q, o + t * d);
        EXPECT_LT(std::abs(glm::dot(glm::normalize(g), d)), 1e-6) << i;
        continue;
      }
      if (!hit) continue;
      EXPECT_LT(rel_err(hit->t, (double)want), 1e-9) << i;
      ++compared;
    }
  }
  EXPECT_GT(compared, 500);
}

TEST(QuadricTest, PluginMatchesSdkIntersectorBitForBit) {
  // Cylinder and cone test themselves against the same SDK function.
  Coefs k = {1, -0.5, 1, 0.1, 0, 0, 0, 0.2, 0, -0.3};
  dvec3 lo(-2, -1, -kInf), hi(2, 3, kInf);
  Shape s = quadric(k, lo, hi);
  prism::sdk::QuadricShape q = prism::sdk::make_quadric(k.data(), &lo.x, &hi.x);
  std::mt19937_64 rng(33);
  for (int i = 0; i < 300; ++i) {
    dvec3 o = 5.0 * random_unit(rng), d = glm::normalize(random_unit(rng) - o);
    double t = 0;
    dvec3 p, point, normal;
    bool want = prism::sdk::intersect_quadric(q, o, d, 0.0, kInf, t, p);
    auto hit = s.intersect(o, d);
    ASSERT_EQ(hit.has_value(), want);
    if (!hit) continue;
    EXPECT_EQ(hit->t, t);
    prism::sdk::quadric_surface(q, p, point, normal);
    EXPECT_EQ(s.surface(o, d, *hit).normal, normal);
  }
}

TEST(QuadricTest, SdkQuadraticSolverIsStableAndExactAboutZeroA) {
  double t0 = 0, t1 = 0;
  // (t - 1e-8)(t - 1e8): the textbook formula loses the small root entirely.
  ASSERT_EQ(prism::sdk::solve_quadratic(1.0, -(1e8 + 1e-8), 1.0, t0, t1), 2);
  EXPECT_LT(rel_err(t0, 1e-8), 1e-15);
  EXPECT_LT(rel_err(t1, 1e8), 1e-15);
  ASSERT_EQ(prism::sdk::solve_quadratic(0.0, 2.0, -4.0, t0, t1), 1);  // a == 0: linear
  EXPECT_EQ(t0, 2.0);
  EXPECT_EQ(prism::sdk::solve_quadratic(0.0, 0.0, 1.0, t0, t1), 0);
  ASSERT_EQ(prism::sdk::solve_quadratic(3.0, 0.0, 0.0, t0, t1), 2);  // double root at 0
  EXPECT_EQ(t0, 0.0);
  EXPECT_EQ(t1, 0.0);
  EXPECT_EQ(prism::sdk::solve_quadratic(1.0, 0.0, 1.0, t0, t1), 0);
  ASSERT_EQ(prism::sdk::solve_quadratic(1e-300, 1.0, -1.0, t0, t1), 2);  // tiny a: near root intact
  EXPECT_EQ(t1, 1.0);
}

TEST(QuadricTest, BoundsOnlyWhenClipBoxIsFinite) {
  double lo[3], hi[3];
  Shape open = quadric(kUnitSphere);
  EXPECT_EQ(open.desc().bounds(open.record(), lo, hi), 0);
  Shape half = quadric(kUnitSphere, {-1, -1, -kInf}, {1, 1, 1});
  EXPECT_EQ(half.desc().bounds(half.record(), lo, hi), 0);
  Shape boxed = quadric(kUnitSphere, {-1, -0.5, -1}, {1, 1, 1});
  ASSERT_EQ(boxed.desc().bounds(boxed.record(), lo, hi), 1);
  EXPECT_EQ(dvec3(lo[0], lo[1], lo[2]), dvec3(-1, -0.5, -1));
  EXPECT_EQ(dvec3(hi[0], hi[1], hi[2]), dvec3(1, 1, 1));
}

TEST(QuadricTest, NanRayMisses) {
  Shape s = quadric(kUnitSphere);
  EXPECT_FALSE(s.intersect({NAN, 0, -5}, {0, 0, 1}));
  EXPECT_FALSE(s.intersect({0, 0, -5}, {NAN, NAN, NAN}));
}

TEST(QuadricTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "quadric", {"quadric"}), "");
}

TEST(QuadricTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // The ray's origin.y carries 2^-58 more in long double than a double can hold;
  // where it grazes the surface that moves t by ~2e-12 relative, which only a
  // polish of the long double ray can see (to ~1e-19 / 1.7e-7 rad, a few
  // 1e-14 relative). Expected t: mpmath at 300 bits.
  Shape s = quadric({1, 1, 1, 0, 0, 0, 0, 0, 0, -1});
  const double c = 1.0 - 0x1p-46;
  auto hit = s.intersect({0, c, -10}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(s.refine({0, c + 0x1p-58L, -10}, {0, 0, 1}, *hit).t, 9.999999831433186728526251), 1e-13);
}

}  // namespace
