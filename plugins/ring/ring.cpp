// Ring primitive: the disk inner <= |p| <= outer in the local xz-plane, zero
// thickness, visible from both sides; the core applies `center` and
// `rotation`. inner_radius = 0 gives a full disk.
//
// Numerics
// - intersect: the origin is moved to the foot of the perpendicular from the
//   centre first; then s = -o.y / d.y (d.y == 0 exactly: parallel, a miss)
//   and the hit point o + s d is formed in that frame, so its error is
//   ~eps * |ring| rather than eps * |origin| for a camera 1e4 away, and the
//   inner/outer test (inclusive, on sqrt(x^2 + z^2) as the spec states it)
//   is decided on an accurate point.
// - surface: the stored point with y set to exactly 0.
// - GPU: ring.glsl, the same method in GLSL double precision.
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "ring.glsl.hpp"

namespace {

using namespace prism::sdk;

struct RingRecord {
  double inner;
  double outer;
  double pad[2];
};
static_assert(sizeof(RingRecord) % 16 == 0);
static_assert(glsl_define(kPluginGlsl, "RING_INNER") == offsetof(RingRecord, inner) / sizeof(double));
static_assert(glsl_define(kPluginGlsl, "RING_OUTER") == offsetof(RingRecord, outer) / sizeof(double));

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

int intersect(const void* record, const PrismRay* ray, double tmin, double tmax, PrismHit* hit) {
  const auto& rec = record_of<RingRecord>(record);
  glm::dvec3 o = load3(ray->origin), d = load3(ray->dir);
  if (d.y == 0.0) return 0;
  double tf = foot_parameter(o, d);
  glm::dvec3 of = o + tf * d;
  double s = -of.y / d.y;
  double t = tf + s;
  if (!(t > tmin && t <= tmax)) return 0;
  glm::dvec3 p = of + s * d;
  p.y = 0.0;
  double radius = std::sqrt(p.x * p.x + p.z * p.z);
  if (!(radius >= rec.inner && radius <= rec.outer)) return 0;
  *hit = PrismHit{};
  hit->t = t;
  store3(p, hit->data);
  return 1;
}

// The plane y = 0 in long double (see prism/sdk/refine.hpp).
void refine(const void*, const PrismRayExt* ray, PrismHit* hit) {
  Vec3x p;
  if (!polish_hit(*ray, *hit, [](const Vec3x& q) { return ImplicitSample{q.y, {0, 1, 0}}; }, &p)) return;
  p.y = 0;
  store3(p, hit->data);
}

void surface(const void* record, const PrismRay*, const PrismHit* hit, PrismSurface* out) {
  const auto& rec = record_of<RingRecord>(record);
  glm::dvec3 p = load3(hit->data);
  double radius = std::sqrt(p.x * p.x + p.z * p.z);
  double u = (radius - rec.inner) / (rec.outer - rec.inner);
  write_surface(out, p, glm::dvec3(0.0, 1.0, 0.0), u, turn_fraction(p.z, p.x));
}

const PrismPrimitiveDesc kDesc = describe_primitive<intersect>("ring", PRISM_PRIMITIVE_TRANSFORMABLE, kFields,
                                                       sizeof(RingRecord), validate, pack, bounds, surface,
                                                       kPluginGlsl, "ring", refine);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
