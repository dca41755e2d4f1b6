// The ring primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: a flat annulus in quad precision; inner
// radii; agreement, uv and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

LocalHit ring_hit(real inner, real outer, const Vec& o_local, const Vec& d, real tmin) {
  if (d.y == 0) return {};  // parallel (or in the plane: zero thickness)
  Recentred r = recentre(o_local, d);
  real s = -r.o.y / d.y;
  real t = r.t0 + s;
  if (!(t > tmin)) return {};
  Vec p = r.o + s * d;
  real rho2 = p.x * p.x + p.z * p.z;
  if (rho2 < inner * inner || rho2 > outer * outer) return {};
  LocalHit h;
  h.hit = true;
  h.t = t;
  h.n = {0, 1, 0};
  return h;
}

OracleShape ring_oracle(ObjectFields& fields) {
  const real inner = fields.number("inner_radius", 0), outer = fields.number("outer_radius");
  if (!(inner >= 0)) ObjectFields::fail("inner_radius", "must be >= 0");
  if (!(outer > inner)) ObjectFields::fail("outer_radius", "must be > inner_radius");
  OracleShape shape;
  shape.hit = [inner, outer](const Vec& o, const Vec& d, real tmin) { return ring_hit(inner, outer, o, d, tmin); };
  shape.distance = [inner, outer](const Vec& p) {
    real rho = sqrtq(p.x * p.x + p.z * p.z);
    real e = rho < inner ? inner - rho : (rho > outer ? rho - outer : 0);
    return sqrtq(e * e + p.y * p.y);
  };
  shape.size = outer;
  return shape;
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  const double outer = s, inner = 0.4 * s;
  shape.object = placed({{"type", "ring"}, {"inner_radius", inner}, {"outer_radius", outer}}, center, rot);
  shape.size = outer;
  shape.sample = [inner, outer](Rng& rng) {
    const double lo = 1.01 * inner, hi = 0.99 * outer;
    const double r = std::sqrt(rng.range(lo * lo, hi * hi)), phi = rng.range(0, 2 * kPi);
    return SurfacePoint{{r * std::cos(phi), 0, r * std::sin(phi)}, {0, rng.sign(), 0}};
  };
}

void add_ring(Builder& b) {
  // Aim points at inner (1 ± eta): outside the hole they hit, inside they miss.
  b.add("ring", "inner", "rays aimed at inner_radius * (1 ± eta), from either side (rotated ring)",
        {"eta", {1e-2, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10}, 1e-5}, [](double eta, int n, Rng& rng) {
          Case c;
          const double inner = 0.5, outer = 1;
          const V center{0.25, 1.5, -0.75};
          c.objects = nlohmann::json::array(
              {placed({{"type", "ring"}, {"inner_radius", inner}, {"outer_radius", outer}}, center, kTilted)});
          for (int i = 0; i < n; ++i) {
            const double rho = inner * (1 + (i % 2 ? eta : -eta)), phi = rng.range(0, 2 * kPi);
            const V P = center + kTilted.apply({rho * std::cos(phi), 0, rho * std::sin(phi)});
            const V N = rng.sign() * normalize(kTilted.apply({0, 1, 0}));
            c.rays.push_back(ray_to(P, rng.cone(-N, 0.1, 1), rng.range(1, 4)));
          }
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_ring_cases() {
  PrimitiveCases c;
  c.type = "ring";
  c.oracle = ring_oracle;
  c.shape = make_shape;
  c.families = add_ring;
  c.agreement.push_back({"ring",
                         R"({"type": "ring", "center": [1, 2, 3], "inner_radius": 0.4, "outer_radius": 1.2})", 1.2});
  // inner 1, outer 2. From above at (0, 5, 1.625): p = (0, 0, 1.625).
  // u = (1.625 - 1)/(2 - 1) = 0.625; v = 0.5 + atan2(1.625, 0)/2pi = 0.75.
  // uv' = (0.625, 0.875) -> texel (2, 3) = (0.375, 0.5, 0.875).
  c.uv.push_back({"RingUv",
                  R"({"position": [0, 5, 1.625], "look_at": [0, 0, 1.625], "up": [0, 0, -1]})",
                  R"(, "uv_offset": [0, 0.125])",
                  R"({"type": "ring", "inner_radius": 1, "outer_radius": 2, "material": "m"})",
                  {0.375, 0.5, 0.875}});
  // Ring 0.5 <= |p| <= 1 in y = 0, seen from |dir.y| >= 0.2: hits aim at the annulus.
  c.bench.push_back({{{"inner_radius", {0.5}}, {"outer_radius", {1.0}}}, prism::cases::bench_origins(4.0, 0.2),
                     [](BenchRng& r) {
                       const double a = r.uniform(0, 2 * kPi), s = std::sqrt(r.uniform(0.55 * 0.55, 0.95 * 0.95));
                       return glm::dvec3(s * std::cos(a), 0.0, s * std::sin(a));
                     }, {}});
  // Random scenes: outer radius s = scale * [0.2, 1.5), inner 0.4 s.
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = random_size(rng, at);
    return random_framed_object(rng, at, "ring", "\"inner_radius\": " + num(0.4 * s) + ", \"outer_radius\": " + num(s));
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_ring_cases)
