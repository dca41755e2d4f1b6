// Box primitive: |p.x| <= hx, |p.y| <= hy, |p.z| <= hz in the local frame;
// the core applies `center` and `rotation`.
//
// intersect and surface are written once, for the CPU and the GPU, in
// box.shared.glsl (the numerics are described there); this file holds
// fields, pack, bounds and the long-double refine.
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "box.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "box.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

struct BoxRecord {
  double half[4];  // hx, hy, hz, unused
};
static_assert(sizeof(BoxRecord) % 16 == 0);
static_assert(BOX_HALF == offsetof(BoxRecord, half) / sizeof(double));

const PrismField kFields[] = {positive_length("half_size", 3, "half of the size along local x, y and z; the box is centred on the local origin")};

void pack(const double* values, void* record) {
  auto* rec = static_cast<BoxRecord*>(record);
  *rec = BoxRecord{{values[0], values[1], values[2], 0.0}};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  const auto& rec = record_of<BoxRecord>(record);
  for (int i = 0; i < 3; ++i) {
    lo[i] = -rec.half[i];
    hi[i] = rec.half[i];
  }
  return 1;
}

// The plane of the face `intersect` found (axis hit->part, on the side of
// the hit point), in long double (see prism/sdk/refine.hpp).
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const int axis = static_cast<int>(hit->part);
  const long double side = std::signbit(hit->data[axis]) ? -1.0L : 1.0L;
  const long double h = record_of<BoxRecord>(record).half[axis];
  Vec3x normal;
  (axis == 0 ? normal.x : axis == 1 ? normal.y : normal.z) = side;
  Vec3x p;
  if (polish_hit(*ray, *hit, [&](const Vec3x& q) { return ImplicitSample{dot(normal, q) - h, normal}; }, &p))
    store3(p, hit->data);
}

const PrismPrimitiveDesc kDesc = describe_primitive<PRISM_SHARED_INTERSECT(box_intersect)>(
    "box", PRISM_PRIMITIVE_TRANSFORMABLE | PRISM_PRIMITIVE_CONVEX, kFields, sizeof(BoxRecord), validate_nothing, pack, bounds,
    f64::abi_surface<f64::box_surface>, kPluginGlsl, "box", refine);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
