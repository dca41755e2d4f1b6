// Tests of the stability suite's oracle (exact.cpp). Every expected value
// below is derived by hand in the comment next to it, not produced by the
// code; then a self-consistency sweep per primitive.
#include "exact.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace prism::stability {
namespace {

using nlohmann::json;

// Quad constants without the Q suffix (the project builds with
// CMAKE_CXX_EXTENSIONS OFF): parsed from decimal, correctly rounded.
real Q(const char* text) { return strtoflt128(text, nullptr); }
real qsqrt(real v) { return sqrtq(v); }

ExactObject object(const char* text) { return ExactObject(json::parse(text)); }

ExactRay ray(real ox, real oy, real oz, real dx, real dy, real dz, real tmin = 0) {
  ExactRay r;
  r.origin = {ox, oy, oz};
  real n = sqrtq(dx * dx + dy * dy + dz * dz);
  r.dir = {dx / n, dy / n, dz / n};
  r.tmin = tmin;
  return r;
}

std::string str(real v) { return to_string(v, 36); }

#define EXPECT_Q(actual, expected, tol)                                                              \
  do {                                                                                               \
    real a_ = (actual), e_ = (expected);                                                             \
    EXPECT_TRUE(fabsq(a_ - e_) <= (tol)) << #actual << " = " << str(a_) << ", expected " << str(e_) \
                                         << " (diff " << str(a_ - e_) << ")";                        \
  } while (0)

void expect_hit(const ExactHit& h, real t, real nx, real ny, real nz, real t_tol = Q("1e-32"),
                real n_tol = Q("1e-32")) {
  ASSERT_TRUE(h.hit) << "expected a hit at t = " << str(t);
  EXPECT_Q(h.t, t, t_tol);
  EXPECT_Q(h.normal.x, nx, n_tol);
  EXPECT_Q(h.normal.y, ny, n_tol);
  EXPECT_Q(h.normal.z, nz, n_tol);
}

void expect_miss(const ExactHit& h) { EXPECT_FALSE(h.hit) << "unexpected hit at t = " << str(h.t); }

// Random rays through the object's neighbourhood (doubles, as a suite sends).
std::vector<ExactRay> random_rays(int count, const Vec& centre, double size, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  std::uniform_real_distribution<double> box(-1, 1);
  std::vector<ExactRay> rays;
  for (int i = 0; i < count; ++i) {
    double u[3] = {gauss(rng), gauss(rng), gauss(rng)};
    double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    double c[3] = {static_cast<double>(centre.x), static_cast<double>(centre.y), static_cast<double>(centre.z)};
    double o[3], d[3];
    for (int k = 0; k < 3; ++k) {
      o[k] = c[k] + 3 * size * u[k] / n;
      d[k] = c[k] + size * box(rng) - o[k];
    }
    rays.push_back(make_ray(o, d, 0));
  }
  return rays;
}

// ------------------------------------------------------------------ sphere

const char* kUnitSphere = R"({"type": "sphere", "radius": 1})";

TEST(ExactSphere, FromOutside) {
  // |(0,0,-5) + t z| = 1  ->  t = 5 - 1; the point (0,0,-1), N = p = -z.
  expect_hit(object(kUnitSphere).intersect(ray(0, 0, -5, 0, 0, 1)), 4, 0, 0, -1);
}

TEST(ExactSphere, FromInside) {
  // From the centre: t = radius; the outward normal, seen from inside: +z.
  expect_hit(object(kUnitSphere).intersect(ray(0, 0, 0, 0, 0, 1)), 1, 0, 0, 1);
}

TEST(ExactSphere, FarOriginIsExact) {
  // t = 1e6 - 1 = 999999, exactly representable.
  expect_hit(object(kUnitSphere).intersect(ray(0, 0, -1e6, 0, 0, 1)), 999999, 0, 0, -1, 0);
}

TEST(ExactSphere, TminIsStrict) {
  // Roots 4 and 6; t > tmin strictly: tmin = 4 gives the far root at z = +1.
  auto s = object(kUnitSphere);
  expect_hit(s.intersect(ray(0, 0, -5, 0, 0, 1, 4)), 6, 0, 0, 1);
  expect_hit(s.intersect(ray(0, 0, -5, 0, 0, 1, Q("3.999999999999999999999"))), 4, 0, 0, -1);
  expect_miss(s.intersect(ray(0, 0, -5, 0, 0, 1, 6)));
}

TEST(ExactSphere, GrazingRayStillHits) {
  // y = 1 - 1e-20 (quad): t = 5 - sqrt(1 - y^2) = 5 - sqrt(2e-20 - 1e-40)
  //   = 5 - sqrt(2) * 1e-10 * (1 - 2.5e-21 + ...); the correction (3.5e-31) is
  // below the tolerance, which is the problem's own conditioning: a quad
  // rounding of y (1e-34) moves t by 1e-34 / sqrt(2e-20) ~ 7e-25.
  real y = 1 - Q("1e-20");
  real root = Q("1.41421356237309504880168872420969807857e-10");
  auto h = object(kUnitSphere).intersect(ray(0, y, -5, 0, 0, 1));
  // N = p = (0, y, -sqrt(2e-20)).
  expect_hit(h, 5 - root, 0, y, -root, Q("1e-23"), Q("1e-23"));
}

TEST(ExactSphere, TangentRayHitsAndAboveMisses) {
  // y = 1 exactly: a double root at t = 5 (a touch counts as a hit), N = +y.
  auto s = object(kUnitSphere);
  expect_hit(s.intersect(ray(0, 1, -5, 0, 0, 1)), 5, 0, 1, 0, Q("1e-30"));
  expect_miss(s.intersect(ray(0, 1 + Q("1e-20"), -5, 0, 0, 1)));
}

TEST(ExactSphere, CentreAndRotation) {
  // Centre (1,2,3), radius 2, any rotation: from (1,2,-10) along +z the
  // surface is at z = 3 - 2 = 1: t = 11, N = -z.
  auto s = object(R"({"type": "sphere", "center": [1, 2, 3], "radius": 2,
                      "rotation": {"axis": [1, 1, 0], "degrees": 33}})");
  expect_hit(s.intersect(ray(1, 2, -10, 0, 0, 1)), 11, 0, 0, -1, Q("1e-31"), Q("1e-32"));
}

TEST(ExactSphere, DistanceToSurface) {
  auto s = object(kUnitSphere);
  real e = Q("1e-6");
  EXPECT_Q(s.distance_to_surface({1 + e, 0, 0}), e, Q("1e-33"));
  EXPECT_Q(s.distance_to_surface({0, 1 - e, 0}), e, Q("1e-33"));
  // Centre (1,2,3), radius 2: the point (1, 2 + 2 + 1e-6, 3).
  auto c = object(R"({"type": "sphere", "center": [1, 2, 3], "radius": 2})");
  EXPECT_Q(c.distance_to_surface({1, 4 + e, 3}), e, Q("1e-32"));
  EXPECT_Q(s.size(), 1, 0);
}

// ------------------------------------------------------------------ plane

TEST(ExactPlane, BothSidesNormalAsGiven) {
  // Plane y = 1 (normal given unnormalised as (0,2,0)): from y = 5 downward
  // and from y = -3 upward both hit at t = 4 with N = +y (not the facing one).
  auto p = object(R"({"type": "plane", "point": [0, 1, 0], "normal": [0, 2, 0]})");
  expect_hit(p.intersect(ray(0, 5, 0, 0, -1, 0)), 4, 0, 1, 0);
  expect_hit(p.intersect(ray(0, -3, 0, 0, 1, 0)), 4, 0, 1, 0);
}

TEST(ExactPlane, ObliqueParallelAndBehind) {
  auto p = object(R"({"type": "plane", "point": [0, 1, 0], "normal": [0, 1, 0]})");
  // From the origin along (1,1,0)/sqrt2: y = t/sqrt2 = 1 -> t = sqrt2.
  expect_hit(p.intersect(ray(0, 0, 0, 1, 1, 0)), qsqrt(2), 0, 1, 0);
  expect_miss(p.intersect(ray(0, 0, 0, 1, 0, 0)));   // parallel
  expect_miss(p.intersect(ray(0, 1, 0, 1, 0, 0)));   // in the plane
  expect_miss(p.intersect(ray(0, 0, 0, 0, -1, 0)));  // behind
  // Tilted normal (1,1,1) through (1,1,1): x+y+z = 3; from 0 along +x: t = 3.
  auto q = object(R"({"type": "plane", "point": [1, 1, 1], "normal": [1, 1, 1]})");
  real k = 1 / qsqrt(3);
  expect_hit(q.intersect(ray(0, 0, 0, 1, 0, 0)), 3, k, k, k, Q("1e-32"));
  EXPECT_Q(q.distance_to_surface({0, 0, 0}), qsqrt(3), Q("1e-32"));
}

TEST(ExactPlane, RejectsCentreAndRotation) {
  EXPECT_THROW(object(R"({"type": "plane", "point": [0,0,0], "normal": [0,1,0], "center": [0,0,0]})"),
               std::invalid_argument);
  EXPECT_THROW(object(R"({"type": "plane", "point": [0,0,0], "normal": [0,0,0]})"), std::invalid_argument);
}

// ------------------------------------------------------------------ box

const char* kBox123 = R"({"type": "box", "half_size": [1, 2, 3]})";
const char* kCube = R"({"type": "box", "half_size": [1, 1, 1]})";

TEST(ExactBox, Faces) {
  auto b = object(kBox123);
  expect_hit(b.intersect(ray(-5, 0, 0, 1, 0, 0)), 4, -1, 0, 0);  // x = -1
  expect_hit(b.intersect(ray(0, -5, 0, 0, 1, 0)), 3, 0, -1, 0);  // y = -2
  expect_hit(b.intersect(ray(0, 0, 10, 0, 0, -1)), 7, 0, 0, 1);  // z = +3
  expect_miss(b.intersect(ray(-5, 2.5, 0, 1, 0, 0)));
  expect_miss(b.intersect(ray(-5, 0, 0, -1, 0, 0)));
  EXPECT_Q(b.size(), 3, 0);
}

TEST(ExactBox, InsideStartHitsTheExitFace) {
  // Spec silent; as plugins/box/box.cpp: the exit face when the entry is <= tmin.
  auto b = object(kBox123);
  expect_hit(b.intersect(ray(0, 0, 0, 0, 1, 0)), 2, 0, 1, 0);
  expect_hit(b.intersect(ray(0.5, 0, 0, -1, 0, 0)), 1.5, -1, 0, 0);
  // tmin past the entry: the exit. From x = -5: entry 4, exit 6.
  expect_hit(b.intersect(ray(-5, 0, 0, 1, 0, 0, 4)), 6, 1, 0, 0);
  expect_miss(b.intersect(ray(-5, 0, 0, 1, 0, 0, 6)));
}

TEST(ExactBox, EdgesAndCornersTieToLowerAxis) {
  auto b = object(kCube);
  // (-3,-3,0) along (1,1,0): the edge (-1,-1,0) at t = 2 sqrt2; |p.x| = |p.y|: x wins.
  expect_hit(b.intersect(ray(-3, -3, 0, 1, 1, 0)), 2 * qsqrt(2), -1, 0, 0, Q("1e-32"));
  // (3,-3,0) along (-1,1,0): the edge (1,-1,0): +x.
  expect_hit(b.intersect(ray(3, -3, 0, -1, 1, 0)), 2 * qsqrt(2), 1, 0, 0, Q("1e-32"));
  // (0,-3,-3) along (0,1,1): the edge (0,-1,-1): y wins over z.
  expect_hit(b.intersect(ray(0, -3, -3, 0, 1, 1)), 2 * qsqrt(2), 0, -1, 0, Q("1e-32"));
  // The corner (-1,-1,-1) from (-3,-3,-3): t = 2 sqrt3, x wins.
  expect_hit(b.intersect(ray(-3, -3, -3, 1, 1, 1)), 2 * qsqrt(3), -1, 0, 0, Q("1e-32"));
}

TEST(ExactBox, RayAlongAFaceTouches) {
  // In the plane y = 1 (the top face) along +x: the solid's boundary is hit
  // at (-1,1,0), t = 4, where x and y tie: N = -x. 1e-20 above: a miss.
  auto b = object(kCube);
  expect_hit(b.intersect(ray(-5, 1, 0, 1, 0, 0)), 4, -1, 0, 0);
  expect_miss(b.intersect(ray(-5, 1 + Q("1e-20"), 0, 1, 0, 0)));
  expect_hit(b.intersect(ray(-5, 1 - Q("1e-20"), 0, 1, 0, 0)), 4, -1, 0, 0);
}

TEST(ExactBox, CentreAndRotation) {
  // 90 deg about z maps local x -> world y, local y -> world -x. Centre
  // (10,0,0), half (1,2,3): world x extent 2, y extent 1.
  auto b = object(R"({"type": "box", "center": [10, 0, 0], "half_size": [1, 2, 3],
                      "rotation": {"axis": [0, 0, 1], "degrees": 90}})");
  // From the origin along +x: world x = 8 (t = 8); local p = (0, 2, 0): face
  // +y, N = R (0,1,0) = (-1,0,0).
  expect_hit(b.intersect(ray(0, 0, 0, 1, 0, 0)), 8, -1, 0, 0);
  // From (10,-5,0) along +y: world y = -1 (t = 4); local (-1,0,0): N = (0,-1,0).
  expect_hit(b.intersect(ray(10, -5, 0, 0, 1, 0)), 4, 0, -1, 0);
}

TEST(ExactBox, DistanceToSurface) {
  auto b = object(kBox123);
  real e = Q("1e-6");
  EXPECT_Q(b.distance_to_surface({1 + e, 0, 0}), e, Q("1e-33"));
  EXPECT_Q(b.distance_to_surface({0.5, 0, 0}), 0.5, 0);     // inside: nearest face x = 1
  EXPECT_Q(b.distance_to_surface({2, 3, 3}), qsqrt(2), Q("1e-33"));  // outside the edge (1,2,3)
}

// ------------------------------------------------------------------ torus

const char* kTorus = R"({"type": "torus", "major_radius": 1, "minor_radius": 0.25})";

TEST(ExactTorus, AlongTheXAxisAllFourRoots) {
  // y = z = 0: the tube cuts the x axis at |x| = 0.75 and 1.25. From x = -5:
  // t = 3.75 (x = -1.25, N = -x), 4.25 (x = -0.75, N = +x towards the hole),
  // 5.75 (x = 0.75, N = -x), 6.25 (x = 1.25, N = +x).
  auto t = object(kTorus);
  expect_hit(t.intersect(ray(-5, 0, 0, 1, 0, 0)), 3.75, -1, 0, 0);
  expect_hit(t.intersect(ray(-5, 0, 0, 1, 0, 0, 3.75)), 4.25, 1, 0, 0);
  expect_hit(t.intersect(ray(-5, 0, 0, 1, 0, 0, 4.25)), 5.75, -1, 0, 0);
  expect_hit(t.intersect(ray(-5, 0, 0, 1, 0, 0, 5.75)), 6.25, 1, 0, 0);
  expect_miss(t.intersect(ray(-5, 0, 0, 1, 0, 0, 6.25)));
  EXPECT_Q(t.size(), 1.25, 0);
}

TEST(ExactTorus, ThroughTheHoleAlongTheAxisMisses) {
  auto t = object(kTorus);
  expect_miss(t.intersect(ray(0, 5, 0, 0, -1, 0)));
  expect_miss(t.intersect(ray(0, 0, 0, 0, 1, 0)));
}

TEST(ExactTorus, TangentToTheTubeTop) {
  // y = r = 0.25, z = 0: (x^2 + 1)^2 = 4 x^2, i.e. (x^2 - 1)^2 = 0: double
  // roots at x = -1 and x = 1; the first at t = 4, on the tube top: N = +y.
  auto t = object(kTorus);
  expect_hit(t.intersect(ray(-5, 0.25, 0, 1, 0, 0)), 4, 0, 1, 0, Q("1e-28"), Q("1e-28"));
  // 1e-20 above: a miss.
  expect_miss(t.intersect(ray(-5, 0.25 + Q("1e-20"), 0, 1, 0, 0)));
  // 1e-20 below: (rho - 1)^2 = r^2 - y^2 = (r - y)(r + y), first at
  // rho = 1 + sqrt(r^2 - y^2) = 1 + sqrt(5e-21) (1 - O(1e-20)): t = 4 - 7.07e-11.
  // Tolerance: the crossing's slope is ~3e-10, so a quad rounding of g moves
  // t by ~1e-24.
  real y = 0.25 - Q("1e-20");
  real root = Q("7.07106781186547524400844362104849039285e-11");
  auto h = t.intersect(ray(-5, y, 0, 1, 0, 0));
  ASSERT_TRUE(h.hit);
  EXPECT_Q(h.t, 4 - root, Q("1e-22"));
}

TEST(ExactTorus, TangentToTheOuterEquator) {
  // x = R + r = 1.25, y = 0, along z: rho = sqrt(1.5625 + z^2) >= 1.25, equal
  // at z = 0: a touch at t = 5 (on the bounding sphere too), N = +x.
  expect_hit(object(kTorus).intersect(ray(1.25, 0, -5, 0, 0, 1)), 5, 1, 0, 0, Q("1e-28"), Q("1e-28"));
}

TEST(ExactTorus, InnerEquatorTouchedFromInside) {
  // x = 0.75, y = 0, along z from z = -5: g = |rho - 1| - 0.25 with
  // rho^2 = 0.5625 + z^2: enters at rho = 1.25 (z = -1, t = 4), touches the
  // inner equator from inside at z = 0 (t = 5, a double root, N = -x), exits
  // at z = 1 (t = 6). Normals at (0.75, 0, -+1): (0.6, 0, -+0.8).
  auto t = object(kTorus);
  real a = Q("0.6"), b = Q("0.8");
  expect_hit(t.intersect(ray(0.75, 0, -5, 0, 0, 1)), 4, a, 0, -b, Q("1e-32"), Q("1e-32"));
  expect_hit(t.intersect(ray(0.75, 0, -5, 0, 0, 1, 4.5)), 5, -1, 0, 0, Q("1e-28"), Q("1e-28"));
  expect_hit(t.intersect(ray(0.75, 0, -5, 0, 0, 1, 5)), 6, a, 0, b, Q("1e-32"), Q("1e-32"));
}

TEST(ExactTorus, FarOriginAndInsideTheTube) {
  auto t = object(kTorus);
  expect_hit(t.intersect(ray(-1e6, 0, 0, 1, 0, 0)), Q("999998.75"), -1, 0, 0, Q("1e-26"));
  // From the core circle point (-1,0,0): the tube wall at distance r.
  expect_hit(t.intersect(ray(-1, 0, 0, 1, 0, 0)), 0.25, 1, 0, 0);
  expect_hit(t.intersect(ray(-1, 0, 0, 0, 1, 0)), 0.25, 0, 1, 0);
}

TEST(ExactTorus, ThinTube) {
  // R = 1, r = 0.001 (read as the double 0.001): from x = -5, t = 4 - r.
  auto t = object(R"({"type": "torus", "major_radius": 1, "minor_radius": 0.001})");
  real r = static_cast<real>(0.001);
  expect_hit(t.intersect(ray(-5, 0, 0, 1, 0, 0)), 4 - r, -1, 0, 0);
  expect_hit(t.intersect(ray(-5, 0, 0, 1, 0, 0, 4)), 4 + r, 1, 0, 0);
  expect_miss(t.intersect(ray(-5, 2 * r, 0, 1, 0, 0)));
}

TEST(ExactTorus, RotatedByAxisAndByQuaternion) {
  // 90 deg about x maps local y (the axis) to world z: the ring lies in the
  // world xy plane. Along +y from (0,-5,0): t = 3.75, N = -y; along the world
  // z axis: through the hole.
  for (const char* rot : {R"({"axis": [1, 0, 0], "degrees": 90})",
                          R"({"quaternion": [0.7071067811865476, 0.7071067811865476, 0, 0]})"}) {
    json j = json::parse(kTorus);
    j["rotation"] = json::parse(rot);
    j["center"] = {0, 0, 0};
    ExactObject t(j);
    expect_hit(t.intersect(ray(0, -5, 0, 0, 1, 0)), 3.75, 0, -1, 0, Q("1e-31"), Q("1e-31"));
    expect_miss(t.intersect(ray(0, 0, 5, 0, 0, -1)));
  }
}

TEST(ExactTorus, DistanceToSurface) {
  auto t = object(kTorus);
  real e = Q("1e-6");
  EXPECT_Q(t.distance_to_surface({1.25 + e, 0, 0}), e, Q("1e-33"));
  EXPECT_Q(t.distance_to_surface({0, 0.25 - e, 1}), e, Q("1e-33"));
}

// An independent cross-check of the torus: the expanded quartic in s (origin
// at the foot of the perpendicular) solved for all four complex roots by
// Durand-Kerner in quad, each real one polished by Newton on the polynomial.
// Different algebra from the oracle's sampling of the signed distance.
struct Cplx {
  real re = 0, im = 0;
};
Cplx operator-(Cplx a, Cplx b) { return {a.re - b.re, a.im - b.im}; }
Cplx operator*(Cplx a, Cplx b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
Cplx operator/(Cplx a, Cplx b) {
  real n = b.re * b.re + b.im * b.im;
  return {(a.re * b.re + a.im * b.im) / n, (a.im * b.re - a.re * b.im) / n};
}

// The smallest real root s > smin of the monic quartic s^4 + c[3] s^3 + ... + c[0];
// false when there is none.
bool quartic_first_root(const real c[4], real scale, real smin, real& root) {
  auto eval = [&](Cplx z) {
    Cplx v{1, 0};
    for (int k = 3; k >= 0; --k) v = v * z - Cplx{-c[k], 0};
    return v;
  };
  Cplx z[4];
  Cplx seed{Q("0.4") * scale, Q("0.9") * scale}, w{1, 0};
  for (auto& zi : z) zi = w = w * seed, zi = w;
  for (int it = 0; it < 300; ++it) {
    real moved = 0;
    for (int i = 0; i < 4; ++i) {
      Cplx den{1, 0};
      for (int j = 0; j < 4; ++j)
        if (j != i) den = den * (z[i] - z[j]);
      Cplx step = eval(z[i]) / den;
      z[i] = z[i] - step;
      moved = fmaxq(moved, fabsq(step.re) + fabsq(step.im));
    }
    if (moved < Q("1e-30") * scale) break;
  }
  bool found = false;
  for (auto& zi : z) {
    if (fabsq(zi.im) > Q("1e-20") * scale) continue;
    real x = zi.re;
    for (int k = 0; k < 3; ++k) {  // Newton on the real polynomial
      real p = 1, dp = 0;
      for (int j = 3; j >= 0; --j) {
        dp = dp * x + p;
        p = p * x + c[j];
      }
      if (dp == 0) break;
      x -= p / dp;
    }
    if (x > smin && (!found || x < root)) {
      root = x;
      found = true;
    }
  }
  return found;
}

// The quartic of the torus (R, r) at the origin along o + s d (|d| = 1, o
// the foot of the perpendicular): alpha = s^2 + 2 b s + c0 with b = o.d,
// c0 = |o|^2 + R^2 - r^2; F = alpha^2 - 4 R^2 ((ox + s dx)^2 + (oz + s dz)^2).
void torus_quartic(real R, real r, const Vec& o, const Vec& d, real c[4]) {
  real b = o.x * d.x + o.y * d.y + o.z * d.z;
  real c0 = o.x * o.x + o.y * o.y + o.z * o.z + R * R - r * r;
  real k = 4 * R * R;
  c[3] = 4 * b;
  c[2] = 4 * b * b + 2 * c0 - k * (d.x * d.x + d.z * d.z);
  c[1] = 4 * b * c0 - 2 * k * (o.x * d.x + o.z * d.z);
  c[0] = c0 * c0 - k * (o.x * o.x + o.z * o.z);
}

TEST(ExactTorus, AgreesWithDurandKernerOnTheQuartic) {
  struct Case {
    double R, r;
  };
  for (Case tc : {Case{1, 0.25}, Case{2, 0.05}, Case{1, 0.9}}) {
    json j = {{"type", "torus"}, {"major_radius", tc.R}, {"minor_radius", tc.r}};
    ExactObject torus(j);
    real R = tc.R, r = tc.r;
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI), unit(-1, 1);
    int checked = 0, hits = 0;
    for (int i = 0; i < 3000; ++i) {
      ExactRay ray_;
      if (i < 1000) {
        ray_ = random_rays(1, {0, 0, 0}, static_cast<double>(R + r), static_cast<unsigned>(i))[0];
      } else {
        // Near-tangent: through a surface point P, along a tangent direction,
        // moved off the surface along the normal by +-1e-10 r.
        real th = angle(rng), ph = angle(rng);
        Vec n{cosq(ph) * cosq(th), sinq(ph), cosq(ph) * sinq(th)};
        Vec p{(R + r * cosq(ph)) * cosq(th), r * sinq(ph), (R + r * cosq(ph)) * sinq(th)};
        Vec a{unit(rng), unit(rng), unit(rng)};
        real an = a.x * n.x + a.y * n.y + a.z * n.z;
        Vec d{a.x - an * n.x, a.y - an * n.y, a.z - an * n.z};
        real dn = sqrtq(d.x * d.x + d.y * d.y + d.z * d.z);
        d = {d.x / dn, d.y / dn, d.z / dn};
        real off = (i % 2 ? 1 : -1) * Q("1e-10") * r, back = 3 * (R + r);
        ray_.origin = {p.x + off * n.x - back * d.x, p.y + off * n.y - back * d.y, p.z + off * n.z - back * d.z};
        ray_.dir = d;
      }
      const Vec& o = ray_.origin;
      const Vec& d = ray_.dir;
      real t0 = -(o.x * d.x + o.y * d.y + o.z * d.z);
      Vec foot{o.x + t0 * d.x, o.y + t0 * d.y, o.z + t0 * d.z};
      real c[4];
      torus_quartic(R, r, foot, d, c);
      real s = 0;
      bool expected = quartic_first_root(c, R + r, ray_.tmin - t0, s);
      ExactHit h = torus.intersect(ray_);
      ASSERT_EQ(h.hit, expected) << "R " << tc.R << " r " << tc.r << " ray " << i << " quartic root "
                                 << (expected ? str(t0 + s) : "none") << " oracle " << (h.hit ? str(h.t) : "miss");
      ++checked;
      if (!h.hit) continue;
      ++hits;
            SCOPED_TRACE("ray " + std::to_string(i) + " R " + std::to_string(tc.R) + " g(oracle) " +
                   str(torus.distance_to_surface({o.x + h.t * d.x, o.y + h.t * d.y, o.z + h.t * d.z})) +
                   " g(quartic) " +
                   str(torus.distance_to_surface({o.x + (t0 + s) * d.x, o.y + (t0 + s) * d.y, o.z + (t0 + s) * d.z})));
      // Random rays: both to ~1e-30. Near-tangent ones cross at a slope
      // ~1e-5..1e-6, where the expanded quartic (thin tube: terms of R^4
      // against values of r^2 R^2) is the less accurate of the two.
      EXPECT_Q(h.t, t0 + s, i < 1000 ? Q("1e-28") : Q("1e-24"));
    }
    EXPECT_GT(hits, 600);
    EXPECT_EQ(checked, 3000);
  }
}

// ------------------------------------------------------------------ ring

const char* kRing = R"({"type": "ring", "inner_radius": 0.5, "outer_radius": 1})";

TEST(ExactRing, BothSidesSameNormal) {
  auto r = object(kRing);
  expect_hit(r.intersect(ray(0.75, 2, 0, 0, -1, 0)), 2, 0, 1, 0);
  expect_hit(r.intersect(ray(0.75, -2, 0, 0, 1, 0)), 2, 0, 1, 0);
  EXPECT_Q(r.size(), 1, 0);
}

TEST(ExactRing, RadiusBoundariesAreInclusive) {
  auto r = object(kRing);
  real e = Q("1e-20");
  expect_hit(r.intersect(ray(0.5, 1, 0, 0, -1, 0)), 1, 0, 1, 0);
  expect_miss(r.intersect(ray(0.5 - e, 1, 0, 0, -1, 0)));
  expect_hit(r.intersect(ray(0.5 + e, 1, 0, 0, -1, 0)), 1, 0, 1, 0);
  expect_hit(r.intersect(ray(0, 1, -1, 0, -1, 0)), 1, 0, 1, 0);
  expect_miss(r.intersect(ray(0, 1, -1 - e, 0, -1, 0)));
  expect_miss(r.intersect(ray(0, 1, 0, 0, -1, 0)));  // the hole
  // inner_radius defaults to 0: a full disk.
  expect_hit(object(R"({"type": "ring", "outer_radius": 1})").intersect(ray(0, 1, 0, 0, -1, 0)), 1, 0, 1, 0);
}

TEST(ExactRing, ParallelRaysMiss) {
  auto r = object(kRing);
  expect_miss(r.intersect(ray(0.75, 0, -5, 0, 0, 1)));  // in the plane: zero thickness
  expect_miss(r.intersect(ray(0.75, 1, -5, 0, 0, 1)));
}

TEST(ExactRing, RotatedSixtyDegrees) {
  // 60 deg about z: N = R (0,1,0) = (-sin 60, cos 60, 0) = (-sqrt3/2, 1/2, 0).
  // The disk passes through the centre, so the ray down the y axis hits at 0.
  auto r = object(R"({"type": "ring", "outer_radius": 10, "rotation": {"axis": [0, 0, 1], "degrees": 60}})");
  expect_hit(r.intersect(ray(0, 2, 0, 0, -1, 0)), 2, -qsqrt(3) / 2, 0.5, 0, Q("1e-32"), Q("1e-33"));
}

TEST(ExactRing, DistanceToSurface) {
  auto r = object(kRing);
  EXPECT_Q(r.distance_to_surface({0.75, Q("1e-6"), 0}), Q("1e-6"), Q("1e-38"));
  // Beyond the outer edge by 3e-6 and 4e-6 above: 5e-6.
  EXPECT_Q(r.distance_to_surface({1 + Q("3e-6"), Q("4e-6"), 0}), Q("5e-6"), Q("1e-32"));
}

// ------------------------------------------------------------------ quadric

TEST(ExactQuadric, LinearWhenTheQuadraticPartVanishes) {
  // f = y - 2: a plane; N = grad f = +y from both sides.
  auto q = object(R"({"type": "quadric", "coefficients": [0,0,0,0,0,0,0,1,0,-2]})");
  expect_hit(q.intersect(ray(0, 0, 0, 0, 1, 0)), 2, 0, 1, 0);
  expect_hit(q.intersect(ray(0, 5, 0, 0, -1, 0)), 3, 0, 1, 0);
  expect_miss(q.intersect(ray(0, 0, 0, 1, 0, 0)));
}

TEST(ExactQuadric, LinearAlongTheParaboloidAxis) {
  // f = x^2 - y; along +y the t^2 coefficient is exactly 0: from (0.5,-5,0),
  // y = 0.25 at t = 5.25; N = (2x, -1, 0) = (1, -1, 0)/sqrt2.
  auto q = object(R"({"type": "quadric", "coefficients": [1,0,0,0,0,0,0,-1,0,0]})");
  real k = 1 / qsqrt(2);
  expect_hit(q.intersect(ray(0.5, -5, 0, 0, 1, 0)), 5.25, k, -k, 0, Q("1e-32"));
}

TEST(ExactQuadric, ClippingChoosesTheFarRoot) {
  // The unit sphere as a quadric, from (0,0,-5) along +z: roots z = -1, +1.
  const char* base = R"({"type": "quadric", "coefficients": [1,1,1,0,0,0,0,0,0,-1])";
  auto make = [&](const std::string& clip) { return ExactObject(json::parse(std::string(base) + clip + "}")); };
  expect_hit(make("").intersect(ray(0, 0, -5, 0, 0, 1)), 4, 0, 0, -1);
  expect_hit(make(R"(, "clip_max": [null, null, 0])").intersect(ray(0, 0, -5, 0, 0, 1)), 4, 0, 0, -1);
  expect_hit(make(R"(, "clip_min": [null, null, 0])").intersect(ray(0, 0, -5, 0, 0, 1)), 6, 0, 0, 1);
  expect_miss(make(R"(, "clip_min": [null, null, 2])").intersect(ray(0, 0, -5, 0, 0, 1)));
  expect_miss(make(R"(, "clip_min": [-1, -1, -0.5], "clip_max": [1, 1, 0.5])").intersect(ray(0, 0, -5, 0, 0, 1)));
  EXPECT_Q(make(R"(, "clip_min": [-1, -1, -2], "clip_max": [1, 1.5, 0.5])").size(), 2, 0);
  EXPECT_Q(make(R"(, "clip_min": [-1, -1, -2])").size(), 1, 0);
}

TEST(ExactQuadric, NegatedCoefficientsFlipTheNormal) {
  auto q = object(R"({"type": "quadric", "coefficients": [-1,-1,-1,0,0,0,0,0,0,1]})");
  expect_hit(q.intersect(ray(0, 0, -5, 0, 0, 1)), 4, 0, 0, 1);
}

TEST(ExactQuadric, ZeroGradientUsesMinusDir) {
  // The double cone x^2 - y^2 + z^2 = 0: along its axis only the apex (a
  // double root at t = 5), where grad f = 0: N = -dir.
  auto q = object(R"({"type": "quadric", "coefficients": [1,-1,1,0,0,0,0,0,0,0]})");
  expect_hit(q.intersect(ray(0, -5, 0, 0, 1, 0)), 5, 0, -1, 0);
}

TEST(ExactQuadric, RayInsideAnInfiniteTubeAlongItsAxisMisses) {
  // x^2 + z^2 = 1 along y: a = b = 0, c = -1: no root.
  auto q = object(R"({"type": "quadric", "coefficients": [1,0,1,0,0,0,0,0,0,-1]})");
  expect_miss(q.intersect(ray(0, 0, 0, 0, 1, 0)));
  EXPECT_Q(q.size(), 1, 0);
  // Distance, first order: f = 2.25 - 1 at (1.5, 0, 0), |grad| = 3: 1.25/3.
  EXPECT_Q(q.distance_to_surface({1.5, 0, 0}), Q("1.25") / 3, Q("1e-33"));
}

// ------------------------------------------------------------------ cylinder, cone

TEST(ExactCylinder, HandValues) {
  auto c = object(R"({"type": "cylinder", "radius": 1, "height": 2})");
  expect_hit(c.intersect(ray(-5, 1, 0, 1, 0, 0)), 4, -1, 0, 0);
  expect_hit(c.intersect(ray(0, 1, 0, 1, 0, 0)), 1, 1, 0, 0);  // from inside: the outward normal
  expect_miss(c.intersect(ray(-5, 3, 0, 1, 0, 0)));           // above the clip
  expect_miss(c.intersect(ray(0, 5, 0, 0, -1, 0)));           // down the open tube
  // Into the top opening from (0, 2.5, 0) along (1,-1,0): the wall x = 1 at
  // y = 1.5, t = sqrt2; seen from inside, N = +x.
  expect_hit(c.intersect(ray(0, 2.5, 0, 1, -1, 0)), qsqrt(2), 1, 0, 0, Q("1e-32"));
  EXPECT_Q(c.size(), 2, 0);
}

TEST(ExactCone, HandValues) {
  // radius 1, height 1: x^2 - y^2 + z^2 = 0; at y = 0.5 the radius is 0.5.
  auto c = object(R"({"type": "cone", "radius": 1, "height": 1})");
  real k = 1 / qsqrt(2);
  expect_hit(c.intersect(ray(-5, 0.5, 0, 1, 0, 0)), 4.5, -k, -k, 0, Q("1e-32"));
  expect_hit(c.intersect(ray(-5, 0.5, 0, 1, 0, 0, 4.5)), 5.5, k, -k, 0, Q("1e-32"));
  expect_miss(c.intersect(ray(-5, -0.5, 0, 1, 0, 0)));  // the lower nappe is clipped away
}

void expect_same(const ExactObject& a, const ExactObject& b, const ExactRay& r) {
  ExactHit ha = a.intersect(r), hb = b.intersect(r);
  ASSERT_EQ(ha.hit, hb.hit);
  if (!ha.hit) return;
  real tol = Q("1e-30");
  EXPECT_Q(ha.t, hb.t, tol);
  EXPECT_Q(ha.normal.x, hb.normal.x, tol);
  EXPECT_Q(ha.normal.y, hb.normal.y, tol);
  EXPECT_Q(ha.normal.z, hb.normal.z, tol);
}

TEST(ExactCylinder, SameAsTheQuadricItStandsFor) {
  const char* place = R"("center": [0.5, -1, 2], "rotation": {"axis": [1, 2, 3], "degrees": 37})";
  auto cyl = ExactObject(json::parse(std::string(R"({"type": "cylinder", "radius": 0.5, "height": 2, )") + place + "}"));
  auto quad = ExactObject(json::parse(std::string(R"({"type": "quadric", "coefficients": [1,0,1,0,0,0,0,0,0,-0.25],
      "clip_min": [null, 0, null], "clip_max": [null, 2, null], )") + place + "}"));
  int hits = 0;
  for (const auto& r : random_rays(1000, {0.5, -1, 2}, 2, 7)) {
    expect_same(cyl, quad, r);
    hits += cyl.intersect(r).hit;
  }
  EXPECT_GT(hits, 100);
}

TEST(ExactCone, SameAsTheQuadricItStandsFor) {
  // radius 1, height 2: -(1/2)^2 = -0.25 exactly.
  const char* place = R"("center": [-1, 0, 1], "rotation": {"quaternion": [1, 0.2, -0.3, 0.4]})";
  auto cone = ExactObject(json::parse(std::string(R"({"type": "cone", "radius": 1, "height": 2, )") + place + "}"));
  auto quad = ExactObject(json::parse(std::string(R"({"type": "quadric", "coefficients": [1,-0.25,1,0,0,0,0,0,0,0],
      "clip_min": [null, 0, null], "clip_max": [null, 2, null], )") + place + "}"));
  int hits = 0;
  for (const auto& r : random_rays(1000, {-1, 0, 1}, 2, 8)) {
    expect_same(cone, quad, r);
    hits += cone.intersect(r).hit;
  }
  EXPECT_GT(hits, 100);
}

// ------------------------------------------------------------------ rotation

TEST(ExactRotation, NinetyAboutYMapsXToMinusZ) {
  // A box long in local x (half 3): rotated 90 deg about y, local +x is world
  // -z, so from (0,0,-10) along +z the face at world z = -3 (t = 7) is local
  // +x: N = R (1,0,0) = (0,0,-1). Along +x the extent is 1: t = 9, N = -x.
  const char* rotations[] = {
      R"({"axis": [0, 1, 0], "degrees": 90})",
      R"({"axis": [0, 5, 0], "degrees": 450})",
      R"({"axis": [0, 1, 0], "degrees": -270})",
      R"({"axis": [0, -1, 0], "degrees": -90})",
      R"({"quaternion": [0.7071067811865476, 0, 0.7071067811865476, 0]})",
      R"({"quaternion": [2, 0, 2, 0]})",
      R"({"quaternion": [-1, 0, -1, 0]})",
  };
  for (const char* rot : rotations) {
    SCOPED_TRACE(rot);
    json j = json::parse(R"({"type": "box", "half_size": [3, 1, 1]})");
    j["rotation"] = json::parse(rot);
    ExactObject b(j);
    expect_hit(b.intersect(ray(0, 0, -10, 0, 0, 1)), 7, 0, 0, -1, Q("1e-31"), Q("1e-32"));
    expect_hit(b.intersect(ray(-10, 0, 0, 1, 0, 0)), 9, -1, 0, 0, Q("1e-31"), Q("1e-32"));
  }
}

TEST(ExactRotation, ThirtyDegreesAboutZ) {
  // A box half (2, 0.5, 0.5) turned 30 deg about z: its +x face normal is
  // (cos30, sin30, 0). From 10 * that direction back towards the centre: the
  // face at distance 2, t = 8.
  auto b = object(R"({"type": "box", "half_size": [2, 0.5, 0.5], "rotation": {"axis": [0, 0, 1], "degrees": 30}})");
  real c = qsqrt(3) / 2, s = 0.5;
  expect_hit(b.intersect(ray(10 * c, 10 * s, 0, -c, -s, 0)), 8, c, s, 0, Q("1e-31"), Q("1e-32"));
}

// ------------------------------------------------------------------ scene, helpers, validation

TEST(ExactScene, ClosestHitTiesGoToTheLowerIndex) {
  std::vector<ExactObject> objects = {
      object(R"({"type": "sphere", "center": [0, 0, 5], "radius": 1})"),
      object(kUnitSphere),
      object(kUnitSphere),
  };
  ExactSceneHit h = closest_hit(objects, ray(0, 0, -5, 0, 0, 1));
  EXPECT_EQ(h.object, 1);
  EXPECT_Q(h.t, 4, 0);
  EXPECT_Q(h.normal.z, -1, 0);
  h = closest_hit(objects, ray(0, 0, -5, 0, 0, 1, 6));  // past both unit spheres: the one at z = 5
  EXPECT_EQ(h.object, 0);
  EXPECT_Q(h.t, 9, 0);
  EXPECT_EQ(closest_hit(objects, ray(0, 5, -5, 0, 0, 1)).object, -1);
}

TEST(ExactHelpers, MakeRayNormalisesInQuad) {
  const double o[3] = {1, 2, 3}, d[3] = {0, 0, 2}, d2[3] = {1, 1, 0}, zero[3] = {0, 0, 0};
  ExactRay r = make_ray(o, d, 0.5);
  EXPECT_Q(r.dir.z, 1, 0);
  EXPECT_Q(r.tmin, 0.5, 0);
  EXPECT_Q(r.origin.y, 2, 0);
  r = make_ray(o, d2, 0);
  EXPECT_Q(r.dir.x, 1 / qsqrt(2), Q("1e-34"));
  EXPECT_Q(r.dir.x * r.dir.x + r.dir.y * r.dir.y, 1, Q("1e-33"));
  EXPECT_THROW(make_ray(o, zero, 0), std::invalid_argument);
}

TEST(ExactHelpers, ToString) {
  EXPECT_EQ(to_string(1.5, 5), "1.5");
  EXPECT_EQ(to_string(real(1) / 3, 30), "0.333333333333333333333333333333");
  EXPECT_EQ(to_string(1 - Q("1e-30"), 32), "0.999999999999999999999999999999");  // %Qg drops trailing zeros
  EXPECT_EQ(to_string(1 - Q("1e-30"), 20), "1");
  EXPECT_EQ(to_string(Q("1e-20")), "1e-20");
}

TEST(ExactValidation, RejectsWhatItDoesNotKnow) {
  EXPECT_THROW(object(R"({"type": "teapot"})"), std::invalid_argument);
  EXPECT_THROW(object(R"({"type": "sphere", "radius": 1, "radiuss": 2})"), std::invalid_argument);
  EXPECT_THROW(object(R"({"type": "sphere"})"), std::invalid_argument);
  EXPECT_THROW(object(R"({"type": "torus", "major_radius": 1, "minor_radius": 2})"), std::invalid_argument);
  EXPECT_THROW(object(R"({"type": "box", "half_size": [1, 1]})"), std::invalid_argument);
  EXPECT_THROW(object(R"({"type": "sphere", "radius": 1, "rotation": {"axis": [0,0,0], "degrees": 1}})"),
               std::invalid_argument);
  EXPECT_THROW(object(R"({"type": "quadric", "coefficients": [0,0,0,0,0,0,0,0,0,1]})"), std::invalid_argument);
  EXPECT_NO_THROW(object(R"({"type": "sphere", "radius": 1, "material": "red", "center": [1, 2, 3]})"));
}

// ------------------------------------------------------------------ sweep

struct SweepCase {
  const char* name;
  const char* json;
  bool closed;  // every ray from outside crosses an even number of times
};

const SweepCase kSweep[] = {
    {"sphere", R"({"type": "sphere", "center": [1, -2, 0.5], "radius": 1.5})", true},
    {"plane", R"({"type": "plane", "point": [1, 2, 3], "normal": [1, -1, 0.5]})", false},
    {"box", R"({"type": "box", "center": [0.3, 0.1, -0.2], "half_size": [1, 0.5, 2],
                "rotation": {"axis": [1, 2, 3], "degrees": 37}})", true},
    {"torus", R"({"type": "torus", "center": [0.2, 0, -0.1], "major_radius": 1, "minor_radius": 0.25,
                  "rotation": {"axis": [1, 0, 1], "degrees": 20}})", true},
    {"torus_thin", R"({"type": "torus", "major_radius": 2, "minor_radius": 0.05,
                       "rotation": {"quaternion": [0.9, 0.1, 0.3, -0.2]}})", true},
    {"torus_fat", R"({"type": "torus", "major_radius": 1, "minor_radius": 0.9})", true},
    {"ring", R"({"type": "ring", "center": [0, 1, 0], "inner_radius": 0.3, "outer_radius": 1.2,
                 "rotation": {"axis": [1, 0, 0], "degrees": 30}})", false},
    {"quadric", R"({"type": "quadric", "coefficients": [1, -1, 1, 0.2, 0, 0.1, 0, 0.3, 0, -0.5],
                    "clip_min": [-2, -2, -2], "clip_max": [2, 2, 2],
                    "rotation": {"axis": [0, 1, 1], "degrees": 50}})", false},
    {"cylinder", R"({"type": "cylinder", "center": [0, -1, 0], "radius": 0.7, "height": 2,
                     "rotation": {"axis": [1, 0, 0], "degrees": 15}})", false},
    {"cone", R"({"type": "cone", "center": [0, -1, 0], "radius": 1, "height": 2,
                 "rotation": {"axis": [0, 0, 1], "degrees": 25}})", false},
};

class ExactSweep : public ::testing::TestWithParam<SweepCase> {};

TEST_P(ExactSweep, ResidualShiftInvarianceAndParity) {
  const SweepCase& c = GetParam();
  ExactObject obj(json::parse(c.json));
  real size = obj.size();
  json j = json::parse(c.json);
  Vec centre{0, 0, 0};
  for (const char* key : {"center", "point"})
    if (j.contains(key)) centre = {j[key][0].get<double>(), j[key][1].get<double>(), j[key][2].get<double>()};
  double span = static_cast<double>(size);
  if (std::string(c.name) == "quadric") span = 2;

  const int kRays = 10000;
  auto rays = random_rays(kRays, centre, span, 12345);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> shift(0.1, 1.0);

  int hits = 0;
  real worst_residual = 0, worst_shift = 0, worst_normal = 0;
  auto start = std::chrono::steady_clock::now();
  std::vector<ExactHit> first(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) first[i] = obj.intersect(rays[i]);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (std::size_t i = 0; i < rays.size(); ++i) {
    const ExactRay& r = rays[i];
    const ExactHit& h = first[i];
    // Moved forward along the ray by delta (still outside: |o - c| = 3 size).
    real delta = static_cast<real>(shift(rng) * 1e-3) * size;
    ExactRay moved = r;
    moved.origin = {r.origin.x + delta * r.dir.x, r.origin.y + delta * r.dir.y, r.origin.z + delta * r.dir.z};
    ExactHit h2 = obj.intersect(moved);
    ASSERT_EQ(h.hit, h2.hit) << c.name << " ray " << i;
    if (!h.hit) continue;
    ++hits;
    Vec p{r.origin.x + h.t * r.dir.x, r.origin.y + h.t * r.dir.y, r.origin.z + h.t * r.dir.z};
    real res = obj.distance_to_surface(p) / size;
    worst_residual = fmaxq(worst_residual, res);
    ASSERT_LT(res, Q("1e-25")) << c.name << " ray " << i << " t = " << str(h.t);
    real ds = fabsq(h2.t - (h.t - delta)) / size;
    worst_shift = fmaxq(worst_shift, ds);
    ASSERT_LT(ds, Q("1e-27")) << c.name << " ray " << i << " t = " << str(h.t) << " t2 = " << str(h2.t);
    real dn = fmaxq(fabsq(h2.normal.x - h.normal.x), fmaxq(fabsq(h2.normal.y - h.normal.y), fabsq(h2.normal.z - h.normal.z)));
    worst_normal = fmaxq(worst_normal, dn);
    ASSERT_LT(dn, Q("1e-25")) << c.name << " ray " << i;
    ASSERT_GT(h.t, 0);
    real nn = h.normal.x * h.normal.x + h.normal.y * h.normal.y + h.normal.z * h.normal.z;
    ASSERT_LT(fabsq(nn - 1), Q("1e-32"));

    if (c.closed) {
      // Every crossing, one after another: an even count (rays from outside
      // end outside; tangent touches have measure zero).
      int crossings = 1;
      ExactRay next = r;
      next.tmin = h.t + Q("1e-15") * size;
      for (ExactHit k = obj.intersect(next); k.hit && crossings < 10; k = obj.intersect(next)) {
        ++crossings;
        ASSERT_LT(obj.distance_to_surface({r.origin.x + k.t * r.dir.x, r.origin.y + k.t * r.dir.y,
                                           r.origin.z + k.t * r.dir.z}) / size, Q("1e-25"));
        next.tmin = k.t + Q("1e-15") * size;
      }
      ASSERT_EQ(crossings % 2, 0) << c.name << " ray " << i << " crossings " << crossings;
    }
  }
  EXPECT_GT(hits, kRays / 20) << c.name;
  std::printf("[ sweep    ] %-10s %5d/%d hits, %9.0f rays/s, worst |f|/|grad f| / size %s, shift %s, normal %s\n",
              c.name, hits, kRays, kRays / seconds, to_string(worst_residual, 3).c_str(),
              to_string(worst_shift, 3).c_str(), to_string(worst_normal, 3).c_str());
}

INSTANTIATE_TEST_SUITE_P(Primitives, ExactSweep, ::testing::ValuesIn(kSweep),
                         [](const ::testing::TestParamInfo<SweepCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace prism::stability
