// Cylinder primitive: the quadric [1,0,1,0,0,0,0,0,0,-radius^2] clipped to
// 0 <= y <= height, an open tube around local y; the core applies `center`
// and `rotation`. uv: u = 0.5 + atan2(z, x)/2pi, v = y/height.
//
// Numerics: none of its own. The record begins with the QuadricShape the
// spec says the cylinder stands for, and intersect/point/normal are the
// quadric plugin's code (prism/sdk/quadric_math.hpp): origin re-centred to
// the foot of the perpendicular, stable roots, clip test on the point formed
// in that frame, one Newton step onto the surface. So t and N are
// bit-identical to those of the equivalent `quadric` object.
//
// intersect and surface are written once, for the CPU and the GPU, in
// cylinder.shared.glsl; this file holds fields, pack and the long-double refine.
#include "prism/sdk/axial_quadric.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "cylinder.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "cylinder.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

const PrismField kFields[] = {
    positive_length("radius", 1, "radius of the open tube around the local y axis"),
    positive_length("height", 1, "length of the tube, which spans 0 <= y <= height"),
};

void pack(const double* values, void* record) {
  const double radius = values[0], height = values[1];
  const double coef[10] = {1, 0, 1, 0, 0, 0, 0, 0, 0, -(radius * radius)};
  pack_axial_quadric(coef, radius, height, record);
}

void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const long double radius = record_of<AxialQuadricRecord>(record).radius;
  polish_axial_quadric_hit(0, -(radius * radius), ray, hit);
}

const PrismPrimitiveDesc kDesc = describe_axial_quadric<PRISM_SHARED_INTERSECT(cylinder_intersect), f64::abi_surface<f64::cylinder_surface>>(
    "cylinder", kFields, pack, refine, kPluginGlsl, "cylinder");

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
