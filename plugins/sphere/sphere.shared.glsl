// Sphere primitive, written once for the CPU and the GPU (the shared
// dialect: prism/sdk/dialect.hpp): |p| = radius in the local frame; the core
// applies `center` and `rotation` (TRANSFORMABLE).
//
// - intersect: prism_intersect_sphere (the SDK library), the routine the
//   core uses for light spheres too: the origin moved to the foot of the
//   perpendicular from the centre and the robust discriminant
//   r^2 - |f - (f.d)d|^2 (Ray Tracing Gems ch. 7), so far or small spheres
//   keep their roots; double because a camera 1e6 away from a small sphere
//   loses the whole answer in float32 (docs/numerics.md, Sphere).
// - surface: the point is re-formed from that foot (its error ~eps*r plus
//   the rounding of t, not eps*|origin|) and re-projected onto the sphere
//   with p *= r/|p| (pbrt-v4), far inside the spec's offset.
//
// Record (doubles; sphere.cpp static_asserts its struct against these):
#define SPHERE_RADIUS 0

bool sphere_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  prism_clear_hit(hit);
  return prism_intersect_sphere(ray.origin, ray.dir, prism_record(rec, SPHERE_RADIUS), tmin, tmax, hit.t);
}

void sphere_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  real r = prism_record(rec, SPHERE_RADIUS);
  real tf = prism_foot_parameter(ray.origin, ray.dir);
  precise real3 p = (ray.origin + tf * ray.dir) + (hit.t - tf) * ray.dir;
  real len = length(p);
  if (len > R(0.0)) p *= r / len;
  s.point = p;
  s.normal = p / r;
  s.uv = real2(prism_turn_fraction(p.z, p.x), R(0.5) - prism_safe_asin(p.y / r) / PRISM_PI);
}
