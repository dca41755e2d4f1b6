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
// GPU: cylinder.glsl runs the core module core/glsl/quadric.glsl, the GLSL
// double port of that code shared with quadric and cone; the record offsets
// the module reads are static_asserted below.
#include "prism/sdk/axial_quadric.hpp"
#include "cylinder.glsl.hpp"
#include "quadric.glsl.hpp"  // kQuadricModuleGlsl: core/glsl/quadric.glsl, which cylinder.glsl requires

namespace {

using namespace prism::sdk;

static_assert(quadric_module_matches_records(kQuadricModuleGlsl));

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

const PrismPrimitiveDesc kDesc = describe_axial_quadric("cylinder", kFields, pack, refine, kPluginGlsl, "cylinder");

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
