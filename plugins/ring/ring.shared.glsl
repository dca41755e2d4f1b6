// Ring primitive, written once for the CPU and the GPU (the shared dialect:
// prism/sdk/dialect.hpp): the disk inner <= |p| <= outer in the local
// xz-plane, zero thickness, visible from both sides.
//
// - intersect: the origin is moved to the foot of the perpendicular from the
//   centre first; then s = -o.y / d.y (d.y == 0 exactly: parallel, a miss)
//   and the hit point o + s d is formed in that frame, so its error is
//   ~eps * |ring| rather than eps * |origin| for a camera 1e4 away, and the
//   inner/outer test (inclusive, on sqrt(x^2 + z^2) as the spec states it)
//   is decided on an accurate point. Double because a camera 1e4 away from
//   a thin ring loses o - c itself in float32 (docs/numerics.md, Ring).
// - surface: the stored point with y exactly 0; u runs inner -> outer, v is
//   the azimuth.
//
// Record (doubles; ring.cpp static_asserts its struct against these):
#define RING_INNER 0
#define RING_OUTER 1

bool ring_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  prism_clear_hit(hit);
  real3 d = ray.dir;
  if (d.y == R(0.0)) return false;
  precise real tf = prism_foot_parameter(ray.origin, d);
  precise real3 of = ray.origin + tf * d;
  precise real s = -of.y / d.y;
  precise real t = tf + s;
  if (!(t > tmin && t <= tmax)) return false;  // NaN rays fail here too
  precise real3 p = of + s * d;
  p.y = R(0.0);
  precise real radius = sqrt(p.x * p.x + p.z * p.z);
  if (!(radius >= prism_record(rec, RING_INNER) && radius <= prism_record(rec, RING_OUTER))) return false;
  hit.t = t;
  hit.data = p;
  return true;
}

void ring_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  real inner = prism_record(rec, RING_INNER);
  real outer = prism_record(rec, RING_OUTER);
  real3 p = hit.data;
  real radius = sqrt(p.x * p.x + p.z * p.z);
  s.point = p;
  s.normal = real3(R(0.0), R(1.0), R(0.0));
  s.uv = real2((radius - inner) / (outer - inner), prism_turn_fraction(p.z, p.x));
}
