// Capsule primitive, an example plugin built outside the Prism tree against
// the installed package (find_package(Prism), prism_add_primitive_plugin).
//
// Local shape: every point within `radius` of the segment from (0,0,0) to
// (0,height,0): a tube around local y capped by two hemispheres, a closed
// solid visible from inside too. The core applies `center` and `rotation`
// (TRANSFORMABLE), so they are not fields here.
//
//   outward normal  p - (0, clamp(p.y, 0, height), 0): from the nearest
//                   point of the segment, so the tube and the caps meet
//                   without a seam in N
//   u               0.5 + atan2(p.z, p.x)/2pi (as sphere and cylinder)
//   v               arc length along the meridian from the bottom pole
//                   (0, -radius, 0) over its whole length pi*radius + height:
//                   0 at the bottom pole, pi*radius/2 / (pi*radius + height)
//                   where the tube begins, 1 at the top pole (0, height + radius, 0)
//
// intersect and surface are written once, for the CPU and the GPU, in
// capsule.shared.glsl (the numerics are described there). This file holds
// what only the CPU has: the fields, the cross-field rule, pack, bounds,
// the long-double refine (Newton on the signed distance to the segment
// minus radius, prism/sdk/refine.hpp) and the entry point.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "capsule.shared.glsl.hpp"  // kPluginGlsl, generated from capsule.shared.glsl by prism_add_primitive_plugin
#include "prism/primitive_abi.h"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/refine.hpp"
#include "prism/sdk/shared_plugin.hpp"

// capsule.shared.glsl compiled as C++: prism::sdk::f64::capsule_intersect in
// double, prism::sdk::f32::capsule_intersect in float, and so on.
#define PRISM_SHARED_SOURCE "capsule.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

// std430-friendly: doubles only, a multiple of 16 bytes. The shared source
// names the offsets (#define CAPSULE_RADIUS 0, ...).
struct CapsuleRecord {
  double radius;
  double height;
  double pad[2];
};
static_assert(sizeof(CapsuleRecord) % 16 == 0);
static_assert(CAPSULE_RADIUS == offsetof(CapsuleRecord, radius) / sizeof(double));
static_assert(CAPSULE_HEIGHT == offsetof(CapsuleRecord, height) / sizeof(double));

const PrismField kFields[] = {
    positive_length("radius", 1, "distance of the surface from the axis segment"),
    positive_length("height", 1, "length of the axis segment: the cap centres are (0,0,0) and (0,height,0)"),
};

// The example's cross-field rule (the core checks each field on its own
// first, and prefixes the JSON path: "objects[2].height: ...").
constexpr double kMaxAspect = 1e6;

int validate(const double* values, PrismError* err) {
  const double radius = values[0], height = values[1];
  if (height <= kMaxAspect * radius) return 0;
  return fail(err, "height", "must be <= 1e6 * radius (%s), got %s", format_number(kMaxAspect * radius).text,
              format_number(height).text);
}

void pack(const double* values, void* record) {
  *static_cast<CapsuleRecord*>(record) = CapsuleRecord{values[0], values[1], {0.0, 0.0}};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  const auto& rec = record_of<CapsuleRecord>(record);
  store3(glm::dvec3(-rec.radius, -rec.radius, -rec.radius), lo);
  store3(glm::dvec3(rec.radius, rec.height + rec.radius, rec.radius), hi);
  return 1;
}

// Optional (ABI 5): the capsule's own bounding sphere, centred halfway up
// the segment, radius half the height plus the radius.
int bounding_sphere(const void* record, double center[3], double* radius) {
  const auto& rec = record_of<CapsuleRecord>(record);
  store3(glm::dvec3(0.0, 0.5 * rec.height, 0.0), center);
  *radius = 0.5 * rec.height + rec.radius;
  return 1;
}

// Signed distance to the segment minus radius, in long double: value and
// unit gradient (see prism/sdk/refine.hpp). Smooth across the seams.
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const auto& rec = record_of<CapsuleRecord>(record);
  const long double r = rec.radius, height = rec.height;
  polish_hit(*ray, *hit, [r, height](const Vec3x& p) {
    const long double yc = std::clamp(p.y, 0.0L, height);
    const Vec3x radial{p.x, p.y - yc, p.z};
    const long double len = std::sqrt(dot(radial, radial));
    return ImplicitSample{len - r, (1.0L / len) * radial};
  });
}

// intersect and intersect_float: the double and float instantiations of
// capsule_intersect; surface: the double one of capsule_surface.
const PrismPrimitiveDesc kDesc = describe_primitive<PRISM_SHARED_INTERSECT(capsule_intersect)>(
    "capsule", PRISM_PRIMITIVE_TRANSFORMABLE, kFields, sizeof(CapsuleRecord), validate, pack, bounds,
    f64::abi_surface<f64::capsule_surface>, kPluginGlsl, "capsule", refine, bounding_sphere);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
