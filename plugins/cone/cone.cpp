// Cone primitive: the quadric [1,-(radius/height)^2,1,0,0,0,0,0,0,0] clipped
// to 0 <= y <= height: open, apex at the origin, axis local y; the core
// applies `center` and `rotation`. uv: u = 0.5 + atan2(z, x)/2pi,
// v = y/height. At the apex the gradient is 0: the normal is all zeros and
// the core uses -dir.
//
// Numerics: none of its own; see prism/sdk/axial_quadric.hpp. t and N are
// bit-identical to those of the equivalent `quadric` object.
//
// intersect and surface are written once, for the CPU and the GPU, in
// cone.shared.glsl; this file holds fields, pack and the long-double refine.
#include "prism/sdk/axial_quadric.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "cone.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "cone.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

const PrismField kFields[] = {
    positive_length("radius", 1, "radius of the open end, at y = height"),
    positive_length("height", 1, "the apex is at the local origin, the open end at y = height"),
};

void pack(const double* values, void* record) {
  const double radius = values[0], height = values[1];
  const double slope = radius / height;
  const double coef[10] = {1, -(slope * slope), 1, 0, 0, 0, 0, 0, 0, 0};
  pack_axial_quadric(coef, radius, height, record);
}

void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const auto& rec = record_of<AxialQuadricRecord>(record);
  const long double slope = static_cast<long double>(rec.radius) / rec.height;
  polish_axial_quadric_hit(-(slope * slope), 0, ray, hit);
}

const PrismPrimitiveDesc kDesc = describe_axial_quadric<PRISM_SHARED_INTERSECT(cone_intersect), f64::abi_surface<f64::cone_surface>>(
    "cone", kFields, pack, refine, kPluginGlsl, "cone");

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
