// A primitive plugin written once in the shared dialect
// (prism/sdk/dialect.hpp): the C ABI entry points of its double
// instantiation. A plugin's .cpp instantiates its `<type>.shared.glsl`
// (PRISM_SHARED_SOURCE + prism/sdk/instantiate.hpp) and hands
//   f64::abi_intersect<f64::<type>_intersect>, f64::abi_surface<f64::<type>_surface>
// to describe_primitive; the same text is its GLSL source (kPluginGlsl).
#pragma once

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

template <SharedSurface Surface>
void abi_surface(const void* record, const ::PrismRay* ray, const ::PrismHit* hit, ::PrismSurface* out) {
  PrismSurface s;
  Surface(prism_record_at(record), ray_from_abi(ray), hit_from_abi(hit), s);
  write_surface(out, s.point, s.normal, s.uv.x, s.uv.y);
}

}  // namespace
}  // namespace prism::sdk::f64
