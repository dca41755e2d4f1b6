// Conveniences for writing a primitive plugin against prism/primitive_abi.h:
// glm <-> double[3] copies, typed record access, field-table shorthands,
// PrismError filling, and the batch and packet queries built from intersect.
#pragma once

#include <bit>
#include <charconv>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string_view>

#include <glm/glm.hpp>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/refine.hpp"

namespace prism::sdk {

inline glm::dvec3 load3(const double v[3]) { return {v[0], v[1], v[2]}; }

inline void store3(const glm::dvec3& v, double out[3]) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

// The record the core hands back is the one `pack` wrote (16-byte aligned).
template <class Record>
const Record& record_of(const void* record) {
  return *static_cast<const Record*>(record);
}

// A number as the shortest text that reads back to the same double
// ("1", "0.1", "1e+07"), for error messages.
struct NumberText {
  char text[32];
};
inline NumberText format_number(double x) {
  NumberText out{};
  auto result = std::to_chars(out.text, out.text + sizeof(out.text) - 1, x);
  *result.ptr = '\0';
  return out;
}

// Fills `err` (field name and printf-style message) and returns 1, the
// value `validate` reports a failure with.
__attribute__((format(printf, 3, 4))) inline int fail(PrismError* err, const char* field, const char* format, ...) {
  std::snprintf(err->field, sizeof(err->field), "%s", field);
  va_list args;
  va_start(args, format);
  std::vsnprintf(err->message, sizeof(err->message), format, args);
  va_end(args);
  return 1;
}

// A required length (or `count` of them), each > 0 and |x| <= 1e7.
constexpr PrismField positive_length(const char* name, uint32_t count, const char* doc) {
  return PrismField{name,
                    count == 1 ? uint32_t{PRISM_FIELD_NUMBER} : uint32_t{PRISM_FIELD_ARRAY},
                    count,
                    PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH,
                    0.0,
                    kInf,
                    0.0,
                    nullptr,
                    doc};
}

// For plugins without cross-field rules.
inline int validate_nothing(const double*, PrismError*) { return 0; }

using IntersectFn = int (*)(const void*, const PrismRay*, double, double, PrismHit*);
using RefineFn = void (*)(const void*, const PrismRayExt*, PrismHit*);
using OccludedFn = int (*)(const void*, const PrismRay*, double, double);
using SurfaceFn = void (*)(const void*, const PrismRay*, const PrismHit*, PrismSurface*);
using BoundingSphereFn = int (*)(const void*, double*, double*);

// intersect_batch for plugins whose batch is just a loop over `intersect`.
template <IntersectFn Intersect>
void intersect_batch(const void* record, size_t count, const PrismRay* rays, const double* tmin,
                     const double* tmax, PrismHit* hits, uint8_t* found) {
  for (size_t i = 0; i < count; ++i) found[i] = Intersect(record, &rays[i], tmin[i], tmax[i], &hits[i]) ? 1 : 0;
}

// Lane `i` of a packet as a scalar ray.
inline PrismRay packet_lane(const PrismRayPacket& rays, unsigned i) {
  return PrismRay{{rays.origin[0][i], rays.origin[1][i], rays.origin[2][i]},
                  {rays.dir[0][i], rays.dir[1][i], rays.dir[2][i]}};
}

// The packet queries as a loop over the active lanes. `Intersect` is a
// template argument, so it is inlined into the loop: the packet costs one
// call through the plugin table instead of one per ray, and each lane gets
// exactly the scalar answer.
template <IntersectFn Intersect>
uint32_t intersect_packet(const void* record, const PrismRayPacket* rays, uint32_t active, PrismHit* hits) {
  uint32_t found = 0;
  for (uint32_t lanes = active; lanes != 0; lanes &= lanes - 1) {
    const unsigned i = unsigned(std::countr_zero(lanes));
    const PrismRay ray = packet_lane(*rays, i);
    if (Intersect(record, &ray, rays->tmin[i], rays->tmax[i], &hits[i])) found |= 1u << i;
  }
  return found;
}

// `occluded` from `intersect`: a hit with t < tmax.
template <IntersectFn Intersect>
int occluded_by_intersect(const void* record, const PrismRay* ray, double tmin, double tmax) {
  PrismHit hit;
  return Intersect(record, ray, tmin, tmax, &hit) && hit.t < tmax ? 1 : 0;
}

template <OccludedFn Occluded>
uint32_t occluded_packet(const void* record, const PrismRayPacket* rays, uint32_t active) {
  uint32_t blocked = 0;
  for (uint32_t lanes = active; lanes != 0; lanes &= lanes - 1) {
    const unsigned i = unsigned(std::countr_zero(lanes));
    const PrismRay ray = packet_lane(*rays, i);
    if (Occluded(record, &ray, rays->tmin[i], rays->tmax[i])) blocked |= 1u << i;
  }
  return blocked;
}

// A plugin's descriptor table from the parts that differ between plugins;
// the batch and packet queries are loops over `Intersect`. `glsl_source` defines
// `<glsl_prefix>_intersect` and `<glsl_prefix>_surface` (see primitive_abi.h);
// `refine` polishes ill-conditioned hits (prism/sdk/refine.hpp).
// `IntersectFloat` is the float32 entry (primitive_abi.h, version 4): a
// plugin written in the shared dialect passes both entries with
// PRISM_SHARED_INTERSECT (prism/sdk/shared_plugin.hpp); a hand-written one
// has no float instantiation, and its double `Intersect` stands in.
// `bounding_sphere` (version 5) is optional: without it the core uses the
// sphere around `bounds`. `Occluded` (version 6) is the occlusion test, by
// default `Intersect`'s hit below tmax; a plugin written in the shared
// dialect may pass its own with PRISM_SHARED_OCCLUDED.
template <IntersectFn Intersect, IntersectFn IntersectFloat = Intersect,
          OccludedFn Occluded = occluded_by_intersect<Intersect>, size_t FieldCount>
constexpr PrismPrimitiveDesc describe_primitive(const char* type_name, uint32_t flags,
                                                const PrismField (&fields)[FieldCount], uint32_t record_size,
                                                int (*validate)(const double*, PrismError*),
                                                void (*pack)(const double*, void*),
                                                int (*bounds)(const void*, double*, double*),
                                                void (*surface)(const void*, const PrismRay*, const PrismHit*,
                                                                PrismSurface*),
                                                const char* glsl_source = nullptr, const char* glsl_prefix = nullptr,
                                                RefineFn refine = nullptr, BoundingSphereFn bounding_sphere = nullptr) {
  return PrismPrimitiveDesc{PRISM_PRIMITIVE_ABI_VERSION,
                            sizeof(PrismPrimitiveDesc),
                            type_name,
                            "1.0.0",
                            flags,
                            uint32_t{FieldCount},
                            fields,
                            record_size,
                            0,
                            validate,
                            pack,
                            bounds,
                            Intersect,
                            intersect_batch<Intersect>,
                            surface,
                            glsl_source,
                            glsl_prefix,
                            refine,
                            intersect_packet<Intersect>,
                            occluded_packet<Occluded>,
                            IntersectFloat,
                            bounding_sphere,
                            Occluded};
}

// Fills a PrismSurface from local point, normal and uv.
inline void write_surface(PrismSurface* out, const glm::dvec3& point, const glm::dvec3& normal, double u, double v) {
  store3(point, out->point);
  store3(normal, out->normal);
  out->uv[0] = u;
  out->uv[1] = v;
}

// The value of `#define NAME <integer>` in a GLSL source, or -1 when absent;
// constexpr, so a plugin can static_assert that its GLSL record offsets are
// the ones its C++ `pack` writes:
//   static_assert(glsl_define(kPluginGlsl, "TORUS_MINOR") == offsetof(TorusRecord, minor) / 8);
constexpr long glsl_define(std::string_view source, std::string_view name) {
  // Plain index loops: string_view::find is not constant-evaluable under GCC's sanitizers.
  constexpr char directive[] = "#define ";
  const size_t directive_size = sizeof directive - 1;
  auto matches_at = [&](size_t at, const char* text, size_t n) {
    if (at + n > source.size()) return false;
    for (size_t i = 0; i < n; ++i)
      if (source[at + i] != text[i]) return false;
    return true;
  };
  for (size_t at = 0; at < source.size(); ++at) {
    if (!matches_at(at, directive, directive_size)) continue;
    size_t pos = at + directive_size;
    if (!matches_at(pos, name.data(), name.size())) continue;
    pos += name.size();
    if (pos >= source.size() || source[pos] != ' ') continue;
    while (pos < source.size() && source[pos] == ' ') ++pos;
    long value = 0;
    bool digits = false;
    for (; pos < source.size() && source[pos] >= '0' && source[pos] <= '9'; ++pos, digits = true)
      value = value * 10 + (source[pos] - '0');
    if (pos < source.size() && source[pos] == 'u') ++pos;
    if (digits && (pos == source.size() || source[pos] == '\n' || source[pos] == ' ')) return value;
  }
  return -1;
}

}  // namespace prism::sdk
