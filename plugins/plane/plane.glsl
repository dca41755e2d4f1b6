// Plane, GPU intersector: the same method as plane.cpp, in double. The
// plane is not TRANSFORMABLE, so the ray is the world ray and `point`,
// `normal` are world-space: t = dot(m, point - o) / dot(m, d), where
// point - o is the only cancellation, exact to one rounding. Double because
// the plane is infinite: a hit far from the camera, or a camera far from
// `point`, loses o - point itself in float32 (docs/numerics.md,
// Plane). dot(m, d) == 0 exactly is a miss; no epsilon band.
//
// Record (std430 doubles; offsets static_asserted in plane.cpp):
#define PLANE_POINT 0
#define PLANE_UV_SCALE 3
#define PLANE_NORMAL 4
#define PLANE_T1 8
#define PLANE_T2 12

bool plane_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  hit.t = 0.0LF;
  hit.data = dvec3(0.0LF);
  hit.part = 0u;
  dvec3 m = prism_record3(rec, PLANE_NORMAL);
  double denom = dot(m, ray.dir);
  if (denom == 0.0LF) return false;
  double t = dot(m, prism_record3(rec, PLANE_POINT) - ray.origin) / denom;
  if (!(t > tmin && t <= tmax)) return false;  // NaN rays fail here too
  hit.t = t;
  return true;
}

// P = o + t d pulled back onto the plane by removing its normal component,
// so the secondary-ray offset starts on the right side; uv in the spec's
// tangent frame from world P (the tangential error ~eps |o| only moves uv).
void plane_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  dvec3 m = prism_record3(rec, PLANE_NORMAL), point = prism_record3(rec, PLANE_POINT);
  dvec3 p = ray.origin + hit.t * ray.dir;
  p -= dot(m, p - point) * m;
  double scale = prism_record(rec, PLANE_UV_SCALE);
  s.point = p;
  s.normal = m;
  double u = dot(p - point, prism_record3(rec, PLANE_T1)) * scale;
  double v = dot(p - point, prism_record3(rec, PLANE_T2)) * scale;
  s.uv = dvec2(u, v);
}
