// Cone primitive: the quadric [1,-(radius/height)^2,1,0,0,0,0,0,0,0] clipped
// to 0 <= y <= height: open, apex at the origin, axis local y; the core
// applies `center` and `rotation`. uv: u = 0.5 + atan2(z, x)/2pi,
// v = y/height. At the apex the gradient is 0: the normal is all zeros and
// the core uses -dir.
//
// Numerics: none of its own; see prism/sdk/axial_quadric.hpp. t and N are
// bit-identical to those of the equivalent `quadric` object.
#include "prism/sdk/axial_quadric.hpp"

namespace {

using namespace prism::sdk;

const PrismField kFields[] = {
    positive_length("radius", 1, "radius of the open end at y = height"),
    positive_length("height", 1, "apex at y = 0, open end at y = height"),
};

void pack(const double* values, void* record) {
  const double radius = values[0], height = values[1];
  const double slope = radius / height;
  const double coef[10] = {1, -(slope * slope), 1, 0, 0, 0, 0, 0, 0, 0};
  pack_axial_quadric(coef, radius, height, record);
}

const PrismPrimitiveDesc kDesc = describe_axial_quadric("cone", kFields, pack);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
