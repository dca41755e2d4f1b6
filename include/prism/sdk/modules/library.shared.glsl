// Prism's shared library, version 2, in the shared dialect
// (prism/sdk/dialect.hpp; core/glsl/prelude.glsl on the GPU): the maths
// every primitive plugin builds on, written once for the CPU and the GPU,
// in double and in float. C++ instantiates it through prism/sdk/library.hpp;
// the kernel generator splices it after the GLSL prelude and before any
// plugin source, so plugins use it as if included.
//
// Geometry is double precision in the renderer: ray origins, object centres
// and t must survive a camera 1e6 away from a 1e-4 object, which float32
// cannot (docs/numerics.md, Float and double: the error is in o - c
// itself). The float instantiation exists to measure that.
#define PRISM_GLSL_LIBRARY_VERSION 2

// A ray in an object's local frame; dir is unit length.
struct PrismRay {
  real3 origin;
  real3 dir;
};

// What a plugin's intersect returns: t plus private data its surface reads.
struct PrismHit {
  real t;
  real3 data;
  uint part;
};

// A plugin's surface: local point (re-projected), outward normal (any
// length; all zero where undefined) and uv.
struct PrismSurface {
  real3 point;
  real3 normal;
  real2 uv;
};

// A hit with nothing in it: what intersect leaves on a miss.
void prism_clear_hit(OUT(PrismHit) hit) {
  hit.t = R(0.0);
  hit.data = real3(R(0.0));
  hit.part = 0u;
}

real prism_max_abs_component(real3 v) { return max(abs(v.x), max(abs(v.y), abs(v.z))); }

// The spec's clamped domain.
real prism_safe_sqrt(real x) { return sqrt(max(x, R(0.0))); }

// The spec's azimuth texture coordinate: 0.5 + atan2(y, x) / 2pi, in [0, 1].
real prism_turn_fraction(real y, real x) { return R(0.5) + prism_atan2(y, x) / (R(2.0) * PRISM_PI); }

// a*b - c*d with one rounding (Kahan's algorithm via fma): keeps b^2 - 4ac
// meaningful for near-tangent rays where the two products nearly cancel.
real prism_difference_of_products(real a, real b, real c, real d) {
  precise real cd = c * d;
  precise real err = fma(-c, d, cd);
  precise real dop = fma(a, b, -cd);
  precise real result = dop + err;
  return result;
}

// Real roots of a t^2 + b t + c = 0 in ascending order; returns how many
// (0, 1 or 2; a double root is reported twice). Uses the cancellation-free
// pair t = c/q, t = q/a with q = -(b + sign(b) sqrt(disc))/2. a == 0 exactly
// makes the equation linear; b == 0 then leaves no isolated root.
int prism_solve_quadratic(real a, real b, real c, OUT(real) t0, OUT(real) t1) {
  t0 = R(0.0);
  t1 = R(0.0);
  if (a == R(0.0)) {
    if (b == R(0.0)) return 0;
    t0 = -c / b;
    t1 = t0;
    return 1;
  }
  real disc = prism_difference_of_products(b, b, R(4.0) * a, c);
  if (!(disc >= R(0.0))) return 0;  // also rejects NaN
  precise real q = R(-0.5) * (b + prism_copysign(sqrt(disc), b));
  if (q == R(0.0)) return 2;  // b == 0 and disc == 0, hence c == 0: double root at 0
  t0 = c / q;
  t1 = q / a;
  if (t0 > t1) {
    real s = t0;
    t0 = t1;
    t1 = s;
  }
  return 2;
}

// Unit vector along v without underflow or overflow of |v|^2: scaling by the
// largest component first makes (1e-300, 0, 0) and (1e300, 1e300, 0) work.
real3 prism_safe_normalize(real3 v) {
  real m = prism_max_abs_component(v);
  if (!(m > R(0.0)) || !prism_is_finite(m)) return real3(R(0.0));
  real3 w = v / m;
  return w / sqrt(dot(w, w));
}

// Parameter of the foot of the perpendicular from the local origin to the
// ray (d unit). Moving a far ray origin there before solving keeps every
// coefficient of order the object's size (Wald, Ray Tracing Gems II ch. 34).
real prism_foot_parameter(real3 o, real3 d) { return -dot(o, d); }

// Smallest root t with tmin < t <= tmax of |o + t d| = r, where o is the ray
// origin relative to the sphere centre and d is unit length. Shared by the
// sphere plugin and the core's visible light spheres (CPU and GPU), so that
// both give the same t for the same sphere.
//
// The origin is first moved to the foot of the perpendicular from the centre
// (t_f = -o.d), so a camera 1e6 away works with numbers of the sphere's size.
// The discriminant is the robust r^2 - |f - (f.d) d|^2 (Ray Tracing Gems
// ch. 7) rather than b^2 - 4ac, which cancels for far or small spheres. After
// re-centring the linear coefficient b = f.d is only a rounding residual, so
// the roots t_f - b -+ sqrt(disc) carry no cancellation.
bool prism_intersect_sphere(real3 o, real3 d, real r, real tmin, real tmax, OUT(real) t) {
  t = R(0.0);
  precise real tf = -dot(o, d);
  precise real3 f = o + tf * d;
  precise real b = dot(f, d);
  precise real3 perp = f - b * d;
  precise real disc = r * r - dot(perp, perp);
  if (!(disc >= R(0.0))) return false;  // also rejects NaN rays
  real h = sqrt(disc);
  precise real mid = tf - b;
  real t0 = mid - h;
  real t1 = mid + h;
  if (t0 > tmin && t0 <= tmax) {
    t = t0;
    return true;
  }
  if (t1 > tmin && t1 <= tmax) {
    t = t1;
    return true;
  }
  return false;
}
