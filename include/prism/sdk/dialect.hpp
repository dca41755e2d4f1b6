// The shared dialect, C++ side: how one source file compiles as C++20 here
// and as GLSL 4.50 in the GPU kernel (core/glsl/prelude.glsl is the GLSL
// side), in double and in float.
//
// A primitive's intersector and the SDK maths it shares (`*.shared.glsl`:
// prism/sdk/modules/library.shared.glsl, quadric.shared.glsl,
// roots.shared.glsl, and each plugins/<type>/<type>.shared.glsl) are written
// once, in GLSL with these words, which each language's prelude defines:
//
//   real, real2, real3    the scalar and vector types: double/dvec3 in the
//                         f64 instantiation, float/vec3 in f32
//   R(0.5)                a floating literal. It must be exact in float (C++
//                         refuses to compile another), so that GLSL's
//                         real(0.5) means the same number in double; other
//                         constants (PRISM_PI) come from the preludes
//   OUT(T) x, INOUT(T) x  GLSL `out T x` / `inout T x`; C++ `T& x`
//   precise               GLSL's `precise` (no contraction, no reordering);
//                         nothing in C++, where -ffp-contract=off (set on
//                         every target that links prism_sdk) already says so
//   PrismRecord rec       a packed record: GLSL `uint`, an index into the
//                         record buffer; C++ a pointer to the record.
//                         prism_record(rec, i), prism_record3(rec, i) read
//                         the doubles at offset i (as real)
//   PrismRay/PrismHit/PrismSurface   the GLSL structs, in real
//   uint, 0u, struct S { ... };, arrays, for/if, .x/.y/.z  as in GLSL
//
// What to avoid: swizzles other than .x .y .z, struct constructors
// (S(a, b) in GLSL, S{a, b} in C++: assign the fields), implicit
// conversions between real and int or double, GLSL built-ins that GLM lacks
// (the prelude lists what both sides have), recursion, and anything after
// `//` that reads as a `prism:require` line.
//
// Instantiating a source in C++ (both precisions, each in its namespace
// prism::sdk::f64 / f32, with internal linkage):
//
//   #define PRISM_SHARED_SOURCE "sphere.shared.glsl"
//   #include "prism/sdk/instantiate.hpp"
//   ... f64::sphere_intersect(...), f32::sphere_intersect(...)
//
// GLSL has no `inline`, so the C++ instantiations get internal linkage (an
// unnamed namespace) instead: each translation unit compiles its own copy of
// the same text with the same flags, and the SDK's inline C++ wrappers
// (solve_quadratic, intersect_sphere, ...) call the copy of the unit they
// are inlined into.
//
// What can still differ between a CPU and a GPU compile of the same text:
// - Built-ins the GLSL spec leaves loosely specified: sqrt, division and
//   length are correctly rounded in IEEE double on the CPU; GLSL 4.50
//   requires double sqrt and division to be correctly rounded too, but
//   float ones only to 2.5-3 ulp, and length/normalize to be "the sum of the
//   products, then inversesqrt" in no fixed order.
// - Contraction: `precise` forbids it in GLSL only where written; the C++
//   side never contracts. Mark each result whose rounding matters (the fma
//   discriminant, re-centring) precise.
// - Transcendentals: GLSL has no double atan/asin, so prism_atan2 and
//   prism_safe_asin evaluate in float on the GPU (uv only; see
//   prelude.glsl); on the CPU they are std:: in the instantiation's type.
// - NaN: GLSL min/max/clamp are undefined for NaN; the C++ ones follow
//   std::min/std::max. Code that must behave on NaN rays tests with
//   `!(x >= y)` instead.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

namespace prism::sdk::dialect {

// R(x)'s check: a literal whose float rounding differs from its double one
// would mean different numbers in GLSL's real(x) and C++'s.
consteval double exact_in_float(double x) {
  if (double(float(x)) != x) throw "R(x): the literal is not exact in float; use a named constant";
  return x;
}

}  // namespace prism::sdk::dialect

// The prelude of each precision: the types and the few functions whose
// C++ and GLSL spellings differ.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace prism::sdk::f64 {
namespace {
using real = double;
using real2 = glm::dvec2;
using real3 = glm::dvec3;
using real4 = glm::dvec4;
#include "prism/sdk/dialect_prelude.inc"
}  // namespace
}  // namespace prism::sdk::f64
namespace prism::sdk::f32 {
namespace {
using real = float;
using real2 = glm::vec2;
using real3 = glm::vec3;
using real4 = glm::vec4;
#include "prism/sdk/dialect_prelude.inc"
}  // namespace
}  // namespace prism::sdk::f32
#pragma GCC diagnostic pop
