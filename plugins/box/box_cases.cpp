// The box primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: the slab method in quad precision;
// edges, corners and face planes; agreement and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

LocalHit box_hit(const real* half, const Vec& o_local, const Vec& d, real tmin) {
  Recentred r = recentre(o_local, d);
  real near = -kInf, far = kInf;
  int near_axis = 0, far_axis = 0;
  for (int i = 0; i < 3; ++i) {
    real di = at(d, i), oi = at(r.o, i), h = half[i];
    if (di == 0) {
      if (!(qabs(oi) <= h)) return {};
      continue;
    }
    real t0 = (-h - oi) / di, t1 = (h - oi) / di;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > near) {
      near = t0;
      near_axis = i;
    }
    if (t1 < far) {
      far = t1;
      far_axis = i;
    }
  }
  if (!(near <= far)) return {};
  real hmax = qmax(half[0], qmax(half[1], half[2]));
  real snap = 64 * kEps * (hmax + r.origin_norm);
  for (int pass = 0; pass < 2; ++pass) {
    real s = pass == 0 ? near : far;
    int axis = pass == 0 ? near_axis : far_axis;
    real t = r.t0 + s;
    if (!(t > tmin)) continue;
    Vec p = r.o + s * d;
    for (int i = 0; i < 3; ++i) {
      real h = half[i];
      if (i == axis) {
        bool entering = pass == 0;
        at(p, i) = ((at(d, i) > 0) == entering) ? -h : h;
      } else {
        real v = qmin(qmax(at(p, i), -h), h);
        if (h - qabs(v) <= snap) v = copysignq(h, v);  // an edge within rounding: the spec's tie rule
        at(p, i) = v;
      }
    }
    int a = 0;
    for (int i = 1; i < 3; ++i)
      if (qabs(at(p, i)) / half[i] > qabs(at(p, a)) / half[a]) a = i;
    LocalHit hit;
    hit.hit = true;
    hit.t = t;
    at(hit.n, a) = at(p, a) < 0 ? -1 : 1;
    return hit;
  }
  return {};
}

real box_distance(const real* half, const Vec& p) {
  real out2 = 0, inside = kInf;
  bool outside = false;
  for (int i = 0; i < 3; ++i) {
    real e = qabs(at(p, i)) - half[i];
    if (e > 0) {
      outside = true;
      out2 += e * e;
    }
    inside = qmin(inside, -e);
  }
  return outside ? sqrtq(out2) : inside;
}

OracleShape box_oracle(ObjectFields& fields) {
  auto h = fields.numbers("half_size", 3);
  for (real v : h)
    if (!(v > 0)) ObjectFields::fail("half_size", "must be > 0");
  OracleShape shape;
  shape.hit = [h](const Vec& o, const Vec& d, real tmin) { return box_hit(h.data(), o, d, tmin); };
  shape.distance = [h](const Vec& p) { return box_distance(h.data(), p); };
  shape.size = qmax(h[0], qmax(h[1], h[2]));
  return shape;
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  const V h{s, 0.6 * s, 0.35 * s};
  shape.object = placed({{"type", "box"}, {"half_size", to_json(h)}}, center, rot);
  shape.size = length(h);
  shape.sample = [h](Rng& rng) {
    const double area[3] = {h.y * h.z, h.x * h.z, h.x * h.y};
    const double pick = rng.range(0, area[0] + area[1] + area[2]);
    const int a = pick < area[0] ? 0 : pick < area[0] + area[1] ? 1 : 2;
    double p[3] = {rng.range(-0.98, 0.98) * h.x, rng.range(-0.98, 0.98) * h.y, rng.range(-0.98, 0.98) * h.z};
    const double hs[3] = {h.x, h.y, h.z}, sg = rng.sign();
    double n[3] = {0, 0, 0};
    p[a] = sg * hs[a];
    n[a] = sg;
    return SurfacePoint{{p[0], p[1], p[2]}, {n[0], n[1], n[2]}};
  };
}

void add_box(Builder& b) {
  const V h{1, 0.6, 0.35};
  const double hs[3] = {h.x, h.y, h.z};
  // Aim points on an edge (eta = 0) or `eta` (relative to the size) inside one
  // of its two faces, from directions that see that face from the front.
  b.add("box", "edge", "rays aimed at box edges, or eta * size inside an adjacent face (rotated box)",
        {"eta", {1e-3, 1e-6, 1e-9, 0}, 0}, [h, hs](double eta, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({placed({{"type", "box"}, {"half_size", to_json(h)}}, kCenterA, kTilted)});
          const double size = length(h);
          for (int i = 0; i < n; ++i) {
            const int a = rng.index(3), b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            double p[3];
            p[a] = rng.range(-0.95, 0.95) * hs[a];
            const double s1 = rng.sign(), s2 = rng.sign();
            p[b1] = s1 * hs[b1];
            p[b2] = s2 * hs[b2];
            const bool first = rng.uniform() < 0.5;  // the face the ray aims at: b1 or b2
            const int face = first ? b1 : b2, other = first ? b2 : b1;
            p[other] -= (first ? s2 : s1) * eta * size;
            double nl[3] = {0, 0, 0};
            nl[face] = first ? s1 : s2;
            c.rays.push_back(ray_at_tilted_surface(rng, {p[0], p[1], p[2]}, {nl[0], nl[1], nl[2]}));
          }
          return c;
        });

  b.add("box", "corner", "rays aimed at box corners, or eta * size inside one of the three faces (rotated box)",
        {"eta", {1e-3, 1e-6, 1e-9, 0}, 0}, [h, hs](double eta, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({placed({{"type", "box"}, {"half_size", to_json(h)}}, kCenterA, kTilted)});
          const double size = length(h);
          for (int i = 0; i < n; ++i) {
            const double s[3] = {rng.sign(), rng.sign(), rng.sign()};
            double p[3] = {s[0] * hs[0], s[1] * hs[1], s[2] * hs[2]};
            const int face = rng.index(3);
            for (int k = 0; k < 3; ++k)
              if (k != face) p[k] -= s[k] * eta * size;
            double nl[3] = {0, 0, 0};
            nl[face] = s[face];
            c.rays.push_back(ray_at_tilted_surface(rng, {p[0], p[1], p[2]}, {nl[0], nl[1], nl[2]}));
          }
          return c;
        });

  // An axis-aligned box with exactly representable faces: rays lying exactly
  // in a face's plane (d_a = 0, o_a = c_a ± h_a: the slab test's 0/0) and rays
  // running exactly along an edge's line. They touch the closed box.
  b.add("box", "face_plane", "rays lying exactly in a face plane or along an edge line (axis-aligned box)",
        {"case", {0}, 0}, [](double, int n, Rng& rng) {
          Case c;
          const double center[3] = {0.5, -0.25, 1.25}, half[3] = {1, 0.5, 0.25};
          c.objects =
              nlohmann::json::array({{{"type", "box"}, {"center", {0.5, -0.25, 1.25}}, {"half_size", {1, 0.5, 0.25}}}});
          for (int i = 0; i < n; ++i) {
            const int a = rng.index(3), b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            double o[3], d[3];
            o[a] = center[a] + rng.sign() * half[a];  // exact: in the face plane
            d[a] = 0;
            if (i % 3 == 2) {
              // Along the edge line where faces a and b1 meet, running along b2.
              o[b1] = center[b1] + rng.sign() * half[b1];
              d[b1] = 0;
              const double s = rng.sign();
              o[b2] = center[b2] - s * half[b2] * rng.range(1.5, 6);
              d[b2] = s;
            } else {
              // Across the face from outside its extent, toward a point of the face (or just beside it).
              const double tb1 = center[b1] + rng.range(-1.2, 1.2) * half[b1];
              const double tb2 = center[b2] + rng.range(-1.2, 1.2) * half[b2];
              const double phi = rng.range(0, 2 * kPi), L = rng.range(2, 5);
              d[b1] = std::cos(phi);
              d[b2] = std::sin(phi);
              o[b1] = tb1 - L * d[b1];
              o[b2] = tb2 - L * d[b2];
            }
            c.rays.push_back(make_ray({o[0], o[1], o[2]}, {d[0], d[1], d[2]}));
          }
          return c;
        });
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_box_cases() {
  PrimitiveCases c;
  c.type = "box";
  c.oracle = box_oracle;
  c.shape = make_shape;
  c.families = add_box;
  c.agreement.push_back({"box",
                         R"({"type": "box", "center": [1, 2, 3], "half_size": [1, 0.5, 0.7]})", 1.2});
  // Box 2 x 1 x 1.5: hits aim inside the box shrunk by 0.9.
  c.bench.push_back({{{"half_size", {1.0, 0.5, 0.75}}}, prism::cases::bench_origins(5.0), [](BenchRng& r) {
                       return glm::dvec3(r.uniform(-0.9, 0.9), r.uniform(-0.45, 0.45), r.uniform(-0.675, 0.675));
                     }, {}});
  // Random scenes: half sizes s, s * [0.1, 1), s * [0.1, 1), s = scale * [0.2, 1.5).
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const double s = random_size(rng, at), y = s * uniform(rng, 0.1, 1), z = s * uniform(rng, 0.1, 1);
    return random_framed_object(rng, at, "box", "\"half_size\": " + vec(s, y, z));
  };
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_box_cases)
