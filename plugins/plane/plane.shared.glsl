// Plane primitive, written once for the CPU and the GPU (the shared dialect:
// prism/sdk/dialect.hpp): dot(normal, p - point) = 0, infinite and
// two-sided. Not TRANSFORMABLE: the ray is the world ray and `point`,
// `normal` are world-space, so the spec's uv (from world P) is formed here.
//
// - intersect: t = dot(m, point - o) / dot(m, d) with m the unit normal. The
//   subtraction point - o is the only cancellation and it is exact to one
//   rounding, so t has relative error ~eps at any distance. A ray parallel
//   to the plane (dot(m, d) == 0 exactly) misses; no epsilon band. Double
//   because the plane is infinite: a hit far from the camera, or a camera
//   far from `point`, loses o - point itself in float32 (docs/numerics.md,
//   Plane).
// - surface: P = o + t d is pulled back onto the plane by removing its
//   normal component (P -= dot(m, P - point) m), so the secondary-ray offset
//   always starts from the right side; the tangential error (~eps |o|) only
//   moves uv by that much.
//
// Record (doubles; plane.cpp static_asserts its struct against these):
#define PLANE_POINT 0
#define PLANE_UV_SCALE 3
#define PLANE_NORMAL 4
#define PLANE_T1 8
#define PLANE_T2 12

bool plane_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  prism_clear_hit(hit);
  real3 m = prism_record3(rec, PLANE_NORMAL);
  real denom = dot(m, ray.dir);
  if (denom == R(0.0)) return false;
  precise real t = dot(m, prism_record3(rec, PLANE_POINT) - ray.origin) / denom;
  if (!(t > tmin && t <= tmax)) return false;  // NaN rays fail here too
  hit.t = t;
  return true;
}

void plane_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  real3 m = prism_record3(rec, PLANE_NORMAL);
  real3 point = prism_record3(rec, PLANE_POINT);
  precise real3 p = ray.origin + hit.t * ray.dir;
  p -= dot(m, p - point) * m;
  real scale = prism_record(rec, PLANE_UV_SCALE);
  s.point = p;
  s.normal = m;
  real u = dot(p - point, prism_record3(rec, PLANE_T1)) * scale;
  real v = dot(p - point, prism_record3(rec, PLANE_T2)) * scale;
  s.uv = real2(u, v);
}
