// Box primitive: |p.x| <= hx, |p.y| <= hy, |p.z| <= hz in the local frame;
// the core applies `center` and `rotation`.
//
// Numerics
// - intersect: the slab method in a frame re-centred at the foot of the
//   perpendicular from the box centre, so each slab distance (+-h - o_i)/d_i
//   is formed from numbers of the box's size even for a camera 1e6 away.
//   An axis with d_i == 0 exactly is either always inside its slab or a miss
//   (no 0 * inf NaNs). Hit: the entry distance if it is in (tmin, tmax],
//   else the exit distance (ray starting inside).
// - surface: the hit point (stored from the re-centred frame, error ~eps*h)
//   is snapped onto the hit face and clamped into the face rectangle; the
//   normal and uv then follow the spec's argmax rule on that point (ties
//   x < y < z), so an edge hit gives the same answer in every backend.
// - GPU: box.glsl, the same method in GLSL double precision.
#include <algorithm>
#include <cmath>
#include <utility>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "box.glsl.hpp"

namespace {

using namespace prism::sdk;

struct BoxRecord {
  double half[4];  // hx, hy, hz, unused
};
static_assert(sizeof(BoxRecord) % 16 == 0);
static_assert(glsl_define(kPluginGlsl, "BOX_HALF") == offsetof(BoxRecord, half) / sizeof(double));

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

// Parameter interval [near, far] of the ray inside the box (relative to the
// ray origin `o`), with the axis that bounds each end; false when empty.
struct Span {
  double near = -kInf, far = kInf;
  int near_axis = 0, far_axis = 0;
};
bool slab_span(const double* h, const glm::dvec3& o, const glm::dvec3& d, Span& span) {
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (!(std::abs(o[i]) <= h[i])) return false;
      continue;
    }
    double t0 = (-h[i] - o[i]) / d[i], t1 = (h[i] - o[i]) / d[i];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > span.near) {
      span.near = t0;
      span.near_axis = i;
    }
    if (t1 < span.far) {
      span.far = t1;
      span.far_axis = i;
    }
  }
  return span.near <= span.far;  // false for NaN rays too
}

int intersect(const void* record, const PrismRay* ray, double tmin, double tmax, PrismHit* hit) {
  const auto& rec = record_of<BoxRecord>(record);
  glm::dvec3 o = load3(ray->origin), d = load3(ray->dir);
  double tf = foot_parameter(o, d);
  glm::dvec3 of = o + tf * d;
  Span span;
  if (!slab_span(rec.half, of, d, span)) return 0;
  const double s[2] = {span.near, span.far};
  const int axis[2] = {span.near_axis, span.far_axis};
  for (int i = 0; i < 2; ++i) {
    double t = tf + s[i];
    if (!(t > tmin && t <= tmax)) continue;
    *hit = PrismHit{};
    hit->t = t;
    store3(of + s[i] * d, hit->data);
    hit->part = static_cast<uint32_t>(axis[i]);
    return 1;
  }
  return 0;
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

// The spec's face: argmax |p_i| / h_i, ties going to the lower axis.
int face_axis(const glm::dvec3& p, const double* h) {
  int a = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(p[i]) / h[i] > std::abs(p[a]) / h[a]) a = i;
  return a;
}

void surface(const void* record, const PrismRay*, const PrismHit* hit, PrismSurface* out) {
  const double* h = record_of<BoxRecord>(record).half;
  glm::dvec3 p = load3(hit->data);
  int hit_axis = static_cast<int>(hit->part);
  for (int i = 0; i < 3; ++i)
    p[i] = i == hit_axis ? std::copysign(h[i], p[i]) : std::clamp(p[i], -h[i], h[i]);
  int a = face_axis(p, h);
  glm::dvec3 n(0.0);
  n[a] = std::copysign(1.0, p[a]);
  // Spec uv: +-x (z, -y), +-y (x, z), +-z (x, -y), each mapped to [0, 1].
  double from_x = (p.x + h[0]) / (2.0 * h[0]), from_z = (p.z + h[2]) / (2.0 * h[2]);
  double down_y = (h[1] - p.y) / (2.0 * h[1]);
  if (a == 0) write_surface(out, p, n, from_z, down_y);
  if (a == 1) write_surface(out, p, n, from_x, from_z);
  if (a == 2) write_surface(out, p, n, from_x, down_y);
}

const PrismPrimitiveDesc kDesc = describe_primitive<intersect>("box", PRISM_PRIMITIVE_TRANSFORMABLE, kFields,
                                                       sizeof(BoxRecord), validate_nothing, pack, bounds, surface,
                                                       kPluginGlsl, "box", refine);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
