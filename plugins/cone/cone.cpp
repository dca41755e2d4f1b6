// Cone primitive: the quadric [1,-(radius/height)^2,1,0,0,0,0,0,0,0] clipped
// to 0 <= y <= height: open, apex at the origin, axis local y; the core
// applies `center` and `rotation`. uv: u = 0.5 + atan2(z, x)/2pi,
// v = y/height. At the apex the gradient is 0: the normal is all zeros and
// the core uses -dir.
//
// Numerics: none of its own. The record begins with the QuadricShape the
// spec says the cone stands for, and intersect/point/normal are the
// quadric plugin's code (prism/sdk/quadric_math.hpp): origin re-centred to
// the foot of the perpendicular, stable roots, clip test on the point formed
// in that frame, one Newton step onto the surface. So t and N are
// bit-identical to those of the equivalent `quadric` object.
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/quadric_math.hpp"

namespace {

using namespace prism::sdk;

struct ConeRecord {
  QuadricShape shape;  // first, so intersect_quadric_record reads it
  double radius;
  double height;
  double pad[2];
};
static_assert(sizeof(ConeRecord) % 16 == 0);

const PrismField kFields[] = {
    positive_length("radius", 1, "radius of the open end at y = height"),
    positive_length("height", 1, "apex at y = 0, open end at y = height"),
};

void pack(const double* values, void* record) {
  double radius = values[0], height = values[1];
  double slope = radius / height;
  const double coef[10] = {1, -(slope * slope), 1, 0, 0, 0, 0, 0, 0, 0};
  const double lo[3] = {-kInf, 0.0, -kInf}, hi[3] = {kInf, height, kInf};
  *static_cast<ConeRecord*>(record) = ConeRecord{make_quadric(coef, lo, hi), radius, height, {0.0, 0.0}};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  const auto& rec = record_of<ConeRecord>(record);
  const double low[3] = {-rec.radius, 0.0, -rec.radius}, high[3] = {rec.radius, rec.height, rec.radius};
  for (int i = 0; i < 3; ++i) {
    lo[i] = low[i];
    hi[i] = high[i];
  }
  return 1;
}

void surface(const void* record, const PrismRay*, const PrismHit* hit, PrismSurface* out) {
  glm::dvec3 point, normal;
  quadric_record_surface(record, hit, point, normal);
  double height = record_of<ConeRecord>(record).height;
  write_surface(out, point, normal, turn_fraction(point.z, point.x), point.y / height);
}

const PrismPrimitiveDesc kDesc = describe_primitive<intersect_quadric_record>("cone", PRISM_PRIMITIVE_TRANSFORMABLE, kFields,
                                                       sizeof(ConeRecord), validate_nothing, pack, bounds, surface);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
