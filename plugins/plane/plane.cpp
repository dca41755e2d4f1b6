// Plane primitive: dot(normal, p - point) = 0, infinite and two-sided. Not
// TRANSFORMABLE: `point` and `normal` place it, so local == world and the
// spec's uv, which uses world P, is computed here directly.
//
// intersect and surface are written once, for the CPU and the GPU, in
// plane.shared.glsl (the numerics are described there); this file holds
// fields, pack, bounds and the long-double refine. m is normalised with
// prism::sdk::safe_normalize, so a normal such as (1e-300, 0, 0), which
// passes the non-zero check, still works.
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "plane.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "plane.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

// std430-friendly: four vec4s of doubles.
struct PlaneRecord {
  double point[4];   // w: uv_scale
  double normal[4];  // unit normal m
  double t1[4];      // spec tangent frame for uv
  double t2[4];
  double given_normal[4];  // `normal` as the file gives it, for refine (the GPU ignores it)
};
static_assert(sizeof(PlaneRecord) % 16 == 0);
static_assert(PLANE_POINT == offsetof(PlaneRecord, point) / sizeof(double));
static_assert(PLANE_UV_SCALE == offsetof(PlaneRecord, point) / sizeof(double) + 3);
static_assert(PLANE_NORMAL == offsetof(PlaneRecord, normal) / sizeof(double));
static_assert(PLANE_T1 == offsetof(PlaneRecord, t1) / sizeof(double));
static_assert(PLANE_T2 == offsetof(PlaneRecord, t2) / sizeof(double));

const double kDefaultUvScale[] = {1.0};

const PrismField kFields[] = {
    {"point", PRISM_FIELD_ARRAY, 3, PRISM_FIELD_REQUIRED | PRISM_FIELD_LENGTH, -kInf, kInf, 0.0, nullptr,
     "a point on the plane, in world coordinates"},
    {"normal", PRISM_FIELD_ARRAY, 3, PRISM_FIELD_REQUIRED | PRISM_FIELD_NONZERO, -kInf, kInf, 0.0, nullptr,
     "normal of the plane, any length; it also sets the uv axes"},
    {"uv_scale", PRISM_FIELD_NUMBER, 1, PRISM_FIELD_MIN_EXCLUSIVE, 0.0, kInf, 0.0, kDefaultUvScale,
     "texture coordinates per world unit along the plane"},
};

void pack(const double* values, void* record) {
  auto* rec = static_cast<PlaneRecord*>(record);
  *rec = PlaneRecord{};
  glm::dvec3 m = safe_normalize(load3(values + 3));
  // Spec: t1 = normalize(cross(|m.y| < 0.999 ? (0,1,0) : (1,0,0), m)), t2 = cross(m, t1).
  glm::dvec3 helper = std::abs(m.y) < 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  glm::dvec3 t1 = glm::normalize(glm::cross(helper, m));
  glm::dvec3 t2 = glm::cross(m, t1);
  store3(load3(values), rec->point);
  rec->point[3] = values[6];
  store3(m, rec->normal);
  store3(t1, rec->t1);
  store3(t2, rec->t2);
  store3(load3(values + 3), rec->given_normal);
}

int bounds(const void*, double*, double*) { return 0; }  // infinite

// dot(normal, p - point) in long double with the normal as given (its
// double normalisation would tilt the plane by an ulp; see prism/sdk/refine.hpp).
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const auto& rec = record_of<PlaneRecord>(record);
  const Vec3x normal = load3x(rec.given_normal), point = load3x(rec.point);
  polish_hit(*ray, *hit, [&](const Vec3x& p) { return ImplicitSample{dot(normal, p - point), normal}; });
}

const PrismPrimitiveDesc kDesc = describe_primitive<PRISM_SHARED_INTERSECT(plane_intersect)>(
    "plane", PRISM_PRIMITIVE_CONVEX, kFields, sizeof(PlaneRecord), validate_nothing, pack, bounds, f64::abi_surface<f64::plane_surface>,
    kPluginGlsl, "plane", refine);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
