// A primitive's test cases, kept in its own folder: plugins/<type>/<type>_cases.cpp
// (examples/primitive-plugin/capsule_cases.cpp for the SDK's example).
//
// The file fills one PrimitiveCases and hands it out with
//
//   PRISM_PRIMITIVE_CASES(make_my_cases)   // PrimitiveCases make_my_cases();
//
// prism_add_primitive_plugin builds it, when it exists, into
// libprism_cases_<type>.so beside the plugin; the suites find every such
// module on the plugins' search path (PRISM_PLUGIN_PATH, then the build's
// lib/prism) and run what it holds, so adding a primitive edits no suite:
//
//   oracle, shape, families   the stability suite (tests/stability): the
//                             quad-precision first hit, the object the
//                             families every type shares are built on, and
//                             the type's own stiff families
//   agreement                 tests/scenes/trace_agreement_test.cpp: every
//                             backend against the reference on random rays
//   uv                        tests/shading/primitive_uv_test.cpp: the uv of
//                             a hit read back through a grid texture
//   bench                     bench/micro/primitive_bench.cpp: the plugin's
//                             CPU intersector on hit and miss rays
//   random_object             backends/embree's tests: random scenes of
//                             every type against a brute-force oracle
//
// Any part may be left empty. Everything crosses as C++ objects between
// programs and modules of one build (same compiler, same standard library);
// nothing here is installed.
#pragma once

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "exact_kit.hpp"
#include "family_kit.hpp"
#include "prism/primitive_abi.h"
#include "spheres_scene.hpp"

namespace prism::cases {

// ---------------------------------------------------------------- stiff families

// A ray at the point `p` of an object placed at stability::kCenterA and
// rotated by stability::kTilted (the "rotated" families), `normal` its
// outward normal there (any length; both in the object's frame): from
// outside, within acos(0.05) of the inward normal, starting 1 to 4 away.
inline stability::Ray ray_at_tilted_surface(stability::Rng& rng, const stability::V& p, const stability::V& normal) {
  const stability::V N = stability::normalize(stability::kTilted.apply(normal));
  return stability::ray_to(stability::kCenterA + stability::kTilted.apply(p), rng.cone(-N, 0.05, 1), rng.range(1, 4));
}

// Ray i of a family aimed at the tube x² + z² = r² (axis y) of a "rotated"
// object, eta * h beside the tube's ends y = 0 and y = h (a cylinder's rims,
// a capsule's seams): i % 4 < 2 the bottom end, else the top; odd i toward
// +y (into the tube at the bottom, past it at the top), even i toward -y.
inline stability::Ray ray_beside_tube_end(stability::Rng& rng, int i, double r, double h, double eta) {
  const double phi = rng.range(0, 2 * stability::kPi), off = (i % 2 ? 1.0 : -1.0) * eta * h;
  const double y = i % 4 < 2 ? off : h + off;
  const stability::V p{r * std::cos(phi), y, r * std::sin(phi)};
  return ray_at_tilted_surface(rng, p, {std::cos(phi), 0, std::sin(phi)});
}

// ---------------------------------------------------------------- trace agreement

// One object for the trace-agreement suite, centred at (1, 2, 3).
struct AgreementCase {
  std::string name;    // the test's name: "<backend>_<name>"
  std::string object;  // the JSON object
  double size = 1;     // roughly the object's radius, to aim rays
  bool rotate = true;  // the suite adds {"axis": [1, 2, 0.5], "degrees": 37}
  // Where a ray from outside aims instead of a random point near the centre
  // (`unit` draws uniformly from [-1, 1)); empty: the suite's default.
  std::function<glm::dvec3(const glm::dvec3& centre, const std::function<double()>& unit)> aim = {};
};

// ---------------------------------------------------------------- uv

// One pixel of `object` seen by `camera` through the grid texture of
// tests/shading/shading_support.hpp: the test's hand-derived texel colour.
struct UvCase {
  std::string name;            // the test's name
  std::string camera;          // a JSON camera object
  std::string material_extra;  // JSON members for material "m", starting with a comma
  std::string object;          // the JSON object, with "material": "m"
  glm::dvec3 expected;         // pixel (0, 0)
};

// ---------------------------------------------------------------- microbenchmarks

// The portable generator of bench/spheres_scene.hpp, with directions.
struct BenchRng : prism::bench_tools::SplitMix64 {
  glm::dvec3 unit() {
    const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 2.0 * stability::kPi);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {s * std::cos(phi), z, s * std::sin(phi)};
  }
  glm::dvec3 in_ball(double radius) { return unit() * (radius * std::cbrt(uniform(0.0, 1.0))); }
};

inline PrismRay bench_ray(const glm::dvec3& origin, const glm::dvec3& target) {
  const glm::dvec3 d = glm::normalize(target - origin);
  return PrismRay{{origin.x, origin.y, origin.z}, {d.x, d.y, d.z}};
}

// Origins on a sphere of `radius` about the origin with |dir.y| >= min_abs_y
// (keeps rays off a ring's plane); `upper`: dir.y >= min_abs_y.
inline std::function<glm::dvec3(BenchRng&)> bench_origins(double radius, double min_abs_y = 0.0,
                                                           bool upper = false) {
  return [=](BenchRng& rng) {
    for (;;) {
      const glm::dvec3 u = rng.unit();
      if ((upper ? u.y : std::abs(u.y)) >= min_abs_y) return radius * u;
    }
  };
}

// One benchmarked object in its local frame: its field values and how rays are aimed at it.
struct BenchCase {
  std::vector<std::pair<std::string, std::vector<double>>> fields;  // others take their defaults
  std::function<glm::dvec3(BenchRng&)> origin;      // where every ray starts
  std::function<glm::dvec3(BenchRng&)> hit_target;  // a point inside the solid or on the surface
  // A candidate miss ray; empty: aim at a point of the bounding box grown by 1.5x.
  std::function<PrismRay(BenchRng&)> miss_candidate = {};
};

// ---------------------------------------------------------------- random scenes

// The generator of the Embree backend's random scenes.
using SceneRng = std::mt19937_64;

inline double uniform(SceneRng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

// A number as JSON, every bit kept.
inline std::string num(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

inline std::string vec(double x, double y, double z) { return "[" + num(x) + ", " + num(y) + ", " + num(z) + "]"; }
inline std::string vec(const glm::dvec3& v) { return vec(v.x, v.y, v.z); }

inline std::string random_vec(SceneRng& rng, double lo, double hi) {
  return vec(uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi));
}

// Where a random scene's objects go: centres (a plane's point) in
// offset + [-8, 8]^3 * scale, sizes times scale.
struct Placement {
  glm::dvec3 offset{0};
  double scale = 1;
};

// A random size for an object placed by `at`: scale * [0.2, 1.5).
inline double random_size(SceneRng& rng, const Placement& at) { return at.scale * uniform(rng, 0.2, 1.5); }

// A point of offset + [-extent, extent]^3 * scale.
inline glm::dvec3 random_point(SceneRng& rng, const Placement& at, double extent) {
  return at.offset + at.scale * glm::dvec3(uniform(rng, -extent, extent), uniform(rng, -extent, extent),
                                           uniform(rng, -extent, extent));
}

// {"type": type, a random centre, a random rotation two times in three (else
// axis-aligned, where box faces coincide with the BVH's boxes), then `fields`}.
inline std::string random_framed_object(SceneRng& rng, const Placement& at, const std::string& type,
                                        const std::string& fields) {
  std::string frame = "\"center\": " + vec(random_point(rng, at, 8));
  if (rng() % 3 != 0)
    frame += ", \"rotation\": {\"axis\": " + random_vec(rng, 0.1, 1) + ", \"degrees\": " + num(uniform(rng, 0, 360)) + "}";
  return "{\"type\": \"" + type + "\", " + frame + ", " + fields + "}";
}

// One object of the type with random parameters placed by `at`, as JSON.
using RandomObjectMaker = std::function<std::string(SceneRng& rng, const Placement& at)>;

// ---------------------------------------------------------------- one primitive

struct PrimitiveCases {
  std::string type;  // the plugin's type name

  // Stability. `transformable`: the object takes "center" and "rotation"
  // (the oracle then works in the local frame); `bounded`: the families of
  // tiny objects and of clusters apply.
  bool transformable = true;
  bool bounded = true;
  stability::OracleMaker oracle;
  stability::ShapeMaker shape;
  std::function<void(stability::Builder&)> families;  // the type's own families

  std::vector<AgreementCase> agreement;
  std::vector<UvCase> uv;
  std::vector<BenchCase> bench;

  // Random scenes (backends/embree): one random object, and how often a
  // scene draws this type relative to the others (in (0, 1]; planes are
  // rare: a scene full of them tests little of the BVH).
  RandomObjectMaker random_object;
  double random_share = 1;
};

// Every case module on the search path, one per type (the first found wins,
// as for plugins), ordered by type. Loaded once; throws std::runtime_error
// when a module cannot be loaded.
const std::vector<const PrimitiveCases*>& all_primitive_cases();
// The cases of `type`; nullptr when no module has them.
const PrimitiveCases* find_primitive_cases(const std::string& type);

}  // namespace prism::cases

// The module's entry point, returning `make()`'s cases (built once).
#define PRISM_PRIMITIVE_CASES(make)                                                                         \
  extern "C" __attribute__((visibility("default"))) const prism::cases::PrimitiveCases* prism_primitive_cases() { \
    static const prism::cases::PrimitiveCases cases = make();                                               \
    return &cases;                                                                                          \
  }
