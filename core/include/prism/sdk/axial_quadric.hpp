// What the cylinder and cone plugins share: a quadric clipped to
// 0 <= y <= height around the local y axis, with radius and height kept for
// bounds and uv (u = 0.5 + atan2(z, x)/2pi, v = y/height). Intersection,
// point and normal are the quadric code itself, so t and N are bit-identical
// to the `quadric` object each stands for.
#pragma once

#include <cstddef>
#include <string_view>

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

// Whether core/glsl/quadric.glsl (`module`, embedded by the plugins that
// require it) reads the record offsets the C++ side writes.
constexpr bool quadric_module_matches_records(std::string_view module) {
  constexpr size_t shape = offsetof(AxialQuadricRecord, shape), d = sizeof(double);
  return glsl_define(module, "PRISM_QUADRIC_COEF") == long((shape + offsetof(QuadricShape, coef)) / d) &&
         glsl_define(module, "PRISM_QUADRIC_LO") == long((shape + offsetof(QuadricShape, lo)) / d) &&
         glsl_define(module, "PRISM_QUADRIC_HI") == long((shape + offsetof(QuadricShape, hi)) / d) &&
         glsl_define(module, "PRISM_AXIAL_QUADRIC_HEIGHT") == long(offsetof(AxialQuadricRecord, height) / d);
}

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

inline void axial_quadric_surface(const void* record, const PrismRay*, const PrismHit* hit, PrismSurface* out) {
  glm::dvec3 point, normal;
  quadric_record_surface(record, hit, point, normal);
  const double height = record_of<AxialQuadricRecord>(record).height;
  write_surface(out, point, normal, turn_fraction(point.z, point.x), point.y / height);
}

// Polishes a hit on x^2 + B y^2 + z^2 + J = 0 (refine.hpp), with B and J
// formed in long double from radius and height: the packed doubles
// -radius^2 and -(radius/height)^2 are rounded.
inline void polish_axial_quadric_hit(long double b, long double j, const PrismRayExt* ray, PrismHit* hit) {
  const long double coef[10] = {1, b, 1, 0, 0, 0, 0, 0, 0, j};
  polish_quadric_hit(coef, ray, hit);
}

// The descriptor of a plugin whose `pack` calls pack_axial_quadric.
template <size_t FieldCount>
constexpr PrismPrimitiveDesc describe_axial_quadric(const char* type_name, const PrismField (&fields)[FieldCount],
                                                    void (*pack)(const double*, void*), RefineFn refine,
                                                    const char* glsl_source = nullptr,
                                                    const char* glsl_prefix = nullptr) {
  return describe_primitive<intersect_quadric_record>(type_name, PRISM_PRIMITIVE_TRANSFORMABLE, fields,
                                                      sizeof(AxialQuadricRecord), validate_nothing, pack,
                                                      axial_quadric_bounds, axial_quadric_surface, glsl_source,
                                                      glsl_prefix, refine);
}

}  // namespace prism::sdk
