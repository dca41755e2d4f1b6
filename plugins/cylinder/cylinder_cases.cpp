// The cylinder primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: the quadric x^2 + z^2 = r^2 clipped
// to 0 <= y <= height; axial rays and rims; agreement, uv and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

OracleShape cylinder_oracle(ObjectFields& fields) {
  const real radius = fields.number("radius"), height = fields.number("height");
  if (!(radius > 0)) ObjectFields::fail("radius", "must be > 0");
  if (!(height > 0)) ObjectFields::fail("height", "must be > 0");
  return quadric_oracle(make_quadric({1, 0, 1, 0, 0, 0, 0, 0, 0, -radius * radius}, 0, height), qmax(radius, height));
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  const double r = 0.5 * s, h = 2 * s;
  shape.object = placed({{"type", "cylinder"}, {"radius", r}, {"height", h}}, center, rot);
  shape.mid = {0, h / 2, 0};
  shape.size = std::sqrt(r * r + h * h / 4);
  shape.sample = [r, h](Rng& rng) {
    const double phi = rng.range(0, 2 * kPi), y = rng.range(0.02, 0.98) * h;
    return SurfacePoint{{r * std::cos(phi), y, r * std::sin(phi)}, {std::cos(phi), 0, std::sin(phi)}};
  };
}

void add_cylinder(Builder& b) {
  // Rays inside or outside the tube, nearly parallel to the axis (tilt): the
  // t² coefficient is sin²(tilt). A quarter exactly parallel (not rotated,
  // exact centre: the coefficient is exactly 0 and they must miss). Height
  // 1e7 so most tilted rays reach the wall inside the clip.
  b.add("cylinder", "axial", "rays nearly parallel to the axis (tilt), a quarter exactly parallel; height 1e7",
        {"tilt", {1e-1, 1e-3, 1e-5, 1e-7}, 1e-7}, [](double tilt, int n, Rng& rng) {
          Case c;
          const V center{0.5, -0.25, 1.0};
          c.objects = nlohmann::json::array(
              {{{"type", "cylinder"}, {"center", to_json(center)}, {"radius", 0.5}, {"height", 1e7}}});
          for (int i = 0; i < n; ++i) {
            const bool inside = i % 2 == 0;
            const double rho0 = inside ? rng.range(0, 0.45) : rng.range(0.55, 2), beta = rng.range(0, 2 * kPi);
            const V o = center + V{rho0 * std::cos(beta), rng.range(1, 100), rho0 * std::sin(beta)};
            const double t = i % 4 < 2 ? 0.0 : tilt;
            // Outside: lean toward the axis; inside: any way.
            const double gamma = inside ? rng.range(0, 2 * kPi) : beta + kPi + rng.range(-0.3, 0.3);
            const V d{std::sin(t) * std::cos(gamma), std::cos(t), std::sin(t) * std::sin(gamma)};
            c.rays.push_back(make_ray(o, d));
          }
          return c;
        });

  // Aim points on the tube at the rims: y = eta*h inside or outside the clip
  // at the bottom, h (1 ± eta) at the top.
  b.add("cylinder", "rim", "rays aimed at the open rims, eta * height inside or outside the clip (rotated)",
        {"eta", {1e-2, 1e-4, 1e-6, 1e-8}, 1e-6}, [](double eta, int n, Rng& rng) {
          Case c;
          const double r = 1, h = 2;
          c.objects =
              nlohmann::json::array({placed({{"type", "cylinder"}, {"radius", r}, {"height", h}}, kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) c.rays.push_back(ray_beside_tube_end(rng, i, r, h, eta));
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_cylinder_cases() {
  PrimitiveCases c;
  c.type = "cylinder";
  c.oracle = cylinder_oracle;
  c.shape = make_shape;
  c.families = add_cylinder;
  c.agreement.push_back({"cylinder",
                         R"({"type": "cylinder", "center": [1, 2, 3], "radius": 0.8, "height": 1.6})", 1.2});
  // radius 1, height 2. From (0, 1.25, 5) along -z: p = (0, 1.25, 1).
  // u = 0.5 + atan2(1, 0)/2pi = 0.75; v = 1.25/2 = 0.625.
  // uv' = (0.875, 0.625) -> texel (3, 2) = (0.5, 0.375, 0.6875).
  c.uv.push_back({"CylinderUv",
                  R"({"position": [0, 1.25, 5], "look_at": [0, 1.25, 0]})",
                  R"(, "uv_offset": [0.125, 0])",
                  R"({"type": "cylinder", "radius": 1, "height": 2, "material": "m"})",
                  {0.5, 0.375, 0.6875}});
  // Open tube radius 1, 0 <= y <= 2: hits aim at points of the tube.
  c.bench.push_back({{{"radius", {1.0}}, {"height", {2.0}}},
                     [](BenchRng& r) { return glm::dvec3(0, 1, 0) + prism::cases::bench_origins(5.0)(r); },
                     [](BenchRng& r) {
                       const double y = r.uniform(0.1, 1.9), a = r.uniform(0, 2 * kPi);
                       return glm::dvec3(std::cos(a), y, std::sin(a));
                     }, {}});
  // Random scenes: radius s = scale * [0.2, 1.5), height 2 s.
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = random_size(rng, at);
    return random_framed_object(rng, at, "cylinder", "\"radius\": " + num(s) + ", \"height\": " + num(2 * s));
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_cylinder_cases)
