// A primitive plugin written once in the shared dialect
// (prism/sdk/dialect.hpp): the C ABI entry points of its instantiations.
// A plugin's .cpp instantiates its `<type>.shared.glsl`
// (PRISM_SHARED_SOURCE + prism/sdk/instantiate.hpp) and hands
//   PRISM_SHARED_INTERSECT(<type>_intersect), f64::abi_surface<f64::<type>_surface>
// to describe_primitive: `intersect` from the double instantiation,
// `intersect_float` from the float one; the same text is its GLSL source
// (kPluginGlsl). The surface stays double (primitive_abi.h, version 4).
#pragma once

#include <cmath>
#include <limits>

#include "prism/primitive_abi.h"
#include "prism/sdk/library.hpp"
#include "prism/sdk/primitive_sdk.hpp"

namespace prism::sdk::f64 {
namespace {

inline PrismRay ray_from_abi(const ::PrismRay* ray) {
  PrismRay r;
  r.origin = load3(ray->origin);
  r.dir = load3(ray->dir);
  return r;
}

inline PrismHit hit_from_abi(const ::PrismHit* hit) {
  PrismHit h;
  h.t = hit->t;
  h.data = load3(hit->data);
  h.part = hit->part;
  return h;
}

inline void store_hit(const PrismHit& h, ::PrismHit* out) {
  *out = ::PrismHit{};
  out->t = h.t;
  store3(h.data, out->data);
  out->part = h.part;
}

using SharedIntersect = bool (*)(PrismRecord, PrismRay, real, real, PrismHit&);
using SharedSurface = void (*)(PrismRecord, PrismRay, PrismHit, PrismSurface&);

// The descriptor's `intersect`: the hit is written only when there is one.
template <SharedIntersect Intersect>
int abi_intersect(const void* record, const ::PrismRay* ray, double tmin, double tmax, ::PrismHit* hit) {
  PrismHit h;
  if (!Intersect(prism_record_at(record), ray_from_abi(ray), tmin, tmax, h)) return 0;
  store_hit(h, hit);
  return 1;
}

using SharedOccluded = bool (*)(PrismRecord, PrismRay, real, real);

// The descriptor's `occluded`, from a shared-dialect occlusion test.
template <SharedOccluded Occluded>
int abi_occluded(const void* record, const ::PrismRay* ray, double tmin, double tmax) {
  return Occluded(prism_record_at(record), ray_from_abi(ray), tmin, tmax) ? 1 : 0;
}

// Two calls of the inlined `Surface`: where the core asks for no uv
// (PRISM_HIT_SKIP_UV), nothing reads the copy's uv, and the compiler drops
// the arithmetic that only uv needs (a sphere's atan2 and asin), while the
// point and normal come from the same operations as in the other call.
template <SharedSurface Surface>
void abi_surface(const void* record, const ::PrismRay* ray, const ::PrismHit* hit, ::PrismSurface* out) {
  PrismSurface s;
  if ((hit->flags & PRISM_HIT_SKIP_UV) != 0) {
    Surface(prism_record_at(record), ray_from_abi(ray), hit_from_abi(hit), s);
    write_surface(out, s.point, s.normal, 0.0, 0.0);
    return;
  }
  Surface(prism_record_at(record), ray_from_abi(ray), hit_from_abi(hit), s);
  write_surface(out, s.point, s.normal, s.uv.x, s.uv.y);
}

}  // namespace
}  // namespace prism::sdk::f64

namespace prism::sdk::f32 {
namespace {

// The nearest float to x no smaller (float_up) or no larger (float_down)
// than x: the float bounds (tmin, tmax] then lie inside the double ones, so
// every t the float instantiation accepts keeps the ABI's contract once
// widened to double.
inline float float_up(double x) {
  const float f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}
inline float float_down(double x) {
  const float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

// The local ray rounded to float, as a float kernel receives it after the
// host has re-centred it in double.
inline PrismRay ray_from_abi(const ::PrismRay* ray) {
  PrismRay r;
  r.origin = real3(::prism::sdk::load3(ray->origin));
  r.dir = real3(::prism::sdk::load3(ray->dir));
  return r;
}

inline void store_hit(const PrismHit& h, ::PrismHit* out) {
  *out = ::PrismHit{};
  out->t = double(h.t);
  store3(glm::dvec3(h.data), out->data);
  out->part = h.part;
}

using SharedIntersect = bool (*)(PrismRecord, PrismRay, real, real, PrismHit&);

// The descriptor's `intersect_float`: `intersect`'s contract, computed by
// the float instantiation.
template <SharedIntersect Intersect>
int abi_intersect_float(const void* record, const ::PrismRay* ray, double tmin, double tmax, ::PrismHit* hit) {
  PrismHit h;
  if (!Intersect(prism_record_at(record), ray_from_abi(ray), float_up(tmin), float_down(tmax), h)) return 0;
  store_hit(h, hit);
  return 1;
}

}  // namespace
}  // namespace prism::sdk::f32

// describe_primitive's two intersect entries (template arguments) for the
// shared-dialect function `name` (e.g. sphere_intersect): its double and
// float instantiations, so no plugin writes its float entry by hand.
#define PRISM_SHARED_INTERSECT(name) \
  ::prism::sdk::f64::abi_intersect<::prism::sdk::f64::name>, \
      ::prism::sdk::f32::abi_intersect_float<::prism::sdk::f32::name>

// describe_primitive's `occluded` entry (the template argument after the two
// above) from the shared-dialect function `name` (e.g. torus_occluded), in
// double: bool name(PrismRecord, PrismRay, real tmin, real tmax).
#define PRISM_SHARED_OCCLUDED(name) ::prism::sdk::f64::abi_occluded<::prism::sdk::f64::name>
