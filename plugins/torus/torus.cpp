// Torus primitive: (|p|^2 + R^2 - r^2)^2 = 4 R^2 (p.x^2 + p.z^2), axis local
// y, 0 < r < R; the core applies `center` and `rotation`.
//
// intersect and surface are written once, for the CPU and the GPU, in
// torus.shared.glsl (its numerics, and why not a closed-form quartic, are
// described there); this file holds fields, validate, pack, bounds and the
// long-double refine.
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "torus.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "torus.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

struct TorusRecord {
  double major;  // R
  double minor;  // r
  double pad[2];
};
static_assert(sizeof(TorusRecord) % 16 == 0);
static_assert(TORUS_MAJOR == offsetof(TorusRecord, major) / sizeof(double));
static_assert(TORUS_MINOR == offsetof(TorusRecord, minor) / sizeof(double));

const PrismField kFields[] = {
    positive_length("major_radius", 1, "R: distance from the local y axis to the centre circle of the tube"),
    positive_length("minor_radius", 1, "r: radius of the tube; must be < major_radius"),
};

int validate(const double* values, PrismError* err) {
  if (values[1] < values[0]) return 0;
  return fail(err, "minor_radius", "must be < major_radius (%s), got %s", format_number(values[0]).text,
              format_number(values[1]).text);
}

void pack(const double* values, void* record) {
  *static_cast<TorusRecord*>(record) = TorusRecord{values[0], values[1], {0.0, 0.0}};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  const auto& rec = record_of<TorusRecord>(record);
  double outer = rec.major + rec.minor;
  const double extent[3] = {outer, rec.minor, outer};
  for (int i = 0; i < 3; ++i) {
    lo[i] = -extent[i];
    hi[i] = extent[i];
  }
  return 1;
}

// Every point lies within major + minor of the centre.
int bounding_sphere(const void* record, double center[3], double* radius) {
  const auto& rec = record_of<TorusRecord>(record);
  store3(glm::dvec3(0.0), center);
  *radius = rec.major + rec.minor;
  return 1;
}

// The signed distance from the tube, sqrt((rho - R)^2 + y^2) - r with rho the
// distance from the y axis, in long double (see prism/sdk/refine.hpp): it
// stays well scaled for thin tubes, where the quartic's value does not.
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const auto& rec = record_of<TorusRecord>(record);
  const long double major = rec.major, minor = rec.minor;
  auto tube_distance = [&](const Vec3x& p) {
    const long double rho = std::sqrt(p.x * p.x + p.z * p.z), off = rho - major;
    const long double q = std::sqrt(off * off + p.y * p.y);
    return ImplicitSample{q - minor, {off * p.x / (rho * q), p.y / q, off * p.z / (rho * q)}};
  };
  Vec3x p;
  if (polish_hit(*ray, *hit, tube_distance, &p)) store3(p, hit->data);
}

const PrismPrimitiveDesc kDesc = describe_primitive<PRISM_SHARED_INTERSECT(torus_intersect), PRISM_SHARED_OCCLUDED(torus_occluded)>(
    "torus", PRISM_PRIMITIVE_TRANSFORMABLE, kFields, sizeof(TorusRecord), validate, pack, bounds,
    f64::abi_surface<f64::torus_surface>, kPluginGlsl, "torus", refine, bounding_sphere);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
