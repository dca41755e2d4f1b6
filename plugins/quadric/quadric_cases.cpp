// The quadric primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: the general quadric of exact_kit.hpp
// with its clip box; nearly linear, hyperboloids, ratios, scaling, the
// double cone; agreement, uv and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

OracleShape general_quadric_oracle(ObjectFields& fields) {
  Quadric q{};
  auto c = fields.numbers("coefficients", 10);
  for (int i = 0; i < 10; ++i) q.c[i] = c[i];
  std::vector<real> lo{kInf, kInf, kInf}, hi{kInf, kInf, kInf};
  if (fields.has("clip_min")) lo = fields.numbers("clip_min", 3, true);
  if (fields.has("clip_max")) hi = fields.numbers("clip_max", 3, true);
  for (int i = 0; i < 3; ++i) {
    q.lo[i] = lo[i] == kInf ? -kInf : lo[i];
    q.hi[i] = hi[i];
  }
  bool any = false;
  for (int i = 0; i < 9; ++i) any = any || q.c[i] != 0;
  if (!any) ObjectFields::fail("coefficients", "A..I must not all be 0");
  for (int i = 0; i < 3; ++i)
    if (!(q.lo[i] <= q.hi[i])) ObjectFields::fail("clip_min", "must be <= clip_max");
  // The size: the clip box's largest coordinate, 1 when it is unbounded.
  real size = 0;
  for (int i = 0; i < 3 && size >= 0; ++i) {
    if (isinfq(q.lo[i]) || isinfq(q.hi[i]))
      size = -1;
    else
      size = qmax(size, qmax(qabs(q.lo[i]), qabs(q.hi[i])));
  }
  return quadric_oracle(q, size > 0 ? size : 1);
}

// Coefficients of the quadric with semi-axes a, b, c: x²/a² + y²/b² + z²/c² = 1.
nlohmann::json ellipsoid(double a, double b, double c) {
  return {1 / (a * a), 1 / (b * b), 1 / (c * c), 0, 0, 0, 0, 0, 0, -1};
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  const double a = s, b = 0.5 * s, c = 0.25 * s;
  shape.object = placed({{"type", "quadric"}, {"coefficients", ellipsoid(a, b, c)}}, center, rot);
  shape.size = a;
  shape.sample = [a, b, c](Rng& rng) {
    const V u = rng.unit();
    return SurfacePoint{{a * u.x, b * u.y, c * u.z}, normalize({u.x / a, u.y / b, u.z / c})};
  };
}

void add_quadric(Builder& b) {
  const V center{0.5, -0.25, 1.0};
  // f = eps (x² + z²) + y: almost the plane y = 0. Half the rays are exactly
  // vertical (the t² coefficient is exactly 0: the linear case), half oblique
  // (the t² coefficient is ~eps).
  b.add("quadric", "nearly_linear", "f = eps (x^2 + z^2) + y: t^2 coefficient exactly 0 (vertical rays) or ~eps",
        {"eps", {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12}, 1e-12}, [center](double eps, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({{{"type", "quadric"},
                                              {"center", to_json(center)},
                                              {"coefficients", {eps, 0, eps, 0, 0, 0, 0, 1, 0, 0}},
                                              {"clip_min", {-10, nullptr, -10}},
                                              {"clip_max", {10, nullptr, 10}}}});
          for (int i = 0; i < n; ++i) {
            const double x = rng.range(-9, 9), z = rng.range(-9, 9);
            const V target = center + V{x, -eps * (x * x + z * z), z};
            if (i % 2 == 0) {
              const double side = rng.sign();
              c.rays.push_back(make_ray(V{target.x, center.y + side * rng.range(1, 5), target.z}, {0, -side, 0}));
            } else {
              const double side = rng.sign();
              c.rays.push_back(ray_to(target, rng.cone({0, -side, 0}, 0.05, 1), rng.range(1, 5)));
            }
          }
          return c;
        });

  // x² + z² - k² y² = 1, clipped to |y| <= 3/k: the waist radius is 1, the
  // clipped rims have radius sqrt(10). Rays from outside at surface points,
  // and from inside the tube.
  b.add("quadric", "hyperboloid1", "one sheet x^2 + z^2 - k^2 y^2 = 1, |y| <= 3/k (rotated)",
        {"k", {1e-2, 1e-1, 1, 10, 100}, 100}, [](double k, int n, Rng& rng) {
          Case c;
          const double ym = 3 / k;
          c.objects = nlohmann::json::array({placed({{"type", "quadric"},
                                                     {"coefficients", {1, -k * k, 1, 0, 0, 0, 0, 0, 0, -1}},
                                                     {"clip_min", {nullptr, -ym, nullptr}},
                                                     {"clip_max", {nullptr, ym, nullptr}}},
                                                    kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            if (i % 4 == 3) {
              const V o{rng.range(-0.5, 0.5), rng.range(-0.9, 0.9) * ym, rng.range(-0.5, 0.5)};
              c.rays.push_back(make_ray(kCenterA + kTilted.apply(o), rng.unit()));
              continue;
            }
            const double y = rng.range(-0.95, 0.95) * ym, phi = rng.range(0, 2 * kPi);
            const double rho = std::sqrt(1 + k * k * y * y);
            const V p{rho * std::cos(phi), y, rho * std::sin(phi)};
            c.rays.push_back(ray_at_tilted_surface(rng, p, {p.x, -k * k * p.y, p.z}));
          }
          return c;
        });

  // k² y² - x² - z² = 1: two sheets 2/k apart, clipped to |x|, |z| <= 3. Rays
  // from the gap between them (hitting a sheet from inside) and from outside.
  b.add("quadric", "hyperboloid2", "two sheets k^2 y^2 - x^2 - z^2 = 1, |x|,|z| <= 3 (rotated)",
        {"k", {1e-2, 1e-1, 1, 10, 100}, 100}, [](double k, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({placed({{"type", "quadric"},
                                                     {"coefficients", {-1, k * k, -1, 0, 0, 0, 0, 0, 0, -1}},
                                                     {"clip_min", {-3, nullptr, -3}},
                                                     {"clip_max", {3, nullptr, 3}}},
                                                    kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            if (i % 2 == 0) {
              const V o{rng.range(-2, 2), rng.range(-0.5, 0.5) / k, rng.range(-2, 2)};
              const V d = rng.cone({0, rng.sign(), 0}, 0.1, 1);
              c.rays.push_back(make_ray(kCenterA + kTilted.apply(o), kTilted.apply(d)));
              continue;
            }
            const double rho = rng.range(0, 2.8), phi = rng.range(0, 2 * kPi), side = rng.sign();
            const V p{rho * std::cos(phi), side * std::sqrt(1 + rho * rho) / k, rho * std::sin(phi)};
            c.rays.push_back(ray_at_tilted_surface(rng, p, {-p.x, k * k * p.y, -p.z}));
          }
          return c;
        });

  // x² + q y² + z² = 1: a lens of radius 1 and half-thickness 1/sqrt(q);
  // coefficient ratios up to 1e12.
  b.add("quadric", "ratio", "spheroid x^2 + q y^2 + z^2 = 1: coefficient ratio q up to 1e12 (rotated)",
        {"q", {1, 1e3, 1e6, 1e9, 1e12}, 1e12}, [](double q, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array(
              {placed({{"type", "quadric"}, {"coefficients", {1, q, 1, 0, 0, 0, 0, 0, 0, -1}}}, kCenterA, kTilted)});
          const double sq = std::sqrt(q);
          for (int i = 0; i < n; ++i) {
            const V u = rng.unit();
            const V p{u.x, u.y / sq, u.z};
            c.rays.push_back(ray_at_tilted_surface(rng, p, {u.x, u.y * sq, u.z}));
          }
          return c;
        });

  // The unit sphere with every coefficient times s: the same surface. Before
  // the plugin normalised its record, 1e-200 traced as noise and 1e200 as
  // nothing, on every backend.
  b.add("quadric", "scaled", "unit sphere s (x^2 + y^2 + z^2 - 1) = 0: every coefficient times s (rotated)",
        {"s", {1e-200, 1e-100, 1e100, 1e200}, 1e-200}, [](double s, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array(
              {placed({{"type", "quadric"}, {"coefficients", {s, s, s, 0, 0, 0, 0, 0, 0, -s}}}, kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            const V u = rng.unit();
            c.rays.push_back(ray_at_tilted_surface(rng, u, u));
          }
          return c;
        });

  // The double cone x² + z² = y² (|y| <= 2, not rotated, apex at an exact
  // centre): rays aimed at the apex itself (eta = 0) or at surface points eta
  // from it, half from inside the cone's solid angle (through the apex the
  // line only touches: a double root that is a robust hit), half from outside.
  b.add("quadric", "cone_apex", "double cone x^2 + z^2 = y^2: rays at the apex (eta = 0) or eta from it",
        {"eta", {1e-1, 1e-3, 1e-6, 1e-9, 0}, 0}, [](double eta, int n, Rng& rng) {
          Case c;
          const V apex{0.25, 0.5, -0.125};
          c.objects = nlohmann::json::array({{{"type", "quadric"},
                                              {"center", to_json(apex)},
                                              {"coefficients", {1, -1, 1, 0, 0, 0, 0, 0, 0, 0}},
                                              {"clip_min", {nullptr, -2, nullptr}},
                                              {"clip_max", {nullptr, 2, nullptr}}}});
          for (int i = 0; i < n; ++i) {
            const double phi = rng.range(0, 2 * kPi), side = rng.sign();
            const V P = apex + (eta / std::sqrt(2.0)) * V{std::cos(phi), side, std::sin(phi)};
            // Inside the solid angle: within 0.8 of the half-angle (45°) of the axis.
            const V d = i % 2 == 0 ? rng.cone({0, rng.sign(), 0}, std::cos(0.8 * kPi / 4), 1)
                                   : rng.cone({0, rng.sign(), 0}, 0, std::cos(1.2 * kPi / 4));
            c.rays.push_back(ray_to(P, d, rng.range(1, 3)));
          }
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_quadric_cases() {
  PrimitiveCases c;
  c.type = "quadric";
  c.oracle = general_quadric_oracle;
  c.shape = make_shape;
  c.families = add_quadric;
  c.agreement.push_back({"quadric",
                         R"({"type": "quadric", "center": [1, 2, 3],
                            "coefficients": [1, -1, 1, 0, 0, 0, 0, 0, 0, -0.25],
                            "clip_min": [-1.5, -1, -1.5], "clip_max": [1.5, 1, 1.5]})",
                         1.5});
  // uv = (0, 0) everywhere; uv' = (0.625, 0.375) -> texel (2, 1) = (0.375, 0.25, 0.375).
  c.uv.push_back({"QuadricUvIsZero",
                  R"({"position": [0, 0, 5], "look_at": [0, 0, 0]})",
                  R"(, "uv_offset": [0.625, 0.375])",
                  R"({"type": "quadric", "coefficients": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1], "material": "m"})",
                  {0.375, 0.25, 0.375}});
  // Quadric: the hyperboloid of one sheet x^2 - y^2 + z^2 = 1, clipped to |y| <= 1.
  c.bench.push_back(
      {{{"coefficients", {1, -1, 1, 0, 0, 0, 0, 0, 0, -1}}, {"clip_min", {-2, -1, -2}}, {"clip_max", {2, 1, 2}}},
       prism::cases::bench_origins(6.0),
       [](BenchRng& r) {
         const double y = r.uniform(-0.95, 0.95), a = r.uniform(0, 2 * kPi), s = std::sqrt(1 + y * y);
         return glm::dvec3(s * std::cos(a), y, s * std::sin(a));
       },
       {}});
  // Random scenes, s = scale * [0.2, 1.5): half the time a hyperboloid
  // clipped to [-s, s]^3 (bounded), else an unclipped ellipsoid (unbounded
  // to the BVH: tested by brute force).
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = random_size(rng, at);
    const std::string fields =
        rng() % 2 == 0 ? "\"coefficients\": [1, -1, 1, 0, 0, 0, 0, 0, 0, " + num(-0.25 * s * s) +
                             "], \"clip_min\": " + vec(-s, -s, -s) + ", \"clip_max\": " + vec(s, s, s)
                       : "\"coefficients\": [" + num(1 / (s * s)) + ", 2, 3, 0, 0, 0, 0, 0, 0, -1]";
    return random_framed_object(rng, at, "quadric", fields);
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_quadric_cases)
