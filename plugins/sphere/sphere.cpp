// Sphere primitive: |p| = radius in the local frame; the core applies
// `center` and `rotation` (TRANSFORMABLE), so they are not fields here.
//
// intersect and surface are written once, for the CPU and the GPU, in
// sphere.shared.glsl (the numerics are described there); this file holds
// what only the CPU has: fields, pack, bounds and the long-double refine.
#include "prism/primitive_abi.h"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "sphere.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "sphere.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

struct SphereRecord {
  double radius;
  double pad;
};
static_assert(sizeof(SphereRecord) % 16 == 0);
static_assert(SPHERE_RADIUS == offsetof(SphereRecord, radius) / sizeof(double));

const PrismField kFields[] = {positive_length("radius", 1, "radius of the sphere, centred on the local origin")};

void pack(const double* values, void* record) {
  auto* rec = static_cast<SphereRecord*>(record);
  *rec = SphereRecord{values[0], 0.0};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  double r = record_of<SphereRecord>(record).radius;
  for (int i = 0; i < 3; ++i) {
    lo[i] = -r;
    hi[i] = r;
  }
  return 1;
}

// The sphere itself.
int bounding_sphere(const void* record, double center[3], double* radius) {
  store3(glm::dvec3(0.0), center);
  *radius = record_of<SphereRecord>(record).radius;
  return 1;
}

// |p|^2 - r^2 in long double (see prism/sdk/refine.hpp).
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const long double r = record_of<SphereRecord>(record).radius;
  polish_hit(*ray, *hit, [r](const Vec3x& p) { return ImplicitSample{dot(p, p) - r * r, 2 * p}; });
}

const PrismPrimitiveDesc kDesc = describe_primitive<PRISM_SHARED_INTERSECT(sphere_intersect)>(
    "sphere", PRISM_PRIMITIVE_TRANSFORMABLE | PRISM_PRIMITIVE_CONVEX, kFields, sizeof(SphereRecord), validate_nothing, pack, bounds,
    f64::abi_surface<f64::sphere_surface>, kPluginGlsl, "sphere", refine, bounding_sphere);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
