// Sphere primitive: |p| = radius in the local frame; the core applies
// `center` and `rotation` (TRANSFORMABLE), so they are not fields here.
//
// Numerics
// - intersect: prism::sdk::intersect_sphere, the same routine the core uses
//   for light spheres. It moves the origin to the foot of the perpendicular
//   from the centre and uses the discriminant r^2 - |f - (f.d)d|^2 (Ray
//   Tracing Gems ch. 7), which does not cancel for far or small spheres; the
//   roots t_f -+ sqrt(disc) then need no further care.
// - surface: the point is re-formed from that foot (so its error is ~eps*r
//   plus the rounding of t itself, not eps*|origin|) and re-projected onto
//   the sphere with p *= r/|p| (pbrt-v4), far inside the spec's offset.
// - GPU: sphere.glsl, the same method in GLSL double precision.
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/sphere_math.hpp"
#include "sphere.glsl.hpp"

namespace {

using namespace prism::sdk;

struct SphereRecord {
  double radius;
  double pad;
};
static_assert(sizeof(SphereRecord) % 16 == 0);
static_assert(glsl_define(kPluginGlsl, "SPHERE_RADIUS") == offsetof(SphereRecord, radius) / sizeof(double));

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

int intersect(const void* record, const PrismRay* ray, double tmin, double tmax, PrismHit* hit) {
  double t = 0.0;
  double r = record_of<SphereRecord>(record).radius;
  if (!intersect_sphere(load3(ray->origin), load3(ray->dir), r, tmin, tmax, t)) return 0;
  *hit = PrismHit{};
  hit->t = t;
  return 1;
}

// |p|^2 - r^2 in long double (see prism/sdk/refine.hpp).
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const long double r = record_of<SphereRecord>(record).radius;
  polish_hit(*ray, *hit, [r](const Vec3x& p) { return ImplicitSample{dot(p, p) - r * r, 2 * p}; });
}

void surface(const void* record, const PrismRay* ray, const PrismHit* hit, PrismSurface* out) {
  double r = record_of<SphereRecord>(record).radius;
  glm::dvec3 o = load3(ray->origin), d = load3(ray->dir);
  double tf = foot_parameter(o, d);
  glm::dvec3 p = (o + tf * d) + (hit->t - tf) * d;
  double len = glm::length(p);
  if (len > 0.0) p *= r / len;
  double u = turn_fraction(p.z, p.x);
  double v = 0.5 - safe_asin(p.y / r) / kPi;
  write_surface(out, p, p / r, u, v);
}

const PrismPrimitiveDesc kDesc = describe_primitive<intersect>("sphere", PRISM_PRIMITIVE_TRANSFORMABLE, kFields,
                                                       sizeof(SphereRecord), validate_nothing, pack, bounds, surface,
                                                       kPluginGlsl, "sphere", refine);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
