// Capsule primitive, written once for the CPU and the GPU in the shared
// dialect (prism/sdk/dialect.hpp): capsule.cpp compiles this file as C++ in
// double and in float, the GPU backends compile it as GLSL. The shape, its
// normal and its uv are described in capsule.cpp.

// Record (doubles; capsule.cpp static_asserts its struct against these):
#define CAPSULE_RADIUS 0
#define CAPSULE_HEIGHT 1

// PrismHit.part: which piece the hit lies on. For information only:
// surface finds the nearest axis point itself, so refine need not keep it
// up to date.
#define CAPSULE_TUBE 0u
#define CAPSULE_BOTTOM_CAP 1u
#define CAPSULE_TOP_CAP 2u

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
// - precise marks the results whose rounding the method relies on, so the
//   GPU compiles them as the CPU does (no fused multiply-add).

// The running union of the pieces' intervals along the line f + s d (s from
// the foot). GLSL has no member functions: merge takes the span inout.
struct CapsuleSpan {
  real s_in;
  real s_out;
  uint part_in;
  uint part_out;
};

void capsule_merge(INOUT(CapsuleSpan) span, real s_in, real s_out, uint part) {
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

// Ball of radius r centred at f - g (g: the line's point f seen from the
// centre): s = -g.d -+ sqrt(r^2 - |g - (g.d)d|^2), d unit.
bool capsule_ball(real3 g, real3 d, real r, OUT(real) s_in, OUT(real) s_out) {
  s_in = R(0.0);
  s_out = R(0.0);
  precise real b = dot(g, d);
  precise real3 perp = g - b * d;
  precise real disc = r * r - dot(perp, perp);
  if (!(disc >= R(0.0))) return false;
  real h = sqrt(disc);
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
bool capsule_tube(real3 f, real3 d, real r, real half_height, OUT(real) s_in, OUT(real) s_out) {
  s_in = R(0.0);
  s_out = R(0.0);
  precise real a = d.x * d.x + d.z * d.z;
  precise real c = f.x * f.x + f.z * f.z - r * r;
  real lo = -prism_inf(), hi = prism_inf();
  if (a == R(0.0)) {
    if (!(c <= R(0.0))) return false;  // parallel to the axis, outside the tube
  } else {
    precise real bh = f.x * d.x + f.z * d.z;
    real k = bh / a;
    precise real px = f.x - k * d.x, pz = f.z - k * d.z;
    precise real disc = a * (r * r - (px * px + pz * pz));
    if (!(disc >= R(0.0))) return false;
    precise real q = -(bh + prism_copysign(sqrt(disc), bh));
    if (q == R(0.0)) {
      lo = R(0.0);
      hi = R(0.0);
    } else {
      real r0 = c / q, r1 = q / a;
      lo = min(r0, r1);
      hi = max(r0, r1);
    }
  }
  if (d.y == R(0.0)) {
    if (!(abs(f.y) <= half_height)) return false;
  } else {
    real y0 = (-half_height - f.y) / d.y, y1 = (half_height - f.y) / d.y;
    lo = max(lo, min(y0, y1));
    hi = min(hi, max(y0, y1));
  }
  if (!(lo <= hi)) return false;
  s_in = lo;
  s_out = hi;
  return true;
}

bool capsule_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  prism_clear_hit(hit);
  real r = prism_record(rec, CAPSULE_RADIUS);
  real half_height = R(0.5) * prism_record(rec, CAPSULE_HEIGHT);
  real3 d = ray.dir;
  real3 middle = real3(R(0.0), half_height, R(0.0));
  precise real3 o = ray.origin - middle;  // origin seen from the middle
  precise real tf = prism_foot_parameter(o, d);
  precise real3 f = o + tf * d;

  CapsuleSpan span;
  span.s_in = prism_inf();
  span.s_out = -prism_inf();
  span.part_in = CAPSULE_TUBE;
  span.part_out = CAPSULE_TUBE;
  real s0 = R(0.0), s1 = R(0.0);
  if (capsule_tube(f, d, r, half_height, s0, s1)) capsule_merge(span, s0, s1, CAPSULE_TUBE);
  if (capsule_ball(f + middle, d, r, s0, s1)) capsule_merge(span, s0, s1, CAPSULE_BOTTOM_CAP);
  if (capsule_ball(f - middle, d, r, s0, s1)) capsule_merge(span, s0, s1, CAPSULE_TOP_CAP);
  if (!(span.s_in <= span.s_out)) return false;

  // Entry first; a ray that starts inside (or past tmin) leaves through the exit.
  precise real t_in = tf + span.s_in, t_out = tf + span.s_out;
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

// The point formed from the foot of the perpendicular, re-projected onto the
// surface radially from its nearest axis point; that radial direction is the
// outward normal (undefined on the axis: all zeros, and the core uses -dir).
// u = 0.5 + atan2(z, x)/2pi; v = meridian arc length from the bottom pole
// over the whole meridian (pi r + height).
void capsule_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  real r = prism_record(rec, CAPSULE_RADIUS);
  real height = prism_record(rec, CAPSULE_HEIGHT);
  real half_height = R(0.5) * height;
  real3 d = ray.dir;
  precise real3 o = ray.origin - real3(R(0.0), half_height, R(0.0));  // seen from the middle
  precise real tf = prism_foot_parameter(o, d);
  precise real3 p = (o + tf * d) + (hit.t - tf) * d;
  real yc = clamp(p.y, -half_height, half_height);  // nearest axis point
  real3 radial = real3(p.x, p.y - yc, p.z);
  real len = length(radial);
  s.normal = real3(R(0.0));
  if (len > R(0.0)) {
    radial *= r / len;
    s.normal = radial / r;
  }
  s.point = real3(radial.x, yc + half_height + radial.y, radial.z);
  real rho = sqrt(radial.x * radial.x + radial.z * radial.z);
  real arc = R(0.5) * PRISM_PI * r + (yc + half_height) + r * prism_atan2(radial.y, rho);
  s.uv = real2(prism_turn_fraction(radial.z, radial.x), arc / (PRISM_PI * r + height));
}
