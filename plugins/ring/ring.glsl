// Ring, GPU intersector: the same method as ring.cpp, in double. The origin
// moves to the foot of the perpendicular from the centre, then
// s = -o.y / d.y (d.y == 0 exactly: parallel, a miss) and the hit point is
// formed in that frame, so the inclusive inner/outer test on
// sqrt(x^2 + z^2) is decided on a point with error ~eps * |ring|. Double
// because a camera 1e4 away from a thin ring loses o - c itself in float32
// (docs/numerics.md, Ring).
//
// Record (std430 doubles; offsets static_asserted in ring.cpp):
#define RING_INNER 0
#define RING_OUTER 1

bool ring_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  hit.t = 0.0LF;
  hit.data = dvec3(0.0LF);
  hit.part = 0u;
  dvec3 d = ray.dir;
  if (d.y == 0.0LF) return false;
  double tf = prism_foot_parameter(ray.origin, d);
  dvec3 of = ray.origin + tf * d;
  double s = -of.y / d.y;
  double t = tf + s;
  if (!(t > tmin && t <= tmax)) return false;  // NaN rays fail here too
  dvec3 p = of + s * d;
  p.y = 0.0LF;
  double radius = sqrt(p.x * p.x + p.z * p.z);
  if (!(radius >= prism_record(rec, RING_INNER) && radius <= prism_record(rec, RING_OUTER))) return false;
  hit.t = t;
  hit.data = p;
  return true;
}

// The stored point (y exactly 0); u runs inner -> outer, v is the azimuth.
void ring_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  double inner = prism_record(rec, RING_INNER), outer = prism_record(rec, RING_OUTER);
  dvec3 p = hit.data;
  double radius = sqrt(p.x * p.x + p.z * p.z);
  s.point = p;
  s.normal = dvec3(0.0LF, 1.0LF, 0.0LF);
  s.uv = dvec2((radius - inner) / (outer - inner), prism_turn_fraction(p.z, p.x));
}
