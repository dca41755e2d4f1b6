// Helpers for a primitive plugin's unit tests (no test framework needed):
// drive a plugin only through its descriptor, the way the core does, with
// glm types; random directions; the spec's secondary-ray offset; and the
// pbrt-style "rays leaving a convex shape never hit it again" check.
#pragma once

#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/shared_source.hpp"

namespace prism::sdk::testing {

struct Hit {
  double t = kInf;
  PrismHit raw{};
};

struct Surface {
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0.0};
  glm::dvec2 uv{0.0};
};

inline const PrismField* find_field(const PrismPrimitiveDesc& desc, const char* name) {
  for (uint32_t i = 0; i < desc.field_count; ++i)
    if (std::strcmp(desc.fields[i].name, name) == 0) return &desc.fields[i];
  return nullptr;
}

// One packed object of a plugin. `values` are the checked field values, field
// after field, as the core would hand them to validate and pack.
class Shape {
 public:
  Shape(const PrismPrimitiveDesc* desc, const std::vector<double>& values)
      : desc_(desc), record_((desc->record_size + 15) / 16) {
    PrismError err{};
    if (desc_->validate(values.data(), &err) != 0)
      throw std::invalid_argument(std::string(err.field) + ": " + err.message);
    desc_->pack(values.data(), record_.data());
  }

  const void* record() const { return record_.data(); }
  const PrismPrimitiveDesc& desc() const { return *desc_; }

  std::optional<Hit> intersect(const glm::dvec3& o, const glm::dvec3& d, double tmin = 0.0,
                               double tmax = kInf) const {
    PrismRay ray = make_ray(o, d);
    Hit hit;
    if (!desc_->intersect(record(), &ray, tmin, tmax, &hit.raw)) return std::nullopt;
    hit.t = hit.raw.t;
    return hit;
  }

  // The plugin's occlusion test (ABI 6): a hit with tmin < t < tmax.
  bool occluded(const glm::dvec3& o, const glm::dvec3& d, double tmin, double tmax) const {
    PrismRay ray = make_ray(o, d);
    return desc_->occluded(record(), &ray, tmin, tmax) != 0;
  }

  Surface surface(const glm::dvec3& o, const glm::dvec3& d, const Hit& hit) const {
    PrismRay ray = make_ray(o, d);
    PrismSurface s{};
    desc_->surface(record(), &ray, &hit.raw, &s);
    return {load3(s.point), load3(s.normal), {s.uv[0], s.uv[1]}};
  }

  // The plugin's `refine` of `hit` for the same ray given in long double
  // (the hit unchanged when the plugin has no refine).
  Hit refine(const Vec3x& o, const Vec3x& d, Hit hit) const {
    if (!desc_->refine) return hit;
    const PrismRayExt ray{{o.x, o.y, o.z}, {d.x, d.y, d.z}};
    desc_->refine(record(), &ray, &hit.raw);
    hit.t = hit.raw.t;
    return hit;
  }

  static PrismRay make_ray(const glm::dvec3& o, const glm::dvec3& d) {
    PrismRay ray{};
    store3(o, ray.origin);
    store3(d, ray.dir);
    return ray;
  }

 private:
  struct alignas(16) Block {
    unsigned char bytes[16];
  };
  const PrismPrimitiveDesc* desc_;
  std::vector<Block> record_;
};

// Runs validate on `values`; returns the error (field and message) or nullopt.
inline std::optional<PrismError> validation_error(const PrismPrimitiveDesc& desc, const std::vector<double>& values) {
  PrismError err{};
  if (desc.validate(values.data(), &err) == 0) return std::nullopt;
  return err;
}

template <class Rng>
glm::dvec3 random_unit(Rng& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    glm::dvec3 v(g(rng), g(rng), g(rng));
    double len = glm::length(v);
    if (len > 1e-3) return v / len;
  }
}

// Uniform direction in the closed hemisphere around unit n.
template <class Rng>
glm::dvec3 random_in_hemisphere(Rng& rng, const glm::dvec3& n) {
  glm::dvec3 v = random_unit(rng);
  return glm::dot(v, n) < 0.0 ? -v : v;
}

// The spec's secondary-ray offset for a hit at P: 1e-4 * (1 + max|P_i|).
inline double spec_offset(const glm::dvec3& p) { return 1e-4 * (1.0 + max_abs_component(p)); }

// pbrt-v4 TestReintersectConvex: `rays` rays leave P + eps*n (n the unit
// outward normal) into n's hemisphere; on a convex shape none may hit it
// again. Returns how many did.
template <class Rng>
int count_reintersections(const Shape& shape, const glm::dvec3& p, const glm::dvec3& n, double eps, int rays,
                          Rng& rng) {
  glm::dvec3 start = p + eps * n;
  int hits = 0;
  for (int i = 0; i < rays; ++i)
    if (shape.intersect(start, random_in_hemisphere(rng, n), 0.0)) ++hits;
  return hits;
}

// Relative difference, for comparing a t with its reference.
inline double rel_err(double got, double want) { return std::abs(got - want) / std::abs(want); }

// Empty when `desc` carries a GPU intersector as primitive_abi.h asks:
// prefix `type`, the two entry points with their exact signatures (in the
// shared dialect, prism/sdk/dialect.hpp, or in plain GLSL for a hand-written
// one), and a `// prism:require <module>` line for each of `modules` (and
// none other, none malformed); otherwise what is wrong.
inline std::string gpu_intersector_problem(const PrismPrimitiveDesc& desc, const std::string& type,
                                           const std::vector<std::string>& modules) {
  if (!desc.glsl_source || !desc.glsl_prefix) return "no GLSL source or prefix";
  if (type != desc.glsl_prefix) return std::string("prefix is ") + desc.glsl_prefix;
  const std::string glsl = desc.glsl_source;
  const bool shared = glsl.find("PrismRecord rec") != std::string::npos;
  const std::string entry_points[] = {
      shared ? "bool " + type + "_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit)"
             : "bool " + type + "_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit)",
      shared ? "void " + type + "_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s)"
             : "void " + type + "_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s)"};
  for (const std::string& e : entry_points)
    if (glsl.find(e) == std::string::npos) return "missing `" + e + "`";
  const RequiredModules required = required_modules(glsl);
  if (!required.problem.empty()) return required.problem;
  if (required.modules != modules) return "unexpected `// prism:require` lines";
  return {};
}

}  // namespace prism::sdk::testing
