// The plane primitive's test cases (the suites find them: see
// tests/cases/primitive_cases.hpp). The oracle: not transformable and unbounded:
// the oracle works in world space; agreement and benchmark objects.
#include <algorithm>
#include <cmath>

#include "primitive_cases.hpp"

namespace {

using namespace prism::stability;
using namespace prism::cases;

// ---------------------------------------------------------------- the oracle

OracleShape plane_oracle(ObjectFields& fields) {
  const Vec point = fields.vec3("point"), normal = fields.vec3("normal");
  if (normal.x == 0 && normal.y == 0 && normal.z == 0) ObjectFields::fail("normal", "must be non-zero");
  if (fields.has("uv_scale") && !(fields.number("uv_scale", 1) > 0)) ObjectFields::fail("uv_scale", "must be > 0");
  OracleShape shape;
  shape.hit = [point, normal](const Vec& o, const Vec& d, real tmin) {
    LocalHit out;
    real nd = dot(normal, d);
    if (nd == 0) return out;
    real t = dot(normal, point - o) / nd;
    if (!(t > tmin) || isinfq(t) || isnanq(t)) return out;
    out.hit = true;
    out.t = t;
    out.n = normal;
    return out;
  };
  shape.distance = [point, normal](const Vec& p) { return qabs(dot(normal, p - point)) / norm(normal); };
  return shape;
}

// ---------------------------------------------------------------- stiff families

// The object the families every type shares are built on.
void make_shape(Shape& shape, double s) {
  const V center = shape.center;
  const Rotation& rot = shape.rot;
  // No center or rotation in the format: the point and the rotated +y.
  shape.object = {{"type", "plane"}, {"point", to_json(center)}, {"normal", to_json(rot.apply({0, 1, 0}))}};
  shape.size = s;
  shape.sample = [s](Rng& rng) {
    const double r = s * std::sqrt(rng.uniform()), phi = rng.range(0, 2 * kPi);
    return SurfacePoint{{r * std::cos(phi), 0, r * std::sin(phi)}, {0, rng.sign(), 0}};
  };
}

// ---------------------------------------------------------------- the cases

PrimitiveCases make_plane_cases() {
  PrimitiveCases c;
  c.type = "plane";
  c.transformable = false;  // a point and a normal, no centre or rotation
  c.bounded = false;        // no tiny plane, no cluster of planes
  c.oracle = plane_oracle;
  c.shape = make_shape;
  c.agreement.push_back({"plane",
                         R"({"type": "plane", "point": [1, 2, 3], "normal": [0.2, 1, -0.3]})", 2.0, false});
  // Plane y = 0, unbounded: hits go down onto the disk |p| < 4, misses go up.
  c.bench.push_back({{{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}},
                     prism::cases::bench_origins(5.0, 0.2, true),
                     [](BenchRng& r) {
                       const double a = r.uniform(0, 2 * kPi), s = 4.0 * std::sqrt(r.uniform(0, 1));
                       return glm::dvec3(s * std::cos(a), 0.0, s * std::sin(a));
                     },
                     [](BenchRng& r) {
                       const glm::dvec3 o = prism::cases::bench_origins(5.0, 0.2, true)(r);
                       glm::dvec3 d = r.unit();
                       d.y = std::abs(d.y);
                       return prism::cases::bench_ray(o, o + d);
                     }});
  // Random scenes: a point of offset + [-12, 12]^3 * scale and any normal;
  // a quarter as often as the others (a scene full of planes tests little
  // of the BVH).
  c.random_object = [](SceneRng& rng, const Placement& at) {
    const glm::dvec3 p = random_point(rng, at, 12);
    return "{\"type\": \"plane\", \"point\": " + vec(p) + ", \"normal\": " + random_vec(rng, -1, 1) + "}";
  };
  c.random_share = 0.25;
  return c;
}

}  // namespace

PRISM_PRIMITIVE_CASES(make_plane_cases)
