// The shared dialect, GLSL side (prism/sdk/dialect.hpp is the C++ side and
// documents the dialect): what makes a `*.shared.glsl` source, written once
// for the CPU and the GPU, plain GLSL 4.50. The kernel generator places it
// after the kernel header (#version, extensions, PRISM_BINDING_* and
// PRISM_FEATURE_* defines) and before the shared library
// (prism/sdk/modules/library.shared.glsl) and every plugin source.
//
// Precision: double, unless the header defines PRISM_REAL_FLOAT (a float
// kernel, or a double one whose plugins intersect in float; also the float
// instantiation that `scripts/check_plugin_glsl.sh` compiles). The record
// buffer is doubles, as the C++ `pack` writes them, except in a float world
// (PRISM_WORLD_FLOAT: gpu/scene.glsl), which has no double anywhere.
//
// GLSL has no double atan/asin: prism_atan2 and prism_safe_asin evaluate in
// float, which is far inside what a texel or an 8-bit pixel resolves; only
// uv uses them.
#ifdef PRISM_REAL_FLOAT
#define real float
#define real2 vec2
#define real3 vec3
#define real4 vec4
#else
#define real double
#define real2 dvec2
#define real3 dvec3
#define real4 dvec4
#endif
#define R(x) real(x)
#define OUT(T) out T
#define INOUT(T) inout T
#define PrismRecord uint

// PRISM_REAL_EPSILON: the spacing of `real` at 1 (std::numeric_limits<real>::epsilon()),
// for tolerances that must not ask for more digits than `real` has.
#ifdef PRISM_REAL_FLOAT
const float PRISM_PI = 3.14159265358979323846;
const float PRISM_REAL_EPSILON = 1.0 / 8388608.0;  // 2^-23
#else
const double PRISM_PI = 3.14159265358979323846LF;
const double PRISM_REAL_EPSILON = 1.0LF / 4503599627370496.0LF;  // 2^-52
#endif

// Every object's packed parameter record, as the plugin's C++ `pack` wrote
// it (std430: a flat run of doubles; rounded to floats for a float world,
// PRISM_WORLD_FLOAT, which holds no double). `rec` is the record's first number.
#ifdef PRISM_WORLD_FLOAT
layout(std430, binding = PRISM_BINDING_RECORDS) readonly buffer PrismRecordBuffer {
  float prism_records[];
};
#else
layout(std430, binding = PRISM_BINDING_RECORDS) readonly buffer PrismRecordBuffer {
  double prism_records[];
};
#endif

// A kernel that knows every record offset (the GPU kernel of a small
// scene, PRISM_RECORD_COUNT) reads the records once into this copy and the
// plugins read the copy: a driver that runs lanes together then reads each
// number once, not once per lane and test (gpu/scene.glsl, "caches").
#ifdef PRISM_RECORD_COUNT
#ifdef PRISM_WORLD_FLOAT
float prism_record_cache[PRISM_RECORD_COUNT];
#else
double prism_record_cache[PRISM_RECORD_COUNT];
#endif
#define PRISM_RECORD_AT(i) prism_record_cache[i]
#else
#define PRISM_RECORD_AT(i) prism_records[i]
#endif

real prism_record(uint rec, uint i) { return real(PRISM_RECORD_AT(rec + i)); }
real3 prism_record3(uint rec, uint i) {
  return real3(PRISM_RECORD_AT(rec + i), PRISM_RECORD_AT(rec + i + 1u), PRISM_RECORD_AT(rec + i + 2u));
}

bool prism_is_finite(real x) { return !isinf(x) && !isnan(x); }

#ifdef PRISM_REAL_FLOAT
float prism_inf() { return uintBitsToFloat(0x7f800000u); }

// std::copysign: the sign bit of y on |x| (-0.0 counts as negative).
float prism_copysign(float x, float y) {
  return uintBitsToFloat((floatBitsToUint(x) & 0x7fffffffu) | (floatBitsToUint(y) & 0x80000000u));
}
#else
double prism_inf() { return packDouble2x32(uvec2(0u, 0x7ff00000u)); }

// std::copysign: the sign bit of y on |x| (-0.0 counts as negative).
double prism_copysign(double x, double y) {
  uvec2 bx = unpackDouble2x32(x), by = unpackDouble2x32(y);
  bx.y = (bx.y & 0x7fffffffu) | (by.y & 0x80000000u);
  return packDouble2x32(bx);
}
#endif

// The spec's clamped domain, in float (see above).
real prism_safe_asin(real x) { return real(asin(float(clamp(x, R(-1.0), R(1.0))))); }

// atan2 with the spec's atan2(0, 0) = 0 (GLSL leaves atan(0, 0) undefined).
real prism_atan2(real y, real x) {
  if (x == R(0.0) && y == R(0.0)) return R(0.0);
  return real(atan(float(y), float(x)));
}
