// Ring primitive: the disk inner <= |p| <= outer in the local xz-plane, zero
// thickness, visible from both sides; the core applies `center` and
// `rotation`. inner_radius = 0 gives a full disk.
//
// intersect and surface are written once, for the CPU and the GPU, in
// ring.shared.glsl (the numerics are described there); this file holds
// fields, validate, pack, bounds and the long-double refine.
#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "ring.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "ring.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

struct RingRecord {
  double inner;
  double outer;
  double pad[2];
};
static_assert(sizeof(RingRecord) % 16 == 0);
static_assert(RING_INNER == offsetof(RingRecord, inner) / sizeof(double));
static_assert(RING_OUTER == offsetof(RingRecord, outer) / sizeof(double));

const double kDefaultInner[] = {0.0};

const PrismField kFields[] = {
    {"inner_radius", PRISM_FIELD_NUMBER, 1, PRISM_FIELD_LENGTH, 0.0, kInf, 0.0, kDefaultInner,
     "radius of the hole; 0 makes a full disc"},
    positive_length("outer_radius", 1, "radius of the outer edge; must be > inner_radius"),
};

int validate(const double* values, PrismError* err) {
  if (values[1] > values[0]) return 0;
  return fail(err, "outer_radius", "must be > inner_radius (%s), got %s", format_number(values[0]).text,
              format_number(values[1]).text);
}

void pack(const double* values, void* record) {
  *static_cast<RingRecord*>(record) = RingRecord{values[0], values[1], {0.0, 0.0}};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  double outer = record_of<RingRecord>(record).outer;
  const double extent[3] = {outer, 0.0, outer};
  for (int i = 0; i < 3; ++i) {
    lo[i] = -extent[i];
    hi[i] = extent[i];
  }
  return 1;
}

// The annulus lies in the disc of the outer radius.
int bounding_sphere(const void* record, double center[3], double* radius) {
  store3(glm::dvec3(0.0), center);
  *radius = record_of<RingRecord>(record).outer;
  return 1;
}

// The plane y = 0 in long double (see prism/sdk/refine.hpp).
void refine(const void*, const PrismRayExt* ray, PrismHit* hit) {
  Vec3x p;
  if (!polish_hit(*ray, *hit, [](const Vec3x& q) { return ImplicitSample{q.y, {0, 1, 0}}; }, &p)) return;
  p.y = 0;
  store3(p, hit->data);
}

const PrismPrimitiveDesc kDesc = describe_primitive<PRISM_SHARED_INTERSECT(ring_intersect)>(
    "ring", PRISM_PRIMITIVE_TRANSFORMABLE | PRISM_PRIMITIVE_CONVEX, kFields, sizeof(RingRecord), validate, pack, bounds,
    f64::abi_surface<f64::ring_surface>, kPluginGlsl, "ring", refine, bounding_sphere);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
