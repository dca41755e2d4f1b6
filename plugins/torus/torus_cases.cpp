// The torus primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: no quartic at all: the signed distance to
// the tube, sampled and bracketed; holes, ratios and tangents; agreement
// (a thin torus too), uv and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

// --- torus

struct TorusSample {
  real g;   // signed distance to the tube surface
  real dg;  // dg/ds
};

struct TorusRay {
  Vec o, d;
  real R, r;
  TorusSample at(real s) const {
    Vec p = o + s * d;
    real rho = sqrtq(p.x * p.x + p.z * p.z);
    real u = rho - R;
    real dist = sqrtq(u * u + p.y * p.y);
    TorusSample e{dist - r, 0};
    if (dist > 0) {
      real drho = rho > 0 ? (p.x * d.x + p.z * d.z) / rho : 0;
      e.dg = (u * drho + p.y * d.y) / dist;
    }
    return e;
  }
};

// The root of g in [a, b] (g(a), g(b) of opposite signs, neither 0):
// safeguarded Newton-bisection to full quad precision.
real torus_root(const TorusRay& tr, real a, real ga, real b) {
  real lo = a, hi = b;  // g(lo) has the sign of ga
  real sign = ga < 0 ? -1 : 1;
  real x = (a + b) / 2;
  TorusSample e = tr.at(x);
  for (int it = 0; it < 400; ++it) {
    if (e.g == 0) return x;
    if (sign * e.g > 0)
      lo = x;
    else
      hi = x;
    real next;
    bool newton = e.dg != 0;
    if (newton) {
      next = x - e.g / e.dg;
      newton = (next - lo) * (next - hi) < 0;  // strictly inside the bracket
    }
    if (!newton) next = (lo + hi) / 2;
    if (next == x || next == lo || next == hi) break;
    real step = qabs(next - x);
    x = next;
    e = tr.at(x);
    if (step <= 4 * kEps * (qabs(x) + tr.R)) {
      // Converged: one more Newton step if it lowers |g|.
      if (e.dg != 0) {
        real x2 = x - e.g / e.dg;
        TorusSample e2 = tr.at(x2);
        if (qabs(e2.g) < qabs(e.g)) x = x2;
      }
      return x;
    }
  }
  return x;
}

// The point of [a, b] where sigma * g has an interior minimum (sigma * g'
// going from < 0 to >= 0), by bisection on g'; false when there is none.
bool torus_extremum(const TorusRay& tr, real sigma, real a, const TorusSample& ea, real b, const TorusSample& eb,
                    real& m) {
  if (!(sigma * ea.dg < 0 && sigma * eb.dg >= 0)) return false;
  real lo = a, hi = b;
  for (int it = 0; it < 400; ++it) {
    real mid = (lo + hi) / 2;
    if (mid == lo || mid == hi) break;
    if (sigma * tr.at(mid).dg < 0)
      lo = mid;
    else
      hi = mid;
  }
  real glo = sigma * tr.at(lo).g, ghi = sigma * tr.at(hi).g;
  m = glo <= ghi ? lo : hi;
  return true;
}

LocalHit torus_hit(real R, real r, const Vec& o_local, const Vec& d, real tmin) {
  Recentred rc = recentre(o_local, d);
  real rb = (R + r) * (1 + real(1e-6));  // bounding sphere, slightly enlarged
  real m2 = dot(rc.o, rc.o);
  if (!(m2 < rb * rb)) return {};
  real half = sqrtq(rb * rb - m2);
  real s_start = qmax(-half, tmin - rc.t0);
  if (!(s_start < half)) return {};
  TorusRay tr{rc.o, d, R, r};
  // Feature scale: the tube radius, or the hole's half width for a fat torus
  // (near the surface |g''| <= 1/r + 1/(R - r) <= 2 / scale).
  const real scale = qmin(r, R - r);
  const real h = qmax(scale / 64, 1024 * kEps * (R + r));  // the floor only matters for absurdly thin tubes
  const real flag = 4 * h * h / scale;  // 4x the deepest dip two samples h apart can hide
  const real tol = 32 * kEps * (R + r + rc.origin_norm);

  auto hit_at = [&](real s) {
    LocalHit out;
    out.hit = true;
    out.t = rc.t0 + s;
    Vec p = rc.o + s * d;
    // The spec's normal: the gradient of (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + z^2).
    real k = 4 * (dot(p, p) + R * R - r * r), l = 8 * R * R;
    out.n = {k * p.x - l * p.x, k * p.y, k * p.z - l * p.z};
    return out;
  };
  auto accept = [&](real s) { return rc.t0 + s > tmin; };

  real sa = s_start;
  TorusSample ea = tr.at(sa);
  real sigma = ea.g < 0 ? -1 : 1;
  if (ea.g == 0) {
    if (accept(sa)) return hit_at(sa);
    // On the surface at tmin: the side the ray moves into.
    sigma = ea.dg < 0 ? -1 : (ea.dg > 0 ? 1 : (tr.at(sa + h / 1024).g < 0 ? -1 : 1));
  }
  while (sa < half) {
    real step = qmax(h, real(0.9) * qabs(ea.g));
    real sb = qmin(sa + step, half);
    TorusSample eb = tr.at(sb);
    if (sigma * eb.g < 0) {
      real s = torus_root(tr, sa, ea.g == 0 ? sigma : ea.g, sb);
      if (accept(s)) return hit_at(s);
    } else {
      if (qmin(qabs(ea.g), qabs(eb.g)) <= flag) {
        real m;
        if (torus_extremum(tr, sigma, sa, ea, sb, eb, m)) {
          real gm = tr.at(m).g;
          if (qabs(gm) <= tol) {
            if (accept(m)) return hit_at(m);  // tangent: a double root
          } else if (sigma * gm < 0) {
            real s = torus_root(tr, sa, ea.g == 0 ? sigma : ea.g, m);
            if (accept(s)) return hit_at(s);
            s = torus_root(tr, m, gm, sb);
            if (accept(s)) return hit_at(s);
          }
        }
      }
      if (eb.g == 0 && accept(sb)) return hit_at(sb);
    }
    sa = sb;
    ea = eb;
    if (ea.g != 0) sigma = ea.g < 0 ? -1 : 1;
  }
  return {};
}

OracleShape torus_oracle(ObjectFields& fields) {
  const real major = fields.number("major_radius"), minor = fields.number("minor_radius");
  if (!(minor > 0)) ObjectFields::fail("minor_radius", "must be > 0");
  if (!(minor < major)) ObjectFields::fail("minor_radius", "must be < major_radius");
  OracleShape shape;
  shape.hit = [major, minor](const Vec& o, const Vec& d, real tmin) { return torus_hit(major, minor, o, d, tmin); };
  shape.distance = [major, minor](const Vec& p) {
    // Exact (the distance to the core circle minus r), not only first order.
    real u = sqrtq(p.x * p.x + p.z * p.z) - major;
    return qabs(sqrtq(u * u + p.y * p.y) - minor);
  };
  shape.size = major + minor;
  return shape;
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  const double R = s / 1.3, r = 0.3 * R;
  shape.object = placed({{"type", "torus"}, {"major_radius", R}, {"minor_radius", r}}, center, rot);
  shape.size = R + r;
  shape.sample = [R, r](Rng& rng) {
    const double u = rng.range(0, 2 * kPi), v = rng.range(0, 2 * kPi);
    const V n{std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)};
    return SurfacePoint{{(R + r * std::cos(v)) * std::cos(u), r * std::sin(v), (R + r * std::cos(v)) * std::sin(u)},
                        n};
  };
}

// The torus at kCenterA, rotated by kTilted, and a point of its surface in
// the local frame (u around the axis, v around the tube).
nlohmann::json tilted_torus(double R, double r) {
  return placed({{"type", "torus"}, {"major_radius", R}, {"minor_radius", r}}, kCenterA, kTilted);
}
V torus_point(double R, double r, double u, double v) {
  return {(R + r * std::cos(v)) * std::cos(u), r * std::sin(v), (R + r * std::cos(v)) * std::sin(u)};
}

void add_torus(Builder& b) {
  const std::vector<double> ratios = {1e-3, 1e-2, 0.1, 0.5, 0.9, 0.99};

  // Random rays at the tube from 3..10 (R + r), across the ratio r/R.
  b.add("torus", "ratio", "rays from 3..10 (R+r) at points near the tube, r/R from 1e-3 to 0.99 (rotated torus)",
        {"r/R", ratios, 1e-3}, [](double ratio, int n, Rng& rng) {
          Case c;
          const double R = 1, r = ratio * R;
          c.objects = nlohmann::json::array({tilted_torus(R, r)});
          for (int i = 0; i < n; ++i) {
            const double u = rng.range(0, 2 * kPi), v = rng.range(0, 2 * kPi);
            const V p = torus_point(R, r, u, v);
            const V target = kCenterA + kTilted.apply(p + 0.3 * r * rng.unit());
            const V origin = kCenterA + rng.range(3, 10) * (R + r) * rng.unit();
            c.rays.push_back(make_ray(origin, target - origin));
          }
          return c;
        });

  // Rays through the hole: a quarter exactly on the axis (the torus is not
  // rotated and its centre is exact, so x and z are exact), the rest parallel
  // or tilted, all staying within 0.9 (R - r) of the axis while inside the
  // slab |y| <= r, so every one must miss.
  b.add("torus", "hole", "rays along the axis and through the hole (must miss), r/R from 1e-3 to 0.99",
        {"r/R", ratios, 0.99}, [](double ratio, int n, Rng& rng) {
          Case c;
          const double R = 1, r = ratio * R;
          const V center{0.5, -0.25, 1.0};
          c.objects = nlohmann::json::array(
              {{{"type", "torus"}, {"center", to_json(center)}, {"major_radius", R}, {"minor_radius", r}}});
          for (int i = 0; i < n; ++i) {
            const double side = rng.sign(), height = r + rng.range(0.5, 5);
            if (i % 4 == 0) {
              c.rays.push_back(make_ray(center + V{0, side * height, 0}, {0, -side, 0}));
              continue;
            }
            const double rho0 = rng.range(0, 0.8) * (R - r), beta = rng.range(0, 2 * kPi);
            const double tilt = i % 4 == 1 ? 0.0 : std::atan(rng.uniform() * (0.9 * (R - r) - rho0) / r);
            const double gamma = rng.range(0, 2 * kPi);
            const V d{std::sin(tilt) * std::cos(gamma), -side * std::cos(tilt), std::sin(tilt) * std::sin(gamma)};
            const V crossing = center + V{rho0 * std::cos(beta), 0, rho0 * std::sin(beta)};
            c.rays.push_back(ray_to(crossing, d, height / std::cos(tilt)));
          }
          return c;
        });

  // Lines tangent to the tube, shifted 5x the ambiguity band off the tangent
  // point (half inward, half outward), at every kind of surface point (outer,
  // inner saddle, top).
  b.add("torus", "tangent", "lines tangent to the tube, 5x the ambiguity band off it, r/R from 1e-3 to 0.99 (rotated)",
        {"r/R", ratios, 1e-3}, [](double ratio, int n, Rng& rng) {
          Case c;
          const double R = 1, r = ratio * R;
          c.objects = nlohmann::json::array({tilted_torus(R, r)});
          for (int i = 0; i < n; ++i) {
            const double u = rng.range(0, 2 * kPi), v = rng.range(0, 2 * kPi);
            const V p = torus_point(R, r, u, v);
            const V N = normalize(kTilted.apply({std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)}));
            const V P = kCenterA + kTilted.apply(p), T = rng.tangent(N);
            const double L = rng.range(1, 3);
            const V start = P - L * T;
            const double shift = (i % 2 ? 1.0 : -1.0) * 5e-7 * (length(start) + L);
            c.rays.push_back(make_ray(start + shift * N, T));
          }
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_torus_cases() {
  PrimitiveCases c;
  c.type = "torus";
  c.oracle = torus_oracle;
  c.shape = make_shape;
  c.families = add_torus;
  c.agreement.push_back({"torus",
                         R"({"type": "torus", "center": [1, 2, 3], "major_radius": 1, "minor_radius": 0.25})", 1.25});
  // Unrotated, R = 1: rays from outside aim at a point within 0.03 of the
  // core circle: hits, grazes and near misses.
  c.agreement.push_back({"thin_torus",
                         R"({"type": "torus", "center": [1, 2, 3], "major_radius": 1, "minor_radius": 0.01})", 1.0,
                         false, [](const glm::dvec3& centre, const std::function<double()>& unit) {
                           const double angle = 3.14159265358979 * unit();
                           return centre + glm::dvec3(std::cos(angle), 0.0, std::sin(angle)) +
                                  0.03 * glm::dvec3(unit(), unit(), unit());
                         }});
  // R = 2, r = 0.5. From above at (0, 5, 2): p = (0, 0.5, 2), the top of the
  // tube. u = 0.5 + atan2(2, 0)/2pi = 0.75; v = 0.5 + atan2(0.5, 2 - 2)/2pi = 0.75.
  // uv' = (0.875, 0.875) -> texel (3, 3) = (0.5, 0.5, 0.9375).
  c.uv.push_back({"TorusUv",
                  R"({"position": [0, 5, 2], "look_at": [0, 0, 2], "up": [0, 0, -1]})",
                  R"(, "uv_offset": [0.125, 0.125])",
                  R"({"type": "torus", "major_radius": 2, "minor_radius": 0.5, "material": "m"})",
                  {0.5, 0.5, 0.9375}});
  // Torus R = 1, r = 0.25: hits aim at the tube's centre circle; misses include the hole.
  c.bench.push_back({{{"major_radius", {1.0}}, {"minor_radius", {0.25}}}, prism::cases::bench_origins(5.0),
                     [](BenchRng& r) {
                       const double a = r.uniform(0, 2 * kPi);
                       return glm::dvec3(std::cos(a), 0.0, std::sin(a));
                     }, {}});
  // Random scenes: major radius s = scale * [0.2, 1.5), minor s * [0.05, 0.5).
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = random_size(rng, at), minor = s * uniform(rng, 0.05, 0.5);
    return random_framed_object(rng, at, "torus", "\"major_radius\": " + num(s) + ", \"minor_radius\": " + num(minor));
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_torus_cases)
