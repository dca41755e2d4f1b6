// Prism GLSL library, version 1: what every primitive plugin's GLSL and the
// shared shading source build on. The kernel generator places it after the
// kernel header (#version, extensions, PRISM_BINDING_* and PRISM_FEATURE_*
// defines) and before any plugin source, so plugins use it as if included.
//
// Geometry is double precision (GLSL 4.00 / shaderFloat64): ray origins,
// object centres and t must survive a camera 1e6 away from a 1e-4 object,
// which float32 cannot (docs/numerics.md, Float and double: the error is in o - c
// itself). GLSL has no double atan/asin/exp/pow: uv and shading terms that
// need them are evaluated in float, which is far inside what a texel or an
// 8-bit pixel resolves.
//
// The functions mirror prism/sdk/math.hpp and prism/sdk/sphere_math.hpp
// line for line, so the CPU and GPU intersectors make the same choices.
#define PRISM_GLSL_LIBRARY_VERSION 1

const double PRISM_PI = 3.14159265358979323846LF;

// A ray in an object's local frame; dir is unit length.
struct PrismRay {
  dvec3 origin;
  dvec3 dir;
};

// What a plugin's intersect returns: t plus private data its surface reads.
struct PrismHit {
  double t;
  dvec3 data;
  uint part;
};

// A plugin's surface: local point (re-projected), outward normal (any
// length; all zero where undefined) and uv.
struct PrismSurface {
  dvec3 point;
  dvec3 normal;
  dvec2 uv;
};

// Every object's packed parameter record, as the plugin's C++ `pack` wrote
// it (std430: a flat run of doubles). `rec` is the record's first double.
layout(std430, binding = PRISM_BINDING_RECORDS) readonly buffer PrismRecordBuffer {
  double prism_records[];
};

double prism_record(uint rec, uint i) { return prism_records[rec + i]; }
dvec3 prism_record3(uint rec, uint i) {
  return dvec3(prism_records[rec + i], prism_records[rec + i + 1u], prism_records[rec + i + 2u]);
}

double prism_inf() { return packDouble2x32(uvec2(0u, 0x7ff00000u)); }
bool prism_is_finite(double x) { return !isinf(x) && !isnan(x); }

double prism_max_abs_component(dvec3 v) { return max(abs(v.x), max(abs(v.y), abs(v.z))); }

// The spec's clamped domains.
double prism_safe_sqrt(double x) { return sqrt(max(x, 0.0LF)); }
double prism_safe_asin(double x) { return double(asin(float(clamp(x, -1.0LF, 1.0LF)))); }

// atan2 with the spec's atan2(0, 0) = 0 (GLSL leaves atan(0, 0) undefined).
double prism_atan2(double y, double x) {
  if (x == 0.0LF && y == 0.0LF) return 0.0LF;
  return double(atan(float(y), float(x)));
}

// The azimuth coordinate 0.5 + atan2(y, x) / 2pi, in [0, 1].
double prism_turn_fraction(double y, double x) { return 0.5LF + prism_atan2(y, x) / (2.0LF * PRISM_PI); }

// a*b - c*d with one rounding (Kahan, via fma).
double prism_difference_of_products(double a, double b, double c, double d) {
  double cd = c * d;
  double err = fma(-c, d, cd);
  double dop = fma(a, b, -cd);
  return dop + err;
}

// copysign for doubles: the sign bit of y on |x| (-0.0 counts as negative,
// as std::copysign does).
double prism_copysign(double x, double y) {
  uvec2 bx = unpackDouble2x32(x), by = unpackDouble2x32(y);
  bx.y = (bx.y & 0x7fffffffu) | (by.y & 0x80000000u);
  return packDouble2x32(bx);
}

// Real roots of a t^2 + b t + c = 0, ascending; returns how many (a double
// root counts twice). The cancellation-free pair c/q, q/a; a == 0 exactly is
// linear, as the spec says.
int prism_solve_quadratic(double a, double b, double c, out double t0, out double t1) {
  t0 = 0.0LF;
  t1 = 0.0LF;
  if (a == 0.0LF) {
    if (b == 0.0LF) return 0;
    t0 = -c / b;
    t1 = t0;
    return 1;
  }
  double disc = prism_difference_of_products(b, b, 4.0LF * a, c);
  if (!(disc >= 0.0LF)) return 0;
  double root = sqrt(disc);
  double q = -0.5LF * (b + prism_copysign(root, b));
  if (q == 0.0LF) return 2;
  t0 = c / q;
  t1 = q / a;
  if (t0 > t1) {
    double s = t0;
    t0 = t1;
    t1 = s;
  }
  return 2;
}

// Unit vector along v without overflow or underflow of |v|^2.
dvec3 prism_safe_normalize(dvec3 v) {
  double m = prism_max_abs_component(v);
  if (!(m > 0.0LF) || !prism_is_finite(m)) return dvec3(0.0LF);
  dvec3 w = v / m;
  return w / sqrt(dot(w, w));
}

// Parameter of the foot of the perpendicular from the local origin to the
// ray (d unit): moving a far origin there keeps every coefficient of the
// object's size (Wald, Ray Tracing Gems II ch. 34).
double prism_foot_parameter(dvec3 o, dvec3 d) { return -dot(o, d); }

// Smallest root tmin < t <= tmax of |o + t d| = r: origin moved to the
// foot of the perpendicular, robust discriminant r^2 - |f - (f.d)d|^2 (Ray
// Tracing Gems ch. 7). Used by the sphere plugin and by light spheres.
bool prism_intersect_sphere(dvec3 o, dvec3 d, double r, double tmin, double tmax, out double t) {
  t = 0.0LF;
  double tf = -dot(o, d);
  dvec3 f = o + tf * d;
  double b = dot(f, d);
  dvec3 perp = f - b * d;
  double disc = r * r - dot(perp, perp);
  if (!(disc >= 0.0LF)) return false;
  double h = sqrt(disc);
  double mid = tf - b;
  double t0 = mid - h, t1 = mid + h;
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
