// Sphere, GPU intersector: the same method as sphere.cpp, in double.
// prism_intersect_sphere (core library) moves the origin to the foot of the
// perpendicular and uses the robust discriminant, exactly as the CPU code;
// double because a far camera (1e6) looking at a small sphere loses the
// whole answer in float32 (docs/numerics.md, Sphere).
//
// Record (std430 doubles; offsets static_asserted in sphere.cpp):
#define SPHERE_RADIUS 0

bool sphere_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  hit.t = 0.0LF;
  hit.data = dvec3(0.0LF);
  hit.part = 0u;
  return prism_intersect_sphere(ray.origin, ray.dir, prism_record(rec, SPHERE_RADIUS), tmin, tmax, hit.t);
}

// The point is re-formed from the foot of the perpendicular and re-projected
// onto the sphere (p *= r/|p|, pbrt-v4), as on the CPU.
void sphere_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  double r = prism_record(rec, SPHERE_RADIUS);
  double tf = prism_foot_parameter(ray.origin, ray.dir);
  dvec3 p = (ray.origin + tf * ray.dir) + (hit.t - tf) * ray.dir;
  double len = length(p);
  if (len > 0.0LF) p *= r / len;
  s.point = p;
  s.normal = p / r;
  s.uv = dvec2(prism_turn_fraction(p.z, p.x), 0.5LF - prism_safe_asin(p.y / r) / PRISM_PI);
}
