// Capsule primitive, an example plugin built outside the Prism tree against
// the installed package (find_package(Prism), prism_add_primitive_plugin).
//
// Local shape: every point within `radius` of the segment from (0,0,0) to
// (0,height,0): a tube around local y capped by two hemispheres, a closed
// solid visible from inside too. The core applies `center` and `rotation`
// (TRANSFORMABLE), so they are not fields here.
//
//   outward normal  p - (0, clamp(p.y, 0, height), 0): from the nearest
//                   point of the segment, so the tube and the caps meet
//                   without a seam in N
//   u               0.5 + atan2(p.z, p.x)/2pi (as sphere and cylinder)
//   v               arc length along the meridian from the bottom pole
//                   (0, -radius, 0) over its whole length pi*radius + height:
//                   0 at the bottom pole, pi*radius/2 / (pi*radius + height)
//                   where the tube begins, 1 at the top pole (0, height + radius, 0)
//
// Numerics
// - intersect: the solid is the union of a finite tube and two balls; it is
//   convex, so a ray's line meets it in one interval, whose ends are the
//   smallest entry and the largest exit over the three pieces. So no point
//   is ever classified as "tube" or "cap" (no pin-holes along the seams):
//   a tube interval cut a rounding short at y = 0 or y = height is covered
//   by the ball there. Everything is solved in a frame re-centred at the
//   foot of the perpendicular from the capsule's middle (0, height/2, 0),
//   so a camera 1e6 away works with numbers of the capsule's size (Wald,
//   Ray Tracing Gems II ch. 34). Balls: the robust discriminant
//   r^2 - |g - (g.d)d|^2 (Ray Tracing Gems ch. 7), as the sphere plugin.
//   Tube: the same discriminant in the xz-plane (the closest approach of the
//   projected line), roots by the stable pair c/q, q/a; a == 0 exactly (a
//   ray along the axis) meets the tube everywhere or nowhere.
// - surface: the point is re-formed from that foot and re-projected onto the
//   surface radially from its nearest axis point (pbrt-v4's p *= r/|p|).
// - refine: Newton on the signed distance to the segment minus radius, in
//   long double (prism/sdk/refine.hpp).
// - GPU: capsule.glsl, the same method in GLSL double precision.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "capsule.glsl.hpp"  // kPluginGlsl, generated from capsule.glsl by prism_add_primitive_plugin
#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/refine.hpp"

namespace {

using namespace prism::sdk;

// std430-friendly: doubles only, a multiple of 16 bytes.
struct CapsuleRecord {
  double radius;
  double height;
  double pad[2];
};
static_assert(sizeof(CapsuleRecord) % 16 == 0);
static_assert(glsl_define(kPluginGlsl, "CAPSULE_RADIUS") == offsetof(CapsuleRecord, radius) / sizeof(double));
static_assert(glsl_define(kPluginGlsl, "CAPSULE_HEIGHT") == offsetof(CapsuleRecord, height) / sizeof(double));

// PrismHit::part: which piece the hit lies on. For information only:
// `surface` finds the nearest axis point itself, so `refine` need not keep
// it up to date.
enum Part : uint32_t { kTube = 0, kBottomCap = 1, kTopCap = 2 };

const PrismField kFields[] = {
    positive_length("radius", 1, "distance of the surface from the axis segment"),
    positive_length("height", 1, "length of the axis segment: the cap centres are (0,0,0) and (0,height,0)"),
};

// The example's cross-field rule (the core checks each field on its own
// first, and prefixes the JSON path: "objects[2].height: ...").
constexpr double kMaxAspect = 1e6;

int validate(const double* values, PrismError* err) {
  const double radius = values[0], height = values[1];
  if (height <= kMaxAspect * radius) return 0;
  return fail(err, "height", "must be <= 1e6 * radius (%s), got %s", format_number(kMaxAspect * radius).text,
              format_number(height).text);
}

void pack(const double* values, void* record) {
  *static_cast<CapsuleRecord*>(record) = CapsuleRecord{values[0], values[1], {0.0, 0.0}};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  const auto& rec = record_of<CapsuleRecord>(record);
  store3(glm::dvec3(-rec.radius, -rec.radius, -rec.radius), lo);
  store3(glm::dvec3(rec.radius, rec.height + rec.radius, rec.radius), hi);
  return 1;
}

// The union of the pieces' intervals along the line f + s d (s from the foot).
struct Span {
  double in = kInf, out = -kInf;
  uint32_t in_part = kTube, out_part = kTube;

  void merge(double s_in, double s_out, uint32_t part) {
    if (!(s_in <= s_out)) return;  // empty (or NaN)
    if (s_in < in) {
      in = s_in;
      in_part = part;
    }
    if (s_out > out) {
      out = s_out;
      out_part = part;
    }
  }
};

// Ball of radius r centred at f - g (g: the line's point f seen from the
// centre): s = -g.d -+ sqrt(r^2 - |g - (g.d)d|^2), d unit.
bool ball(const glm::dvec3& g, const glm::dvec3& d, double r, double& s_in, double& s_out) {
  const double b = glm::dot(g, d);
  const glm::dvec3 perp = g - b * d;
  const double disc = r * r - glm::dot(perp, perp);
  if (!(disc >= 0.0)) return false;
  const double h = std::sqrt(disc);
  s_in = -b - h;
  s_out = -b + h;
  return true;
}

// Tube x^2 + z^2 <= r^2 cut to |y| <= half_height (frame centred on the capsule).
// With a = |d_xz|^2, b' = f_xz.d_xz and c = |f_xz|^2 - r^2 the roots solve
// a s^2 + 2 b' s + c = 0; its discriminant b'^2 - a c equals
// a (r^2 - |perp|^2), perp the projected line's closest approach to the
// axis, which does not cancel for far or near-tangent rays. The roots are
// the stable pair c/q, q/a with q = -(b' + sign(b') sqrt(disc)).
bool tube(const glm::dvec3& f, const glm::dvec3& d, double r, double half_height, double& s_in, double& s_out) {
  const double a = d.x * d.x + d.z * d.z;
  const double c = f.x * f.x + f.z * f.z - r * r;
  double lo = -kInf, hi = kInf;
  if (a == 0.0) {
    if (!(c <= 0.0)) return false;  // parallel to the axis, outside the tube
  } else {
    const double bh = f.x * d.x + f.z * d.z;
    const double k = bh / a;
    const double px = f.x - k * d.x, pz = f.z - k * d.z;
    const double disc = a * (r * r - (px * px + pz * pz));
    if (!(disc >= 0.0)) return false;
    const double q = -(bh + std::copysign(std::sqrt(disc), bh));
    if (q == 0.0) {
      lo = hi = 0.0;
    } else {
      const double r0 = c / q, r1 = q / a;
      lo = std::min(r0, r1);
      hi = std::max(r0, r1);
    }
  }
  if (d.y == 0.0) {
    if (!(std::abs(f.y) <= half_height)) return false;
  } else {
    const double y0 = (-half_height - f.y) / d.y, y1 = (half_height - f.y) / d.y;
    lo = std::max(lo, std::min(y0, y1));
    hi = std::min(hi, std::max(y0, y1));
  }
  if (!(lo <= hi)) return false;
  s_in = lo;
  s_out = hi;
  return true;
}

int intersect(const void* record, const PrismRay* ray, double tmin, double tmax, PrismHit* hit) {
  const auto& rec = record_of<CapsuleRecord>(record);
  const double r = rec.radius, half_height = 0.5 * rec.height;
  const glm::dvec3 d = load3(ray->dir);
  const glm::dvec3 o = load3(ray->origin) - glm::dvec3(0.0, half_height, 0.0);  // origin seen from the middle
  const double tf = foot_parameter(o, d);
  const glm::dvec3 f = o + tf * d;

  Span span;
  double s0 = 0.0, s1 = 0.0;
  if (tube(f, d, r, half_height, s0, s1)) span.merge(s0, s1, kTube);
  if (ball(f + glm::dvec3(0.0, half_height, 0.0), d, r, s0, s1)) span.merge(s0, s1, kBottomCap);
  if (ball(f - glm::dvec3(0.0, half_height, 0.0), d, r, s0, s1)) span.merge(s0, s1, kTopCap);
  if (!(span.in <= span.out)) return 0;

  // Entry first; a ray that starts inside (or past tmin) leaves through the exit.
  const double t_in = tf + span.in, t_out = tf + span.out;
  *hit = PrismHit{};
  if (t_in > tmin && t_in <= tmax && std::isfinite(t_in)) {
    hit->t = t_in;
    hit->part = span.in_part;
    return 1;
  }
  if (t_out > tmin && t_out <= tmax && std::isfinite(t_out)) {
    hit->t = t_out;
    hit->part = span.out_part;
    return 1;
  }
  return 0;
}

// Signed distance to the segment minus radius, in long double: value and
// unit gradient (see prism/sdk/refine.hpp). Smooth across the seams.
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const auto& rec = record_of<CapsuleRecord>(record);
  const long double r = rec.radius, height = rec.height;
  polish_hit(*ray, *hit, [r, height](const Vec3x& p) {
    const long double yc = std::clamp(p.y, 0.0L, height);
    const Vec3x radial{p.x, p.y - yc, p.z};
    const long double len = std::sqrt(dot(radial, radial));
    return ImplicitSample{len - r, (1.0L / len) * radial};
  });
}

void surface(const void* record, const PrismRay* ray, const PrismHit* hit, PrismSurface* out) {
  const auto& rec = record_of<CapsuleRecord>(record);
  const double r = rec.radius, height = rec.height, half_height = 0.5 * height;
  const glm::dvec3 d = load3(ray->dir);
  const glm::dvec3 o = load3(ray->origin) - glm::dvec3(0.0, half_height, 0.0);
  const double tf = foot_parameter(o, d);
  const glm::dvec3 p = (o + tf * d) + (hit->t - tf) * d;         // seen from the middle
  const double yc = std::clamp(p.y, -half_height, half_height);  // nearest axis point
  glm::dvec3 radial(p.x, p.y - yc, p.z);
  const double len = glm::length(radial);
  glm::dvec3 normal(0.0);  // undefined on the axis: the core then uses -dir
  if (len > 0.0) {
    radial *= r / len;
    normal = radial / r;
  }
  const glm::dvec3 point(radial.x, yc + half_height + radial.y, radial.z);
  const double rho = std::sqrt(radial.x * radial.x + radial.z * radial.z);
  const double arc = 0.5 * kPi * r + (yc + half_height) + r * atan2_spec(radial.y, rho);
  write_surface(out, point, normal, turn_fraction(radial.z, radial.x), arc / (kPi * r + height));
}

const PrismPrimitiveDesc kDesc =
    describe_primitive<intersect>("capsule", PRISM_PRIMITIVE_TRANSFORMABLE, kFields, sizeof(CapsuleRecord), validate,
                                  pack, bounds, surface, kPluginGlsl, "capsule", refine);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
