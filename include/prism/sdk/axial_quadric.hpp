// What the cylinder and cone plugins share: a quadric clipped to
// 0 <= y <= height around the local y axis, with radius and height kept for
// bounds and uv (u = 0.5 + atan2(z, x)/2pi, v = y/height). Intersection,
// point and normal are the quadric code itself (prism_quadric_intersect and
// prism_axial_quadric_surface in prism/sdk/modules/quadric.shared.glsl), so t
// and N are bit-identical to the `quadric` object each stands for.
#pragma once

#include <cmath>
#include <cstddef>

#include "prism/primitive_abi.h"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/quadric_math.hpp"

namespace prism::sdk {

struct AxialQuadricRecord {
  QuadricShape shape;  // first, so intersect_quadric_record reads it
  double radius;
  double height;
  double pad[2];
};
static_assert(sizeof(AxialQuadricRecord) % 16 == 0);

static_assert(PRISM_QUADRIC_COEF == (offsetof(AxialQuadricRecord, shape) + offsetof(QuadricShape, coef)) / sizeof(double));
static_assert(PRISM_AXIAL_QUADRIC_HEIGHT == offsetof(AxialQuadricRecord, height) / sizeof(double));

// Packs coefficients `coef` clipped to 0 <= y <= height.
inline void pack_axial_quadric(const double coef[10], double radius, double height, void* record) {
  const double lo[3] = {-kInf, 0.0, -kInf}, hi[3] = {kInf, height, kInf};
  *static_cast<AxialQuadricRecord*>(record) = AxialQuadricRecord{make_quadric(coef, lo, hi), radius, height, {0.0, 0.0}};
}

inline int axial_quadric_bounds(const void* record, double lo[3], double hi[3]) {
  const auto& rec = record_of<AxialQuadricRecord>(record);
  store3(glm::dvec3(-rec.radius, 0.0, -rec.radius), lo);
  store3(glm::dvec3(rec.radius, rec.height, rec.radius), hi);
  return 1;
}

// The sphere around the cylinder of `radius` and `height` (the cone's too,
// which lies inside it): centred halfway up the axis, through the rims.
inline int axial_quadric_bounding_sphere(const void* record, double center[3], double* radius) {
  const auto& rec = record_of<AxialQuadricRecord>(record);
  store3(glm::dvec3(0.0, 0.5 * rec.height, 0.0), center);
  *radius = std::hypot(rec.radius, 0.5 * rec.height);
  return 1;
}

// Polishes a hit on x^2 + B y^2 + z^2 + J = 0 (refine.hpp), with B and J
// formed in long double from radius and height: the packed doubles
// -radius^2 and -(radius/height)^2 are rounded.
inline void polish_axial_quadric_hit(long double b, long double j, const PrismRayExt* ray, PrismHit* hit) {
  const long double coef[10] = {1, b, 1, 0, 0, 0, 0, 0, 0, j};
  polish_quadric_hit(coef, ray, hit);
}

// The descriptor of a plugin whose `pack` calls pack_axial_quadric, with
// the C ABI entry points of its one source (prism/sdk/shared_plugin.hpp:
// PRISM_SHARED_INTERSECT gives the first two), which calls
// prism_quadric_intersect and prism_axial_quadric_surface.
template <IntersectFn Intersect, IntersectFn IntersectFloat, SurfaceFn Surface, size_t FieldCount>
constexpr PrismPrimitiveDesc describe_axial_quadric(const char* type_name, const PrismField (&fields)[FieldCount],
                                                    void (*pack)(const double*, void*), RefineFn refine,
                                                    const char* glsl_source, const char* glsl_prefix) {
  return describe_primitive<Intersect, IntersectFloat>(type_name, PRISM_PRIMITIVE_TRANSFORMABLE, fields, sizeof(AxialQuadricRecord),
                                       validate_nothing, pack, axial_quadric_bounds, Surface, glsl_source,
                                       glsl_prefix, refine, axial_quadric_bounding_sphere);
}

}  // namespace prism::sdk
