// The sphere primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: a quadric with its own exact distance;
// the inside-rays family; agreement, uv and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

OracleShape sphere_oracle(ObjectFields& fields) {
  const real radius = fields.number("radius");
  if (!(radius > 0)) ObjectFields::fail("radius", "must be > 0");
  OracleShape shape = quadric_oracle(make_quadric({1, 1, 1, 0, 0, 0, 0, 0, 0, -radius * radius}, -kInf, kInf), radius);
  shape.distance = [radius](const Vec& p) { return qabs(norm(p) - radius); };
  return shape;
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  shape.object = placed({{"type", "sphere"}, {"radius", s}}, center, rot);
  shape.size = s;
  shape.sample = [s](Rng& rng) {
    const V u = rng.unit();
    return SurfacePoint{s * u, u};
  };
}

void add_sphere(Builder& b) {
  // Embree's verify case: a small sphere far from the world origin, rays from
  // inside it. Every ray must hit.
  b.add("sphere", "inside", "rays from inside a radius-1 sphere whose centre is 1..1e6 from the world origin",
        {"center", {1, 1e2, 1e4, 1e6}, 1e6}, [](double m, int n, Rng& rng) {
          Case c;
          const V center = m * V{0.5547, 0.0046, -0.8321};
          c.objects = nlohmann::json::array({{{"type", "sphere"}, {"center", to_json(center)}, {"radius", 1.0}}});
          for (int i = 0; i < n; ++i) {
            const V origin = center + 0.9 * std::cbrt(rng.uniform()) * rng.unit();
            c.rays.push_back(make_ray(origin, rng.unit()));
          }
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_sphere_cases() {
  PrimitiveCases c;
  c.type = "sphere";
  c.oracle = sphere_oracle;
  c.shape = make_shape;
  c.families = add_sphere;
  c.agreement.push_back({"sphere",
                         R"({"type": "sphere", "center": [1, 2, 3], "radius": 1.3})", 1.3});
  // Straight down onto the north pole: p = (0, 1, 0), u = 0.5 + atan2(0, 0)/2pi
  // = 0.5, v = 0.5 - asin(1)/pi = 0; uv' = (0.625, 0.125) -> texel (2, 0) =
  // (0.375, 0.125, 0.125). (atan2 = pi would give u = 1 -> texel (0, 0).)
  c.uv.push_back({"SpherePoleTakesAtan2OfZeroZeroAsZero",
                  R"({"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1]})",
                  R"(, "uv_offset": [0.125, 0.125])",
                  R"({"type": "sphere", "radius": 1, "material": "m"})",
                  {0.375, 0.125, 0.125}});
  // Unit sphere: hits aim inside radius 0.9.
  c.bench.push_back(
      {{{"radius", {1.0}}}, prism::cases::bench_origins(4.0), [](BenchRng& r) { return r.in_ball(0.9); }, {}});
  // Random scenes: radius scale * [0.2, 1.5).
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = random_size(rng, at);
    return random_framed_object(rng, at, "sphere", "\"radius\": " + num(s));
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_sphere_cases)
