// The cone primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: the quadric x^2 + z^2 = (r/h)^2 y^2
// clipped to 0 <= y <= height; apex and rim; agreement, uv and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

OracleShape cone_oracle(ObjectFields& fields) {
  const real radius = fields.number("radius"), height = fields.number("height");
  if (!(radius > 0)) ObjectFields::fail("radius", "must be > 0");
  if (!(height > 0)) ObjectFields::fail("height", "must be > 0");
  // -(radius/height)^2 with a single rounding: the squares of doubles are exact in quad.
  const real k2 = (radius * radius) / (height * height);
  return quadric_oracle(make_quadric({1, -k2, 1, 0, 0, 0, 0, 0, 0, 0}, 0, height), qmax(radius, height));
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  const double r = 0.5 * s, h = s, k = r / h;
  shape.object = placed({{"type", "cone"}, {"radius", r}, {"height", h}}, center, rot);
  shape.mid = {0, h / 2, 0};
  shape.size = std::sqrt(r * r + h * h / 4);
  shape.sample = [k, h](Rng& rng) {
    const double phi = rng.range(0, 2 * kPi), y = rng.range(0.05, 0.98) * h;
    const V p{k * y * std::cos(phi), y, k * y * std::sin(phi)};
    return SurfacePoint{p, normalize({p.x, -k * k * p.y, p.z})};
  };
}

void add_cone(Builder& b) {
  // The apex (not rotated, exact centre): rays at the apex itself (eta = 0)
  // or at surface points eta * height from it; half from inside the cone's
  // solid angle (from above, down through the apex: a robust hit at a double
  // root), half from outside.
  b.add("cone", "apex", "rays at the apex (eta = 0) or eta * height from it along the surface",
        {"eta", {1e-1, 1e-3, 1e-6, 1e-9, 0}, 0}, [](double eta, int n, Rng& rng) {
          Case c;
          const double r = 1, h = 2, half_angle = std::atan(r / h);
          const V apex{0.25, 0.5, -0.125};
          c.objects =
              nlohmann::json::array({{{"type", "cone"}, {"center", to_json(apex)}, {"radius", r}, {"height", h}}});
          for (int i = 0; i < n; ++i) {
            const double phi = rng.range(0, 2 * kPi);
            const V gen = normalize({r / h * std::cos(phi), 1, r / h * std::sin(phi)});
            const V P = apex + eta * h * gen;
            const V d = i % 2 == 0 ? rng.cone({0, -1, 0}, std::cos(0.8 * half_angle), 1)
                                   : rng.cone({0, -1, 0}, -1, std::cos(1.2 * half_angle));
            c.rays.push_back(ray_to(P, d, rng.range(1, 3)));
          }
          return c;
        });

  b.add("cone", "rim", "rays aimed at the open base rim, height (1 ± eta) (rotated)",
        {"eta", {1e-2, 1e-4, 1e-6, 1e-8}, 1e-6}, [](double eta, int n, Rng& rng) {
          Case c;
          const double r = 1, h = 2, k = r / h;
          c.objects =
              nlohmann::json::array({placed({{"type", "cone"}, {"radius", r}, {"height", h}}, kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            const double phi = rng.range(0, 2 * kPi), y = h * (1 + (i % 2 ? eta : -eta));
            const V p{k * y * std::cos(phi), y, k * y * std::sin(phi)};
            c.rays.push_back(ray_at_tilted_surface(rng, p, {p.x, -k * k * p.y, p.z}));
          }
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_cone_cases() {
  PrimitiveCases c;
  c.type = "cone";
  c.oracle = cone_oracle;
  c.shape = make_shape;
  c.families = add_cone;
  c.agreement.push_back({"cone",
                         R"({"type": "cone", "center": [1, 2, 3], "radius": 0.8, "height": 1.6})", 1.2});
  // radius 1, height 1 (x^2 + z^2 = y^2). From (0, 0.625, 5) along -z:
  // p = (0, 0.625, 0.625). u = 0.75, v = 0.625/1.
  // uv' = (0.875, 0.625) -> texel (3, 2) = (0.5, 0.375, 0.6875).
  c.uv.push_back({"ConeUv",
                  R"({"position": [0, 0.625, 5], "look_at": [0, 0.625, 0]})",
                  R"(, "uv_offset": [0.125, 0])",
                  R"({"type": "cone", "radius": 1, "height": 1, "material": "m"})",
                  {0.5, 0.375, 0.6875}});
  // Open cone, apex at 0, radius 1 at y = 2: hits aim at points of the cone.
  c.bench.push_back({{{"radius", {1.0}}, {"height", {2.0}}},
                     [](BenchRng& r) { return glm::dvec3(0, 1, 0) + prism::cases::bench_origins(5.0)(r); },
                     [](BenchRng& r) {
                       const double y = r.uniform(0.1, 1.9), a = r.uniform(0, 2 * kPi), s = y / 2.0;
                       return glm::dvec3(s * std::cos(a), y, s * std::sin(a));
                     }, {}});
  // Random scenes: radius s = scale * [0.2, 1.5), height 2 s.
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = random_size(rng, at);
    return random_framed_object(rng, at, "cone", "\"radius\": " + num(s) + ", \"height\": " + num(2 * s));
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_cone_cases)
