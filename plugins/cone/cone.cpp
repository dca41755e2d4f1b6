// Cone primitive: the quadric [1,-(radius/height)^2,1,0,0,0,0,0,0,0] clipped
// to 0 <= y <= height: open, apex at the origin, axis local y; the core
// applies `center` and `rotation`. uv: u = 0.5 + atan2(z, x)/2pi,
// v = y/height. At the apex the gradient is 0: the normal is all zeros and
// the core uses -dir.
//
// Numerics: none of its own; see prism/sdk/axial_quadric.hpp. t and N are
// bit-identical to those of the equivalent `quadric` object.
//
// GPU: cone.glsl runs the core module core/glsl/quadric.glsl, the GLSL
// double port of that code shared with quadric and cylinder; the record
// offsets the module reads are static_asserted below.
#include "prism/sdk/axial_quadric.hpp"
#include "cone.glsl.hpp"
#include "quadric.glsl.hpp"  // kQuadricModuleGlsl: core/glsl/quadric.glsl, which cone.glsl requires

namespace {

using namespace prism::sdk;

static_assert(quadric_module_matches_records(kQuadricModuleGlsl));

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

const PrismPrimitiveDesc kDesc = describe_axial_quadric("cone", kFields, pack, refine, kPluginGlsl, "cone");

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
