// Capsule, GPU intersector: the same method as capsule.cpp, step for step,
// in GLSL 4.50 double precision (a camera 1e6 away from a small capsule
// loses o - c itself in float32). Only the uv angles are float
// (prism_atan2, prism_turn_fraction: GLSL has no double atan).
//
// Local shape: every point within `radius` of the segment (0,0,0)-(0,height,0).
// The solid is the union of a finite tube and two balls; it is convex, so a
// ray's line meets it in one interval: the smallest entry and the largest
// exit over the three pieces, taken in a frame re-centred at the foot of the
// perpendicular from the capsule's middle (0, height/2, 0). No seam test.
//
// Record (std430 doubles; offsets static_asserted in capsule.cpp):
#define CAPSULE_RADIUS 0
#define CAPSULE_HEIGHT 1

// The running union of the pieces' intervals along the line f + s d.
struct CapsuleSpan {
  double s_in;
  double s_out;
  uint part_in;
  uint part_out;
};

void capsule_merge(inout CapsuleSpan span, double s_in, double s_out, uint part) {
  if (!(s_in <= s_out)) return;  // empty (or NaN)
  if (s_in < span.s_in) {
    span.s_in = s_in;
    span.part_in = part;
  }
  if (s_out > span.s_out) {
    span.s_out = s_out;
    span.part_out = part;
  }
}

// Ball of radius r around the point at g = -(its centre) from f: the robust
// discriminant r^2 - |g - (g.d)d|^2 (Ray Tracing Gems ch. 7), as prism_intersect_sphere.
bool capsule_ball(dvec3 g, dvec3 d, double r, out double s_in, out double s_out) {
  s_in = 0.0LF;
  s_out = 0.0LF;
  double b = dot(g, d);
  dvec3 perp = g - b * d;
  double disc = r * r - dot(perp, perp);
  if (!(disc >= 0.0LF)) return false;
  double h = sqrt(disc);
  s_in = -b - h;
  s_out = -b + h;
  return true;
}

// Tube x^2 + z^2 <= r^2 cut to |y| <= half_height (frame centred on the capsule):
// discriminant from the closest approach in xz (no cancellation for far or
// near-tangent rays), roots by the stable pair c/q, q/a, then the slab.
bool capsule_tube(dvec3 f, dvec3 d, double r, double half_height, out double s_in, out double s_out) {
  s_in = 0.0LF;
  s_out = 0.0LF;
  double a = d.x * d.x + d.z * d.z;
  double c = f.x * f.x + f.z * f.z - r * r;
  double lo = -prism_inf(), hi = prism_inf();
  if (a == 0.0LF) {
    if (!(c <= 0.0LF)) return false;  // parallel to the axis, outside the tube
  } else {
    double bh = f.x * d.x + f.z * d.z;
    double k = bh / a;
    double px = f.x - k * d.x, pz = f.z - k * d.z;
    double disc = a * (r * r - (px * px + pz * pz));
    if (!(disc >= 0.0LF)) return false;
    double q = -(bh + prism_copysign(sqrt(disc), bh));
    if (q == 0.0LF) {
      lo = 0.0LF;
      hi = 0.0LF;
    } else {
      double r0 = c / q, r1 = q / a;
      lo = min(r0, r1);
      hi = max(r0, r1);
    }
  }
  if (d.y == 0.0LF) {
    if (!(abs(f.y) <= half_height)) return false;
  } else {
    double y0 = (-half_height - f.y) / d.y, y1 = (half_height - f.y) / d.y;
    lo = max(lo, min(y0, y1));
    hi = min(hi, max(y0, y1));
  }
  if (!(lo <= hi)) return false;
  s_in = lo;
  s_out = hi;
  return true;
}

bool capsule_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  hit.t = 0.0LF;
  hit.data = dvec3(0.0LF);
  hit.part = 0u;
  double r = prism_record(rec, CAPSULE_RADIUS);
  double half_height = 0.5LF * prism_record(rec, CAPSULE_HEIGHT);
  dvec3 d = ray.dir;
  dvec3 o = ray.origin - dvec3(0.0LF, half_height, 0.0LF);
  double tf = prism_foot_parameter(o, d);
  dvec3 f = o + tf * d;

  CapsuleSpan span;
  span.s_in = prism_inf();
  span.s_out = -prism_inf();
  span.part_in = 0u;
  span.part_out = 0u;
  double s0, s1;
  if (capsule_tube(f, d, r, half_height, s0, s1)) capsule_merge(span, s0, s1, 0u);
  if (capsule_ball(f + dvec3(0.0LF, half_height, 0.0LF), d, r, s0, s1)) capsule_merge(span, s0, s1, 1u);
  if (capsule_ball(f - dvec3(0.0LF, half_height, 0.0LF), d, r, s0, s1)) capsule_merge(span, s0, s1, 2u);
  if (!(span.s_in <= span.s_out)) return false;

  double t_in = tf + span.s_in, t_out = tf + span.s_out;
  if (t_in > tmin && t_in <= tmax && prism_is_finite(t_in)) {
    hit.t = t_in;
    hit.part = span.part_in;
    return true;
  }
  if (t_out > tmin && t_out <= tmax && prism_is_finite(t_out)) {
    hit.t = t_out;
    hit.part = span.part_out;
    return true;
  }
  return false;
}

// Point formed from the foot of the perpendicular, re-projected onto the
// surface radially from its nearest axis point; that radial direction is the
// outward normal. u = 0.5 + atan2(z, x)/2pi; v = meridian arc length from the
// bottom pole over the whole meridian (pi r + height).
void capsule_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  double r = prism_record(rec, CAPSULE_RADIUS);
  double height = prism_record(rec, CAPSULE_HEIGHT);
  double half_height = 0.5LF * height;
  dvec3 o = ray.origin - dvec3(0.0LF, half_height, 0.0LF);
  double tf = prism_foot_parameter(o, ray.dir);
  dvec3 p = (o + tf * ray.dir) + (hit.t - tf) * ray.dir;
  double yc = clamp(p.y, -half_height, half_height);
  dvec3 radial = dvec3(p.x, p.y - yc, p.z);
  double len = length(radial);
  if (len > 0.0LF) {
    radial *= r / len;
    s.normal = radial / r;
  } else {
    s.normal = dvec3(0.0LF);
  }
  s.point = dvec3(radial.x, yc + half_height + radial.y, radial.z);
  double rho = sqrt(radial.x * radial.x + radial.z * radial.z);
  double arc = 0.5LF * PRISM_PI * r + (yc + half_height) + r * prism_atan2(radial.y, rho);
  s.uv = dvec2(prism_turn_fraction(radial.z, radial.x), arc / (PRISM_PI * r + height));
}
