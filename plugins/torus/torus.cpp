// Torus primitive: (|p|^2 + R^2 - r^2)^2 = 4 R^2 (p.x^2 + p.z^2), axis local
// y, 0 < r < R; the core applies `center` and `rotation`.
//
// Numerics (why not a closed-form quartic: see docs/numerics.md, Torus;
// closed forms lose everything for far origins, thin tubes and grazing rays)
// 1. Bounding sphere: the ray is clipped to the sphere of radius
//    (R + r)(1 + 1e-3) with the robust discriminant, and the origin is moved
//    to the chord's midpoint (the foot of the perpendicular), in double. A
//    camera 1e4 or 1e6 away then loses nothing, and the quartic is built from
//    numbers of the torus's size.
// 2. Scale by 1/R: in s = (t - t_f)/R the quartic f(s) is monic with O(1)
//    coefficients. Its roots are isolated on the chord [-H, H] by the
//    derivative sequence: roots of the quadratic f'' split the cubic f' into
//    monotone pieces, each sign change of f' is solved by safeguarded
//    Newton-bisection, and those critical points split f into monotone
//    pieces, each holding at most one root. Critical points are well
//    conditioned (f'' = O(1) there) even where f itself is not.
// 3. Signs and roots come from the signed distance to the tube,
//    g(s) = sqrt((sqrt(x^2 + z^2) - 1)^2 + y^2) - r/R, not from the expanded
//    quartic: g
//    has the same sign as f everywhere (f = A*B with A = dist^2 - (r/R)^2 and
//    B > 0 for r < R), but no cancellation: for r/R = 1e-3 the quartic loses
//    ~6 digits near the tube while g keeps full precision, and |g'| <= 1.
//    Each bracketed sign change of g is solved by safeguarded
//    Newton-bisection on g itself, which doubles as the final polish.
// 4. Pieces are visited in order and only as far as needed: the first root
//    with tmin < t <= tmax wins, tested on t itself (not on a rounded s).
//    A grazing touch (g == 0 at a critical point) counts as a hit.
// 5. surface: the stored point is re-projected onto the tube (nearest point
//    of the core circle plus r along the radial direction) and the normal is
//    that radial direction, which is parallel to the spec's gradient.
// 6. GPU: torus.glsl, the same steps in GLSL double precision, with the
//    Newton-bisection of the shared module `roots` (prism/sdk/shared/roots.shared.glsl),
//    which solve_bracketed runs on the CPU too.
#include <cmath>

#include "prism/primitive_abi.h"
#include "prism/sdk/math.hpp"
#include "prism/sdk/primitive_sdk.hpp"
#include "torus.glsl.hpp"

namespace {

using namespace prism::sdk;

struct TorusRecord {
  double major;  // R
  double minor;  // r
  double pad[2];
};
static_assert(sizeof(TorusRecord) % 16 == 0);
static_assert(glsl_define(kPluginGlsl, "TORUS_MAJOR") == offsetof(TorusRecord, major) / sizeof(double));
static_assert(glsl_define(kPluginGlsl, "TORUS_MINOR") == offsetof(TorusRecord, minor) / sizeof(double));

const PrismField kFields[] = {
    positive_length("major_radius", 1, "R: distance from the local y axis to the centre circle of the tube"),
    positive_length("minor_radius", 1, "r: radius of the tube; must be < major_radius"),
};

int validate(const double* values, PrismError* err) {
  if (values[1] < values[0]) return 0;
  return fail(err, "minor_radius", "must be < major_radius (%s), got %s", format_number(values[0]).text,
              format_number(values[1]).text);
}

void pack(const double* values, void* record) {
  *static_cast<TorusRecord*>(record) = TorusRecord{values[0], values[1], {0.0, 0.0}};
}

int bounds(const void* record, double lo[3], double hi[3]) {
  const auto& rec = record_of<TorusRecord>(record);
  double outer = rec.major + rec.minor;
  const double extent[3] = {outer, rec.minor, outer};
  for (int i = 0; i < 3; ++i) {
    lo[i] = -extent[i];
    hi[i] = extent[i];
  }
  return 1;
}

// Newton stops once a step is below these (in units of R); the step just
// taken leaves an error ~K * step^2, far below double resolution. A critical
// point off by 1e-9 changes f's extremum by ~1e-18, so it still separates
// any root pair that double precision can tell apart.
constexpr double kCriticalTol = 1e-9;
constexpr double kRootTol = 1e-12;

// The ray in the scaled frame: p(s) = u + s d, torus with R = 1 and tube
// radius `tube` = r/R.
struct ScaledRay {
  glm::dvec3 u, d;
  double tube;
};

// Signed distance to the tube and its derivative along the ray.
void tube_distance(const ScaledRay& ray, double s, double& g, double& dg) {
  glm::dvec3 p = ray.u + s * ray.d;
  double radial = std::sqrt(p.x * p.x + p.z * p.z);
  double q = radial - 1.0;
  double dist = std::sqrt(q * q + p.y * p.y);
  g = dist - ray.tube;
  // d(radial)/ds is undefined on the axis; NaN sends the solver to bisection.
  double dradial = (p.x * ray.d.x + p.z * ray.d.z) / radial;
  dg = (q * dradial + p.y * ray.d.y) / dist;
}

// Monic quartic s^4 + c[3] s^3 + c[2] s^2 + c[1] s + c[0] of the torus along
// the scaled ray; only its derivatives are used (for critical points).
struct Quartic {
  double c[4];
  double d1(double s) const { return ((4.0 * s + 3.0 * c[3]) * s + 2.0 * c[2]) * s + c[1]; }
  double d2(double s) const { return (12.0 * s + 6.0 * c[3]) * s + 2.0 * c[2]; }
};

Quartic torus_quartic(const ScaledRay& ray) {
  const glm::dvec3& u = ray.u;
  const glm::dvec3& d = ray.d;
  double e = glm::dot(u, d);
  double k = glm::dot(u, u) + 1.0 - ray.tube * ray.tube;
  double dxz = d.x * d.x + d.z * d.z, exz = u.x * d.x + u.z * d.z, gxz = u.x * u.x + u.z * u.z;
  // (s^2 + 2es + k)^2 - 4 (dxz s^2 + 2 exz s + gxz), d unit.
  return Quartic{{k * k - 4.0 * gxz, 4.0 * e * k - 8.0 * exz, 4.0 * e * e + 2.0 * k - 4.0 * dxz, 4.0 * e}};
}

// Walks the chord's monotone pieces of f in order, given their ends one at a
// time, and stops at the first root of g with tmin < t <= tmax.
struct RootScan {
  const ScaledRay& ray;
  double tf, big, tmin, tmax;
  double a = 0.0, ga = 0.0;  // the previous break and g there
  bool done = false, found = false;
  double root = 0.0;

  double distance_at(double s) const {
    double v = 0.0, dv = 0.0;
    tube_distance(ray, s, v, dv);
    return v;
  }
  void start(double s) {
    a = s;
    ga = distance_at(s);
  }
  // Closes the piece [a, b]: at most one root, solved only if g changes sign
  // there and the piece reaches past tmin.
  void advance(double b) {
    if (done) return;
    double a0 = a, g0 = ga, gb = distance_at(b);
    a = b;
    ga = gb;
    if (tf + big * a0 > tmax) {
      done = true;
      return;
    }
    if ((g0 > 0.0) == (gb > 0.0) || tf + big * b <= tmin) return;
    auto g = [this](double s, double& v, double& dv) { tube_distance(ray, s, v, dv); };
    double s = solve_bracketed(g, a0, b, g0, gb, kRootTol * (1.0 + std::abs(b)));
    double t = tf + big * s;
    if (t > tmax) {
      done = true;
    } else if (t > tmin) {
      done = found = true;
      root = s;
    }
  }
};

// Feeds `scan` the critical points of f in [-h, h] in order, then h: the
// roots of the quadratic f'' split the cubic f' into monotone pieces, and
// each sign change of f' there is one critical point.
void scan_monotone_pieces(const Quartic& f, double h, RootScan& scan) {
  double r[2] = {0.0, 0.0};
  int n = solve_quadratic(12.0, 6.0 * f.c[3], 2.0 * f.c[2], r[0], r[1]);
  double ends[4] = {-h, 0.0, 0.0, 0.0};
  int count = 1;
  for (int i = 0; i < n; ++i)
    if (r[i] > -h && r[i] < h) ends[count++] = r[i];
  ends[count++] = h;
  auto d1 = [&f](double s, double& v, double& dv) {
    v = f.d1(s);
    dv = f.d2(s);
  };
  scan.start(-h);
  for (int i = 0; i + 1 < count && !scan.done; ++i) {
    double a = ends[i], b = ends[i + 1], fa = f.d1(a), fb = f.d1(b);
    if ((fa > 0.0) == (fb > 0.0)) continue;
    scan.advance(solve_bracketed(d1, a, b, fa, fb, kCriticalTol * (1.0 + std::abs(a))));
  }
  scan.advance(h);
}

int intersect(const void* record, const PrismRay* ray, double tmin, double tmax, PrismHit* hit) {
  const auto& rec = record_of<TorusRecord>(record);
  const double big = rec.major;
  glm::dvec3 o = load3(ray->origin), d = load3(ray->dir);
  double tf = foot_parameter(o, d);
  glm::dvec3 foot = o + tf * d;
  glm::dvec3 perp = foot - glm::dot(foot, d) * d;
  double bound = (rec.major + rec.minor) * (1.0 + 1e-3);  // slack: the outer equator touches R + r
  double half2 = bound * bound - glm::dot(perp, perp);
  if (!(half2 >= 0.0)) return 0;
  double h = std::sqrt(half2) / big;
  if (tf + big * h <= tmin || tf - big * h > tmax) return 0;

  ScaledRay sr{foot / big, d, rec.minor / big};
  RootScan scan{sr, tf, big, tmin, tmax};
  scan_monotone_pieces(torus_quartic(sr), h, scan);
  if (!scan.found) return 0;
  *hit = PrismHit{};
  hit->t = tf + big * scan.root;
  store3(foot + (big * scan.root) * d, hit->data);
  return 1;
}

// The signed distance from the tube, sqrt((rho - R)^2 + y^2) - r with rho the
// distance from the y axis, in long double (see prism/sdk/refine.hpp): it
// stays well scaled for thin tubes, where the quartic's value does not.
void refine(const void* record, const PrismRayExt* ray, PrismHit* hit) {
  const auto& rec = record_of<TorusRecord>(record);
  const long double major = rec.major, minor = rec.minor;
  auto tube_distance = [&](const Vec3x& p) {
    const long double rho = std::sqrt(p.x * p.x + p.z * p.z), off = rho - major;
    const long double q = std::sqrt(off * off + p.y * p.y);
    return ImplicitSample{q - minor, {off * p.x / (rho * q), p.y / q, off * p.z / (rho * q)}};
  };
  Vec3x p;
  if (polish_hit(*ray, *hit, tube_distance, &p)) store3(p, hit->data);
}

void surface(const void* record, const PrismRay*, const PrismHit* hit, PrismSurface* out) {
  const auto& rec = record_of<TorusRecord>(record);
  glm::dvec3 p = load3(hit->data);
  double radial = std::sqrt(p.x * p.x + p.z * p.z);
  glm::dvec3 normal(0.0);
  if (radial > 0.0) {
    glm::dvec3 core(rec.major * p.x / radial, 0.0, rec.major * p.z / radial);
    glm::dvec3 out_dir = p - core;
    double len = glm::length(out_dir);
    if (len > 0.0) {
      normal = out_dir / len;
      p = core + rec.minor * normal;
    }
  }
  double u = turn_fraction(p.z, p.x);
  double v = turn_fraction(p.y, std::sqrt(p.x * p.x + p.z * p.z) - rec.major);
  write_surface(out, p, normal, u, v);
}

const PrismPrimitiveDesc kDesc = describe_primitive<intersect>("torus", PRISM_PRIMITIVE_TRANSFORMABLE, kFields,
                                                       sizeof(TorusRecord), validate, pack, bounds, surface,
                                                       kPluginGlsl, "torus", refine);

}  // namespace

extern "C" PRISM_EXPORT const PrismPrimitiveDesc* prism_primitive_entry(void) { return &kDesc; }
