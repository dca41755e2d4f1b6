// Torus plugin tests. Expected values come from 2-D geometry worked out by
// hand (cross-sections of the torus are circles), evaluated in long double,
// and from a long-double sphere-tracing oracle on the exact distance
// function: algebra entirely unlike the plugin's quartic isolation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <span>
#include <string_view>

#include "prism/sdk/plugin_testing.hpp"

extern "C" const PrismPrimitiveDesc* prism_primitive_entry(void);

namespace {

using glm::dvec3;
using prism::sdk::kInf;
using prism::sdk::kPi;
using namespace prism::sdk::testing;
using ld = long double;

Shape torus(double major, double minor) { return Shape(prism_primitive_entry(), {major, minor}); }

ld distance_to_tube(const ld p[3], ld major, ld minor) {
  ld q = std::sqrt(p[0] * p[0] + p[2] * p[2]) - major;
  return std::sqrt(q * q + p[1] * p[1]) - minor;
}

// Sphere tracing with the exact distance in long double. `ambiguous` marks
// rays that graze (|cos| < 1e-3 at the hit) or pass within 1e-7 R of the
// surface without hitting: the band where two correct solvers may disagree.
struct Traced {
  bool hit = false, ambiguous = false;
  ld t = 0;
};
Traced sphere_trace(const dvec3& o, const dvec3& d, double major, double minor) {
  Traced out;
  ld t = 0, closest = INFINITY, limit = glm::length(o) + 2 * (major + minor);
  auto dist_at = [&](ld s) {
    ld p[3] = {o.x + s * d.x, o.y + s * d.y, o.z + s * d.z};
    return distance_to_tube(p, major, minor);
  };
  for (int i = 0; i < 4000000 && t < limit; ++i) {
    ld g = std::abs(dist_at(t));
    if (g < 1e-13L * major) {
      ld h = 1e-9L * major, slope = (dist_at(t + h) - dist_at(t - h)) / (2 * h);
      for (int k = 0; k < 3; ++k) t -= dist_at(t) / slope;  // polish the sphere-traced root
      out.hit = true;
      out.t = t;
      out.ambiguous = std::abs(slope) < 1e-3L;
      return out;
    }
    closest = std::min(closest, g);
    t += g;
  }
  out.ambiguous = closest < 1e-7L * major;
  return out;
}

dvec3 torus_point(double major, double minor, double phi, double theta) {
  double rho = major + minor * std::cos(theta);
  return {rho * std::cos(phi), minor * std::sin(theta), rho * std::sin(phi)};
}

dvec3 torus_normal(double phi, double theta) {
  return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

TEST(TorusTest, DescriptorDeclaresBothRadiiAsLengths) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  EXPECT_STREQ(desc.type_name, "torus");
  EXPECT_EQ(desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE, PRISM_PRIMITIVE_TRANSFORMABLE);
  ASSERT_EQ(desc.field_count, 2u);
  EXPECT_STREQ(desc.fields[0].name, "major_radius");
  EXPECT_STREQ(desc.fields[1].name, "minor_radius");
  for (int i = 0; i < 2; ++i)
    EXPECT_EQ(desc.fields[i].flags, PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH);
  EXPECT_EQ(desc.record_size % 16, 0u);
}

TEST(TorusTest, ValidateRejectsMinorNotBelowMajor) {
  const PrismPrimitiveDesc& desc = *prism_primitive_entry();
  auto err = validation_error(desc, {1.0, 2.0});
  ASSERT_TRUE(err);
  EXPECT_STREQ(err->field, "minor_radius");
  EXPECT_STREQ(err->message, "must be < major_radius (1), got 2");
  err = validation_error(desc, {0.1, 0.1});
  ASSERT_TRUE(err);
  EXPECT_STREQ(err->message, "must be < major_radius (0.1), got 0.1");
  EXPECT_EQ(validation_error(desc, {1.0, 0.999}), std::nullopt);
}

TEST(TorusTest, EquatorialRayFindsAllFourCrossingsInOrder) {
  Shape s = torus(1.0, 0.25);
  dvec3 o(-10, 0, 0), d(1, 0, 0);
  const double want[4] = {8.75, 9.25, 10.75, 11.25};  // x = -1.25, -0.75, 0.75, 1.25
  double tmin = 0.0;
  for (double w : want) {
    auto hit = s.intersect(o, d, tmin);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, w, 1e-14);
    tmin = hit->t;
  }
  EXPECT_FALSE(s.intersect(o, d, tmin));
  auto first = s.intersect(o, d);
  EXPECT_EQ(s.surface(o, d, *first).normal, dvec3(-1, 0, 0));
  EXPECT_FALSE(s.intersect(o, d, 0.0, 8.7));
}

// The occlusion test on the equatorial ray: blocked exactly where a
// crossing lies strictly inside (tmin, tmax), whether the interval holds
// the whole bracket of a root (solved no further), ends inside the tube or
// the hole, or ends on a crossing itself.
TEST(TorusTest, OcclusionTestSeesACrossingStrictlyInsideTheBounds) {
  Shape s = torus(1.0, 0.25);
  dvec3 o(-10, 0, 0), d(1, 0, 0);
  EXPECT_TRUE(s.occluded(o, d, 0.0, kInf));
  EXPECT_TRUE(s.occluded(o, d, 0.0, 30.0));
  EXPECT_FALSE(s.occluded(o, d, 0.0, 8.7));    // short of x = -1.25
  EXPECT_TRUE(s.occluded(o, d, 0.0, 8.8));
  EXPECT_FALSE(s.occluded(o, d, 8.8, 9.2));    // inside the tube, x = -1.2 .. -0.8
  EXPECT_TRUE(s.occluded(o, d, 8.8, 9.3));
  EXPECT_FALSE(s.occluded(o, d, 9.3, 10.7));   // across the hole, x = -0.7 .. 0.7
  EXPECT_TRUE(s.occluded(o, d, 9.3, 10.8));
  EXPECT_FALSE(s.occluded(o, d, 11.3, kInf));  // past the last crossing
  for (double tmin : {0.0, 9.0, 10.0, 11.0}) {  // each crossing as tmax, and the double after it
    const auto hit = s.intersect(o, d, tmin);
    ASSERT_TRUE(hit);
    EXPECT_FALSE(s.occluded(o, d, tmin, hit->t)) << tmin;
    EXPECT_TRUE(s.occluded(o, d, tmin, std::nextafter(hit->t, kInf))) << tmin;
  }
  EXPECT_FALSE(s.occluded(o, -d, 0.0, kInf));  // away from the torus
}

// Along o + t d, with crossings at `crossing` (ascending, derived by hand):
// from each window's end, the closest hit lies within 1e-9 of the next
// crossing; a window (tmin, tmax) that ends `gap` short of it sees nothing,
// one that ends `gap` past it or starts `gap` before it sees it; a window
// between two crossings, `gap` inside each (the tube's inside, the hole),
// sees nothing, nor one past the last crossing.
void expect_windows_around(Shape& s, const dvec3& o, const dvec3& d, std::span<const double> crossing, double gap) {
  double tmin = 0.0;
  for (double want : crossing) {
    const auto hit = s.intersect(o, d, tmin);
    ASSERT_TRUE(hit) << want;
    EXPECT_NEAR(hit->t, want, 1e-9);
    EXPECT_FALSE(s.occluded(o, d, tmin, want - gap)) << want;
    EXPECT_TRUE(s.occluded(o, d, tmin, want + gap)) << want;
    EXPECT_TRUE(s.occluded(o, d, want - gap, kInf)) << want;
    EXPECT_FALSE(s.intersect(o, d, tmin, want - gap)) << want;
    tmin = want + gap;
  }
  for (size_t k = 0; k + 1 < crossing.size(); ++k)
    EXPECT_FALSE(s.occluded(o, d, crossing[k] + gap, crossing[k + 1] - gap)) << crossing[k];
  EXPECT_FALSE(s.occluded(o, d, tmin, kInf));  // past the last crossing
}

// The equatorial ray of the test above from a million units away: the
// crossings at x = -1.25, -0.75, 0.75, 1.25 (t = 1e6 + x, exact in double),
// and windows (tmin, tmax) that end or start a micro-unit from one of them,
// far above t's rounding at 1e6 (~1e-10): the window tests on t, after the
// origin moved to the chord's middle, must keep each crossing on its side.
TEST(TorusTest, WindowsAroundCrossingsFromAfar) {
  Shape s = torus(1.0, 0.25);
  const dvec3 o(-1e6, 0, 0), d(1, 0, 0);
  const double crossing[4] = {999998.75, 999999.25, 1000000.75, 1000001.25};
  expect_windows_around(s, o, d, crossing, 1e-6);
  // A ray beside the tube, 1e-6 outside its outer equator (x = 1.25 + 1e-6,
  // along z): no hit; 1e-6 inside it: the crossings at z = -+sqrt(1.25^2 - x^2).
  EXPECT_FALSE(s.occluded({1.25 + 1e-6, 0, -1e6}, {0, 0, 1}, 0.0, kInf));
  const double x = 1.25 - 1e-6;
  const auto grazing = s.intersect({x, 0, -1e6}, {0, 0, 1});
  ASSERT_TRUE(grazing);
  EXPECT_NEAR(grazing->t, 1e6 - std::sqrt((1.25 - x) * (1.25 + x)), 1e-9);
}

// The same from x = -10 (t = 8.75, 9.25, 10.75, 11.25), windows 1e-8 from
// each crossing: the occlusion test's Bernstein proof (a window clear of
// the tube by more than rounding) must never claim a window that holds a
// crossing, nor the scan miss one just inside.
TEST(TorusTest, WindowsAHundredthOfAMicronFromEachCrossing) {
  Shape s = torus(1.0, 0.25);
  const dvec3 o(-10, 0, 0), d(1, 0, 0);
  const double crossing[4] = {8.75, 9.25, 10.75, 11.25};
  expect_windows_around(s, o, d, crossing, 1e-8);
  EXPECT_FALSE(s.occluded(o, -d, 0.0, kInf));  // away from the torus
}

TEST(TorusTest, RayFromInsideTubeExitsThroughTopWithSpecUv) {
  Shape s = torus(1.0, 0.25);
  auto hit = s.intersect({0, 0, 1}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 0.25, 1e-15);
  Surface surf = s.surface({0, 0, 1}, {0, 1, 0}, *hit);
  EXPECT_NEAR(surf.normal.y, 1.0, 1e-15);
  EXPECT_NEAR(surf.uv.x, 0.75, 1e-15);  // 0.5 + atan2(1, 0)/2pi
  EXPECT_NEAR(surf.uv.y, 0.75, 1e-15);  // 0.5 + atan2(0.25, 0)/2pi
}

TEST(TorusTest, RayFromCentreOfHoleHitsInnerEquator) {
  Shape s = torus(2.0, 0.5);
  auto hit = s.intersect({0, 0, 0}, {0, 0, -1});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 1.5, 1e-15);
  EXPECT_NEAR(s.surface({0, 0, 0}, {0, 0, -1}, *hit).normal.z, 1.0, 1e-15);  // outward = toward the axis
}

TEST(TorusTest, NormalHitAtKnownAnglesGivesSpecUv) {
  double major = 1.5, minor = 0.4, phi = 40 * kPi / 180, theta = 60 * kPi / 180;
  Shape s = torus(major, minor);
  dvec3 p = torus_point(major, minor, phi, theta), n = torus_normal(phi, theta);
  auto hit = s.intersect(p + 3.0 * n, -n);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 3.0, 1e-14);
  Surface surf = s.surface(p + 3.0 * n, -n, *hit);
  EXPECT_NEAR(glm::length(surf.point - p), 0.0, 1e-15);
  EXPECT_NEAR(glm::dot(glm::normalize(surf.normal), n), 1.0, 1e-15);
  EXPECT_NEAR(surf.uv.x, 0.5 + 40.0 / 360.0, 1e-15);
  EXPECT_NEAR(surf.uv.y, 0.5 + 60.0 / 360.0, 1e-15);
}

TEST(TorusTest, RayAlongAxisPassesThroughHole) {
  for (double minor : {0.5, 0.1, 1e-3}) {
    Shape s = torus(1.0, minor);
    EXPECT_FALSE(s.intersect({0, 1e4, 0}, {0, -1, 0})) << minor;
    EXPECT_FALSE(s.intersect({0, 5, 0}, {0, -1, 0})) << minor;
    EXPECT_FALSE(s.intersect({0, 0, 0}, {0, 1, 0})) << minor;
    // Tilted so that it crosses y = 0 at x = 0.4: still inside the hole.
    EXPECT_FALSE(s.intersect({0, 1e4, 0}, glm::normalize(dvec3(0.4e-4, -1, 0)))) << minor;
  }
}

TEST(TorusTest, ThinTubeGrazingRayFrom1e4) {
  // R = 1, r = 1e-3; the line x = -1, y = c runs along z, tangent to the core
  // circle and c just below r: it meets the tube where sqrt(1 + z^2) = 1 + w,
  // w = sqrt(r^2 - c^2), i.e. z = -sqrt(2w + w^2).
  double minor = 1e-3;
  Shape s = torus(1.0, minor);
  for (double rel : {1e-2, 1e-5, 1e-8}) {
    double c = minor * (1.0 - rel);
    auto hit = s.intersect({-1, c, -1e4}, {0, 0, 1});
    ASSERT_TRUE(hit) << rel;
    ld w = std::sqrt(((ld)minor - c) * ((ld)minor + c));
    ld want = 1e4L - std::sqrt(2 * w + w * w);
    EXPECT_LT(rel_err(hit->t, (double)want), 1e-12) << rel;
  }
  EXPECT_FALSE(s.intersect({-1, minor * (1.0 + 1e-8), -1e4}, {0, 0, 1}));
}

TEST(TorusTest, GrazingOuterEquatorFrom1e4HitsOrMissesBySide) {
  Shape s = torus(1.0, 1e-3);
  ld outer = 1.001L;
  double c = 1.001 * (1.0 - 1e-10);
  auto hit = s.intersect({-1e4, 0, c}, {1, 0, 0});
  ASSERT_TRUE(hit);
  ld want = 1e4L - std::sqrt((outer - c) * (outer + c));
  EXPECT_LT(rel_err(hit->t, (double)want), 1e-12);
  EXPECT_FALSE(s.intersect({-1e4, 0, 1.001 * (1.0 + 1e-10)}, {1, 0, 0}));
}

TEST(TorusTest, GrazingInnerEquatorSeparatesTheCloseRootPair) {
  // z = c just inside the hole's radius R - r: the ray leaves the tube into
  // the hole and re-enters it at x = -+sqrt((R-r)^2 - c^2), 2e-5 apart.
  Shape s = torus(1.0, 0.25);
  double c = 0.75 * (1.0 - 1e-10);
  dvec3 o(-1e4, 0, c), d(1, 0, 0);
  auto first = s.intersect(o, d);
  ASSERT_TRUE(first);
  ld half = std::sqrt((0.75L - c) * (0.75L + c));
  auto leave = s.intersect(o, d, first->t);
  ASSERT_TRUE(leave);
  EXPECT_LT(rel_err(leave->t, (double)(1e4L - half)), 1e-13);
  auto reenter = s.intersect(o, d, leave->t);
  ASSERT_TRUE(reenter);
  EXPECT_LT(rel_err(reenter->t, (double)(1e4L + half)), 1e-13);
  EXPECT_GT(reenter->t, leave->t);
}

TEST(TorusTest, RandomRaysFromAfarMatchSphereTracingOracle) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  int compared = 0, ambiguous = 0;
  for (double minor : {0.5, 0.1, 1e-3}) {
    Shape s = torus(1.0, minor);
    for (double dist : {3.0, 100.0, 1e4}) {
      for (int i = 0; i < 150; ++i) {
        double phi = angle(rng), theta = angle(rng);
        dvec3 target = torus_point(1.0, minor, phi, theta);
        dvec3 d = -random_in_hemisphere(rng, torus_normal(phi, theta));
        dvec3 o = target - dist * d;
        Traced want = sphere_trace(o, d, 1.0, minor);
        if (want.ambiguous) {
          ++ambiguous;
          continue;
        }
        auto hit = s.intersect(o, d);
        ASSERT_EQ(hit.has_value(), want.hit) << "r " << minor << " dist " << dist << " i " << i;
        if (!hit) continue;
        EXPECT_LT(rel_err(hit->t, (double)want.t), 1e-9) << "r " << minor << " dist " << dist << " i " << i;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 1100);
  EXPECT_LT(ambiguous, 60);
}

TEST(TorusTest, RaysFromInsideTheTubeMatchSphereTracingOracle) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> angle(-kPi, kPi), frac(0.0, 0.95);
  for (double minor : {0.5, 1e-3}) {
    Shape s = torus(1.0, minor);
    for (int i = 0; i < 200; ++i) {
      dvec3 o = torus_point(1.0, minor * frac(rng), angle(rng), angle(rng));
      dvec3 d = random_unit(rng);
      Traced want = sphere_trace(o, d, 1.0, minor);
      if (want.ambiguous) continue;
      ASSERT_TRUE(want.hit);
      auto hit = s.intersect(o, d);
      ASSERT_TRUE(hit) << i;
      EXPECT_LT(rel_err(hit->t, (double)want.t), 1e-9) << i;
    }
  }
}

TEST(TorusTest, SecondaryRaysFromOffsetHitPointsMatchSphereTracingOracle) {
  // Spec offsets P +- eps n with random directions: hits a few eps away (the
  // tube itself again, seen from just outside or inside) must be as exact as
  // far ones; a solver that stops on a bisection midpoint fails here.
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> angle(-kPi, kPi), u01(0.0, 1.0);
  for (double minor : {0.5, 1e-2}) {
    Shape s = torus(1.0, minor);
    for (int i = 0; i < 400; ++i) {
      double phi = angle(rng), theta = angle(rng);
      dvec3 p = torus_point(1.0, minor, phi, theta), n = torus_normal(phi, theta);
      dvec3 o = p + (u01(rng) < 0.5 ? 1.0 : -1.0) * spec_offset(p) * n, d = random_unit(rng);
      Traced want = sphere_trace(o, d, 1.0, minor);
      if (want.ambiguous) continue;
      auto hit = s.intersect(o, d);
      ASSERT_EQ(hit.has_value(), want.hit) << i;
      if (hit) {
        EXPECT_LT(rel_err(hit->t, (double)want.t), 1e-9) << i;
      }
    }
  }
}

TEST(TorusTest, SdkBracketedSolverReturnsConvergedNewtonIterate) {
  // g(s) = s^2 - 2 on [1, 2]: converged, not a bracket midpoint.
  auto g = [](double s, double& v, double& dv) {
    v = s * s - 2.0;
    dv = 2.0 * s;
  };
  double root = prism::sdk::solve_bracketed(g, 1.0, 2.0, -1.0, 2.0, 1e-12);
  EXPECT_NEAR(root, std::sqrt(2.0), 4e-16);
}

TEST(TorusTest, SurfacePointIsOnTheTubeAcrossScales) {
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (double scale : {1e-4, 1.0, 1e6}) {
    double major = scale, minor = 0.3 * scale;
    Shape s = torus(major, minor);
    for (int i = 0; i < 200; ++i) {
      double phi = angle(rng), theta = angle(rng);
      dvec3 d = -random_in_hemisphere(rng, torus_normal(phi, theta));
      dvec3 o = torus_point(major, minor, phi, theta) - 10.0 * scale * d;
      auto hit = s.intersect(o, d);
      if (!hit) continue;
      Surface surf = s.surface(o, d, *hit);
      ld p[3] = {surf.point.x, surf.point.y, surf.point.z};
      EXPECT_LT(std::abs(distance_to_tube(p, major, minor)), 1e-15L * scale);
      EXPECT_NEAR(glm::length(surf.normal), 1.0, 1e-15);
    }
  }
}

TEST(TorusTest, BoundsCoverOuterRadiusAndTubeHeight) {
  Shape s = torus(2.0, 0.5);
  double lo[3], hi[3];
  ASSERT_EQ(s.desc().bounds(s.record(), lo, hi), 1);
  EXPECT_EQ(dvec3(lo[0], lo[1], lo[2]), dvec3(-2.5, -0.5, -2.5));
  EXPECT_EQ(dvec3(hi[0], hi[1], hi[2]), dvec3(2.5, 0.5, 2.5));
}

TEST(TorusTest, NanRayMisses) {
  Shape s = torus(1.0, 0.25);
  EXPECT_FALSE(s.intersect({NAN, 0, -5}, {0, 0, 1}));
  EXPECT_FALSE(s.intersect({0, 0, -5}, {NAN, NAN, NAN}));
}

TEST(TorusTest, DescriptorCarriesGpuIntersectorWithTypePrefix) {
  EXPECT_EQ(gpu_intersector_problem(*prism_primitive_entry(), "torus", {"roots"}), "");
}

TEST(TorusTest, RefinePolishesAGrazingHitForTheLongDoubleRay) {
  // The ray's origin.y (it skims the top of the tube) carries 2^-58 more in long double than a double can hold;
  // where it grazes the surface that moves t by ~2e-12 relative, which only a
  // polish of the long double ray can see (to ~1e-19 / 1.7e-7 rad, a few
  // 1e-14 relative). Expected t: mpmath at 300 bits.
  Shape s = torus(1.0, 0.25);
  const double y = 0.25 - 0x1p-48;
  auto hit = s.intersect({-10, y, 0}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_LT(rel_err(s.refine({-10, y + 0x1p-58L, 0}, {1, 0, 0}, *hit).t, 8.999999957873736031731213), 1e-13);
}

}  // namespace
