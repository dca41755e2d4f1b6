// Quadric primitive: f(p) = A x^2 + B y^2 + C z^2 + D xy + E yz + F xz
// + G x + H y + I z + J = 0 inside the clip box clip_min <= p <= clip_max
// (null entries: unbounded); the core applies `center` and `rotation`.
// Outward normal: grad f (negating every coefficient flips it); where the
// gradient vanishes the normal is all zeros and the core uses -dir.
//
// Numerics (prism/sdk/quadric_math.hpp, shared with cylinder and cone so
// that they give bit-identical t and normal)
// - The origin is moved to the foot of the perpendicular from the local
//   origin before b and c are formed, so a far camera does not swamp c with
//   |o|^2 terms.
// - Roots by the stable pair c/q, q/a with an fma-accurate discriminant; the
//   t^2 coefficient is tested against exactly 0 (linear case) and nothing
//   else, so a tiny `a` keeps an accurate near root and sends the far one
//   towards infinity (non-finite roots are rejected).
// - First root in (tmin, tmax] whose point lies in the clip box, else the far
//   one; the point is formed in the re-centred frame and pulled onto f = 0 by
//   one Newton step along the gradient in `surface`.
// - clip_min/clip_max are coordinates (PRISM_FIELD_LENGTH): the core checks
//   |x| <= 1e7 on the numbers only, and a null entry reads as -inf / +inf.
// - intersect and surface are written once, for the CPU and the GPU, in
//   quadric.shared.glsl, on the module prism/sdk/modules/quadric.shared.glsl
//   that cylinder and cone run too.
#include <algorithm>
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "prism/sdk/quadric_math.hpp"
#include "prism/sdk/shared_plugin.hpp"
#include "quadric.shared.glsl.hpp"

#define PRISM_SHARED_SOURCE "quadric.shared.glsl"
#include "prism/sdk/instantiate.hpp"

namespace {

using namespace prism::sdk;

using QuadricRecord = QuadricShape;
static_assert(sizeof(QuadricRecord) % 16 == 0);

const double kNoMin[] = {-kInf, -kInf, -kInf};
const double kNoMax[] = {kInf, kInf, kInf};

const PrismField kFields[] = {
    {"coefficients", PRISM_FIELD_ARRAY, 10, PRISM_FIELD_REQUIRED, -kInf, kInf, 0.0, nullptr,
     "[A..J] of Ax^2 + By^2 + Cz^2 + Dxy + Eyz + Fxz + Gx + Hy + Iz + J = 0; A..I not all 0"},
    {"clip_min", PRISM_FIELD_ARRAY_OR_NULL, 3, PRISM_FIELD_LENGTH, -kInf, kInf, -kInf, kNoMin,
     "lower corner of the local-frame box the surface is clipped to; null: no limit"},
    {"clip_max", PRISM_FIELD_ARRAY_OR_NULL, 3, PRISM_FIELD_LENGTH, -kInf, kInf, kInf, kNoMax,
     "upper corner of that box, each entry >= clip_min's; null: no limit"},
};

int validate(const double* values, PrismError* err) {
  bool any = false;
  for (int i = 0; i < 9; ++i) any = any || values[i] != 0.0;
  if (!any) return fail(err, "coefficients", "A..I (the first 9) must not all be 0");
  const double* lo = values + 10;
  const double* hi = values + 13;
  for (int i = 0; i < 3; ++i)
    if (!(lo[i] <= hi[i]))
      return fail(err, "clip_max", "entry %d must be >= clip_min (%s), got %s", i, format_number(lo[i]).text,
                  format_number(hi[i]).text);
  return 0;
}

// f and s f have the same surface for any s != 0, but the intersector's
// products of coefficients underflow near 1e-200 (noise) and overflow near
// 1e200 (nothing). Dividing by the power of two nearest the largest
// |coefficient| makes every record's largest coefficient lie in [1, 2) at
// no cost in precision (a power of two scales exactly unless a coefficient
// falls below the normal range), for the CPU and the GLSL intersector alike.
void normalise_coefficients(double coef[10]) {
  double largest = 0.0;
  for (int i = 0; i < 10; ++i) largest = std::max(largest, std::abs(coef[i]));
  if (!(largest > 0.0) || !std::isfinite(largest)) return;  // validate() refused all-zero A..I
  const int exponent = std::ilogb(largest);
  for (int i = 0; i < 10; ++i) coef[i] = std::ldexp(coef[i], -exponent);
}

void pack(const double* values, void* record) {
  double coef[10];
  std::copy(values, values + 10, coef);
  normalise_coefficients(coef);
  *static_cast<QuadricRecord*>(record) = make_quadric(coef, values + 10, values + 13);
}

int bounds(const void* record, double lo[3], double hi[3]) {
  return quadric_bounds(record_of<QuadricRecord>(record), lo, hi) ? 1 : 0;
}

const PrismPrimitiveDesc kDesc =
    describe_primitive<PRISM_SHARED_INTERSECT(quadric_intersect)>(
        "quadric", PRISM_PRIMITIVE_TRANSFORMABLE, kFields, sizeof(QuadricRecord), validate, pack, bounds,
        f64::abi_surface<f64::quadric_surface>, kPluginGlsl, "quadric", refine_quadric_record);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
