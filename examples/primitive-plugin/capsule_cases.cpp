// The capsule's test cases, found by Prism's suites when the capsule is
// built inside a Prism tree (its stability oracle and stiff families, its
// trace-agreement, uv and benchmark objects, random objects for the Embree
// backend's tests): see Prism's
// tests/cases/primitive_cases.hpp. A build against the installed package
// (this folder's CMakeLists.txt) does not use this file.
//
// The oracle, in quad precision and independent of capsule.cpp: the capsule
// is the union of a tube clipped to 0 <= y <= height and two balls; it is
// convex, so a line meets it in one interval, from the smallest entry to the
// largest exit over the three pieces. The first end with t > tmin is the
// hit, polished by Newton on the signed distance to the axis segment minus
// radius.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

// Where the line o + s d is inside one convex piece: s in [lo, hi].
struct Span {
  bool hit = false;
  real lo = 0, hi = 0;
};

Span ball_span(const Vec& o, const Vec& d, real centre_y, real radius) {
  const Vec g = o - Vec{0, centre_y, 0};
  const real b = dot(g, d);  // |d| = 1
  const Vec perp = g - b * d;
  const real disc = radius * radius - dot(perp, perp);
  if (disc < 0) return {};
  const real q = sqrtq(disc);
  return {true, -b - q, -b + q};
}

Span tube_span(const Vec& o, const Vec& d, real radius, real height) {
  Span slab{true, -kInf, kInf};
  if (d.y == 0) {
    if (!(o.y >= 0 && o.y <= height)) return {};
  } else {
    const real a = -o.y / d.y, b = (height - o.y) / d.y;
    slab = {true, qmin(a, b), qmax(a, b)};
  }
  const real a = d.x * d.x + d.z * d.z;
  if (a == 0) return o.x * o.x + o.z * o.z <= radius * radius ? slab : Span{};
  const real foot = -(o.x * d.x + o.z * d.z) / a;
  const real mx = o.x + foot * d.x, mz = o.z + foot * d.z;
  const real disc = (radius * radius - (mx * mx + mz * mz)) / a;
  if (disc < 0) return {};
  const real q = sqrtq(disc);
  const real lo = qmax(foot - q, slab.lo), hi = qmin(foot + q, slab.hi);
  if (!(lo <= hi)) return {};
  return {true, lo, hi};
}

// The nearest point of the axis segment to p.
Vec axis_point(const Vec& p, real height) { return {0, qmin(qmax(p.y, 0), height), 0}; }

real signed_distance(const Vec& p, real radius, real height) { return norm(p - axis_point(p, height)) - radius; }

// Newton on the signed distance along the ray, kept while |f| decreases.
real polish(const Vec& o, const Vec& d, real s, real radius, real height) {
  real f = signed_distance(o + s * d, radius, height);
  for (int it = 0; it < 3 && f != 0; ++it) {
    const Vec p = o + s * d;
    const Vec away = p - axis_point(p, height);
    const real len = norm(away);
    if (len == 0) break;
    const real slope = dot(away, d) / len;
    if (slope == 0) break;
    const real s2 = s - f / slope, f2 = signed_distance(o + s2 * d, radius, height);
    if (!(qabs(f2) < qabs(f))) break;
    s = s2;
    f = f2;
  }
  return s;
}

LocalHit capsule_hit(real radius, real height, const Vec& o_local, const Vec& d, real tmin) {
  const Recentred r = recentre(o_local, d);
  Span all;
  for (const Span& piece : {ball_span(r.o, d, 0, radius), ball_span(r.o, d, height, radius),
                            tube_span(r.o, d, radius, height)}) {
    if (!piece.hit) continue;
    all = all.hit ? Span{true, qmin(all.lo, piece.lo), qmax(all.hi, piece.hi)} : piece;
  }
  if (!all.hit) return {};
  for (real s : {all.lo, all.hi}) {
    if (!(r.t0 + s > tmin)) continue;
    s = polish(r.o, d, s, radius, height);
    if (!(r.t0 + s > tmin)) continue;
    const Vec p = r.o + s * d;
    LocalHit h;
    h.hit = true;
    h.t = r.t0 + s;
    h.n = p - axis_point(p, height);
    return h;
  }
  return {};
}

OracleShape capsule_oracle(ObjectFields& fields) {
  const real radius = fields.number("radius"), height = fields.number("height");
  if (!(radius > 0)) ObjectFields::fail("radius", "must be > 0");
  if (!(height > 0)) ObjectFields::fail("height", "must be > 0");
  OracleShape shape;
  shape.hit = [radius, height](const Vec& o, const Vec& d, real tmin) {
    return capsule_hit(radius, height, o, d, tmin);
  };
  shape.distance = [radius, height](const Vec& p) { return qabs(signed_distance(p, radius, height)); };
  shape.size = qmax(radius, height);
  return shape;
}

// ---------------------------------------------------------------- stiff families

// A capsule of radius s/2 and height s, its surface sampled by area.
void make_shape(Shape& shape, double s) {
  const double r = 0.5 * s, h = s;
  shape.object = placed({{"type", "capsule"}, {"radius", r}, {"height", h}}, shape.center, shape.rot);
  shape.mid = {0, h / 2, 0};
  shape.size = r + h / 2;
  shape.sample = [r, h](Rng& rng) {
    const double tube = 2 * kPi * r * h, caps = 4 * kPi * r * r;
    if (rng.range(0, tube + caps) < tube) {
      const double phi = rng.range(0, 2 * kPi), y = rng.range(0, h);
      return SurfacePoint{{r * std::cos(phi), y, r * std::sin(phi)}, {std::cos(phi), 0, std::sin(phi)}};
    }
    const V u = rng.unit();
    const double centre_y = u.y < 0 ? 0 : h;
    return SurfacePoint{{r * u.x, centre_y + r * u.y, r * u.z}, u};
  };
}

void add_capsule(Builder& b) {
  // Aim points on the tube eta * height beside a seam (where the tube meets
  // a cap: y = 0 and y = height), from directions that see the point.
  b.add("capsule", "seam", "rays aimed at the seams of tube and caps, eta * height off them (rotated)",
        {"eta", {1e-2, 1e-4, 1e-6, 1e-8, 0}, 0}, [](double eta, int n, Rng& rng) {
          Case c;
          const double r = 1, h = 2;
          c.objects =
              nlohmann::json::array({placed({{"type", "capsule"}, {"radius", r}, {"height", h}}, kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) c.rays.push_back(ray_beside_tube_end(rng, i, r, h, eta));
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_capsule_cases() {
  PrimitiveCases c;
  c.type = "capsule";
  c.oracle = capsule_oracle;
  c.shape = make_shape;
  c.families = add_capsule;
  c.agreement.push_back(
      {"capsule", R"({"type": "capsule", "center": [1, 2, 3], "radius": 0.5, "height": 1.2})", 1.1});
  // radius 1, height 2, seen from below: p = (0, -1, 0), the bottom pole.
  // u = 0.5 + atan2(0, 0)/2pi = 0.5, v = 0; uv' = (0.625, 0.125) -> texel
  // (2, 0) = (0.375, 0.125, 0.125).
  c.uv.push_back({"CapsuleBottomPoleUv",
                  R"({"position": [0, -5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1]})",
                  R"(, "uv_offset": [0.125, 0.125])",
                  R"({"type": "capsule", "radius": 1, "height": 2, "material": "m"})",
                  {0.375, 0.125, 0.125}});
  // radius 0.5, height 1: hits aim inside the solid (within 0.45 of the axis segment).
  c.bench.push_back({{{"radius", {0.5}}, {"height", {1.0}}},
                     [](BenchRng& r) { return glm::dvec3(0, 0.5, 0) + prism::cases::bench_origins(4.0)(r); },
                     [](BenchRng& r) { return glm::dvec3(0, r.uniform(0, 1), 0) + r.in_ball(0.45); },
                     {}});
  // Random scenes: radius s = scale * [0.1, 0.75), height 2 s.
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = 0.5 * random_size(rng, at);
    return random_framed_object(rng, at, "capsule", "\"radius\": " + num(s) + ", \"height\": " + num(2 * s));
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_capsule_cases)
