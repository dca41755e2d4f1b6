// The stability suite's oracle: exact first hits in quad precision.
//
// Method (independent of the plugins, ~34 significant digits):
// - Every number of the object is read as a double (as Prism reads it) and
//   widened exactly; the rotation is built in quad (exact for multiples of
//   90 degrees); the ray is taken into the local frame with R^T (R is
//   orthonormal to quad precision, so t stays the world distance).
// - The origin is moved to the foot of the perpendicular from the local origin
//   (one quad rounding, ~1e-34 * |origin|), so every later quantity is formed
//   from numbers of the object's size even for an origin 1e6 away.
// - sphere, quadric, cylinder, cone: the quadratic a s^2 + b s + c in quad with
//   the stable pair q/a, c/q (a == 0 exactly: linear), a discriminant within
//   quad rounding of 0 counted as a double root (a tangent ray hits), then up
//   to 3 Newton steps on f(o + s d) itself (kept only while |f| decreases);
//   roots in increasing order, the first with t > tmin inside the clip box.
// - plane, ring: the linear equation; box: the slab method (entry if
//   t > tmin, else the exit: a ray starting inside hits the exit face, as
//   plugins/box/box.cpp does; the spec is silent).
// - torus: no quartic coefficients at all. The signed distance to the tube
//   g(s) = sqrt((rho - R)^2 + y^2) - r (same sign as the spec's quartic, and
//   1-Lipschitz in s) is sampled along the chord of the bounding sphere with
//   steps max(h, 0.9 |g|), h = L/64 with L = min(r, R - r) (a longer step
//   cannot skip a root: |g'| <= 1). A sign change is solved by safeguarded
//   Newton-bisection on g to full precision. Where two samples of equal sign
//   come within 4 h^2 / L of zero (4x the deepest dip that can hide between
//   them, as |g''| <= 1/r + 1/(R - r) <= 2/L near the surface), the
//   extremum of g between them is located by bisection on g' and tested: a
//   value within quad rounding of 0 is a tangent (double) root, one of the
//   other sign splits the piece into two brackets.
#include "exact.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <set>
#include <stdexcept>

namespace prism::stability {
namespace {

using json = nlohmann::json;

// No Q literals: the project builds with CMAKE_CXX_EXTENSIONS OFF.
const real kEps = ldexpq(1, -112);  // FLT128_EPSILON
const real kPi = acosq(-1);
const real kInf = HUGE_VALQ;

Vec operator+(const Vec& a, const Vec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(const Vec& a, const Vec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(real s, const Vec& a) { return {s * a.x, s * a.y, s * a.z}; }
real dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
real norm(const Vec& a) { return sqrtq(dot(a, a)); }
real qabs(real v) { return fabsq(v); }
real qmax(real a, real b) { return a > b ? a : b; }
real qmin(real a, real b) { return a < b ? a : b; }
real& at(Vec& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
real at(const Vec& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
Vec normalized(const Vec& a) {
  real n = norm(a);
  return n > 0 ? (1 / n) * a : a;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what);
}

real number(const json& j, const std::string& path) {
  if (!j.is_number()) fail(path, "must be a number");
  double v = j.get<double>();
  if (!std::isfinite(v)) fail(path, "must be finite");
  return static_cast<real>(v);
}

const json& field(const json& obj, const char* key) {
  auto it = obj.find(key);
  if (it == obj.end()) fail(key, "required");
  return *it;
}

real number_field(const json& obj, const char* key, real fallback = kInf) {
  auto it = obj.find(key);
  if (it == obj.end()) {
    if (fallback == kInf) fail(key, "required");
    return fallback;
  }
  return number(*it, key);
}

std::vector<real> numbers(const json& j, const std::string& path, std::size_t n, bool allow_null = false) {
  if (!j.is_array() || j.size() != n) fail(path, "must be an array of " + std::to_string(n) + " numbers");
  std::vector<real> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (allow_null && j[i].is_null())
      out.push_back(kInf);  // the caller picks the sign
    else
      out.push_back(number(j[i], path + "[" + std::to_string(i) + "]"));
  }
  return out;
}

Vec vec3(const json& j, const std::string& path) {
  auto v = numbers(j, path, 3);
  return {v[0], v[1], v[2]};
}

// ---------------------------------------------------------------- shapes

struct Quadric {
  real c[10];  // A..J
  real lo[3], hi[3];
};

// The parameters of one object, parsed from its JSON (the header keeps only
// the JSON, so each query re-reads the few numbers it needs).
struct Shape {
  real radius = 0, height = 0;
  real half[3] = {0, 0, 0};
  real major = 0, minor = 0;
  real inner = 0, outer = 0;
  Vec point, normal;
  Quadric quadric{};
};

Quadric make_quadric(std::initializer_list<real> coefficients, real ymin, real ymax) {
  Quadric q{};
  int i = 0;
  for (real v : coefficients) q.c[i++] = v;
  for (int k = 0; k < 3; ++k) {
    q.lo[k] = -kInf;
    q.hi[k] = kInf;
  }
  q.lo[1] = ymin;
  q.hi[1] = ymax;
  return q;
}

Shape parse_shape(const std::string& type, const json& o) {
  Shape s;
  if (type == "sphere") {
    s.radius = number_field(o, "radius");
    s.quadric = make_quadric({1, 1, 1, 0, 0, 0, 0, 0, 0, -s.radius * s.radius}, -kInf, kInf);
  } else if (type == "plane") {
    s.point = vec3(field(o, "point"), "point");
    s.normal = vec3(field(o, "normal"), "normal");
  } else if (type == "box") {
    auto h = numbers(field(o, "half_size"), "half_size", 3);
    for (int i = 0; i < 3; ++i) s.half[i] = h[i];
  } else if (type == "torus") {
    s.major = number_field(o, "major_radius");
    s.minor = number_field(o, "minor_radius");
  } else if (type == "ring") {
    s.inner = number_field(o, "inner_radius", 0);
    s.outer = number_field(o, "outer_radius");
  } else if (type == "quadric") {
    auto c = numbers(field(o, "coefficients"), "coefficients", 10);
    for (int i = 0; i < 10; ++i) s.quadric.c[i] = c[i];
    std::vector<real> lo{kInf, kInf, kInf}, hi{kInf, kInf, kInf};
    if (auto it = o.find("clip_min"); it != o.end()) lo = numbers(*it, "clip_min", 3, true);
    if (auto it = o.find("clip_max"); it != o.end()) hi = numbers(*it, "clip_max", 3, true);
    for (int i = 0; i < 3; ++i) {
      s.quadric.lo[i] = lo[i] == kInf ? -kInf : lo[i];
      s.quadric.hi[i] = hi[i];
    }
  } else if (type == "cylinder" || type == "cone") {
    s.radius = number_field(o, "radius");
    s.height = number_field(o, "height");
    if (type == "cylinder") {
      s.quadric = make_quadric({1, 0, 1, 0, 0, 0, 0, 0, 0, -s.radius * s.radius}, 0, s.height);
    } else {
      // -(radius/height)^2 with a single rounding: the squares of doubles are exact in quad.
      real k2 = (s.radius * s.radius) / (s.height * s.height);
      s.quadric = make_quadric({1, -k2, 1, 0, 0, 0, 0, 0, 0, 0}, 0, s.height);
    }
  } else {
    fail("type", "unknown object type '" + type + "'");
  }
  return s;
}

void validate(const std::string& type, const json& o, const Shape& s) {
  static const std::set<std::string> kCommon = {"type", "material", "center", "rotation"};
  std::set<std::string> allowed;
  if (type == "sphere") allowed = {"radius"};
  if (type == "plane") allowed = {"point", "normal", "uv_scale"};
  if (type == "box") allowed = {"half_size"};
  if (type == "torus") allowed = {"major_radius", "minor_radius"};
  if (type == "ring") allowed = {"inner_radius", "outer_radius"};
  if (type == "quadric") allowed = {"coefficients", "clip_min", "clip_max"};
  if (type == "cylinder" || type == "cone") allowed = {"radius", "height"};
  for (auto it = o.begin(); it != o.end(); ++it) {
    const std::string& key = it.key();
    bool common = kCommon.count(key) && !(type == "plane" && (key == "center" || key == "rotation"));
    if (!common && !allowed.count(key)) fail(key, "unknown field for a " + type);
  }
  if (o.contains("material") && !o["material"].is_string()) fail("material", "must be a string");
  auto positive = [](real v, const char* what) {
    if (!(v > 0)) fail(what, "must be > 0");
  };
  if (type == "sphere") positive(s.radius, "radius");
  if (type == "plane") {
    if (s.normal.x == 0 && s.normal.y == 0 && s.normal.z == 0) fail("normal", "must be non-zero");
    if (o.contains("uv_scale")) positive(number(o["uv_scale"], "uv_scale"), "uv_scale");
  }
  if (type == "box")
    for (real h : s.half) positive(h, "half_size");
  if (type == "torus") {
    positive(s.minor, "minor_radius");
    if (!(s.minor < s.major)) fail("minor_radius", "must be < major_radius");
  }
  if (type == "ring") {
    if (!(s.inner >= 0)) fail("inner_radius", "must be >= 0");
    if (!(s.outer > s.inner)) fail("outer_radius", "must be > inner_radius");
  }
  if (type == "quadric") {
    bool any = false;
    for (int i = 0; i < 9; ++i) any = any || s.quadric.c[i] != 0;
    if (!any) fail("coefficients", "A..I must not all be 0");
    for (int i = 0; i < 3; ++i)
      if (!(s.quadric.lo[i] <= s.quadric.hi[i])) fail("clip_min", "must be <= clip_max");
  }
  if (type == "cylinder" || type == "cone") {
    positive(s.radius, "radius");
    positive(s.height, "height");
  }
}

// ---------------------------------------------------------------- rotation

void rotation_from_json(const json& r, real m[3][3]) {
  if (!r.is_object()) fail("rotation", "must be an object");
  if (r.contains("quaternion")) {
    if (r.size() != 1) fail("rotation", "either quaternion or axis and degrees");
    auto q = numbers(r["quaternion"], "rotation.quaternion", 4);
    real n = sqrtq(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n == 0) fail("rotation.quaternion", "must be non-zero");
    real w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    real rows[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                       {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                       {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = rows[i][j];
    return;
  }
  for (auto it = r.begin(); it != r.end(); ++it)
    if (it.key() != "axis" && it.key() != "degrees") fail("rotation." + it.key(), "unknown field");
  if (!r.contains("axis") || !r.contains("degrees")) fail("rotation", "needs axis and degrees (or quaternion)");
  Vec axis = vec3(r["axis"], "rotation.axis");
  if (axis.x == 0 && axis.y == 0 && axis.z == 0) fail("rotation.axis", "must be non-zero");
  axis = normalized(axis);
  real degrees = fmodq(number(r["degrees"], "rotation.degrees"), 360);  // exact
  real c, s;
  if (fmodq(degrees, 90) == 0) {  // exact quarter turns
    int k = static_cast<int>(degrees / 90);
    k = ((k % 4) + 4) % 4;
    const int cs[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    c = cs[k][0];
    s = cs[k][1];
  } else {
    real a = degrees * (kPi / 180);
    c = cosq(a);
    s = sinq(a);
  }
  real k = 1 - c, x = axis.x, y = axis.y, z = axis.z;
  // Rodrigues, right-hand rule: R = c I + s [axis]x + (1 - c) axis axis^T.
  real rows[3][3] = {{c + x * x * k, x * y * k - z * s, x * z * k + y * s},
                     {y * x * k + z * s, c + y * y * k, y * z * k - x * s},
                     {z * x * k - y * s, z * y * k + x * s, c + z * z * k}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = rows[i][j];
}

Vec apply(const real m[3][3], const Vec& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}
Vec apply_transposed(const real m[3][3], const Vec& v) {
  return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
          m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
}

// ---------------------------------------------------------------- local hits

// A hit in the local frame: t along the ray, the local outward normal (not
// normalised); `minus_dir` for a quadric point where grad f = 0.
struct LocalHit {
  bool hit = false;
  real t = 0;
  Vec n;
  bool minus_dir = false;
};

// The ray with its origin moved to the foot of the perpendicular from the
// local origin: point(s) = o + s d, t = t0 + s.
struct Recentred {
  Vec o, d;
  real t0;
  real origin_norm;  // |original local origin|, for rounding bounds
};
Recentred recentre(const Vec& o, const Vec& d) {
  real t0 = -dot(o, d);
  return {o + t0 * d, d, t0, norm(o)};
}

real quadric_f(const real* c, const Vec& p) {
  return c[0] * p.x * p.x + c[1] * p.y * p.y + c[2] * p.z * p.z + c[3] * p.x * p.y + c[4] * p.y * p.z +
         c[5] * p.x * p.z + c[6] * p.x + c[7] * p.y + c[8] * p.z + c[9];
}
// Sum of the terms' magnitudes: the scale of the rounding in quadric_f.
real quadric_f_scale(const real* c, const Vec& p) {
  return qabs(c[0] * p.x * p.x) + qabs(c[1] * p.y * p.y) + qabs(c[2] * p.z * p.z) + qabs(c[3] * p.x * p.y) +
         qabs(c[4] * p.y * p.z) + qabs(c[5] * p.x * p.z) + qabs(c[6] * p.x) + qabs(c[7] * p.y) +
         qabs(c[8] * p.z) + qabs(c[9]);
}
Vec quadric_grad(const real* c, const Vec& p) {
  return {2 * c[0] * p.x + c[3] * p.y + c[5] * p.z + c[6], 2 * c[1] * p.y + c[3] * p.x + c[4] * p.z + c[7],
          2 * c[2] * p.z + c[4] * p.y + c[5] * p.x + c[8]};
}

LocalHit quadric_hit(const Quadric& q, const Vec& o_local, const Vec& d, real tmin) {
  const real* c = q.c;
  Recentred r = recentre(o_local, d);
  const Vec& o = r.o;
  real a = c[0] * d.x * d.x + c[1] * d.y * d.y + c[2] * d.z * d.z + c[3] * d.x * d.y + c[4] * d.y * d.z +
           c[5] * d.x * d.z;
  Vec grad_o = quadric_grad(c, o);
  real b = dot(grad_o, d);
  real cc = quadric_f(c, o);

  real roots[2];
  int count = 0;
  bool polish = true;
  if (a == 0) {
    if (b == 0) return {};  // f constant along the ray: no isolated root (or the ray lies in the surface)
    roots[count++] = -cc / b;
  } else {
    real disc = b * b - 4 * a * cc;
    if (disc < 0) {
      // Within quad rounding of 0 (including the rounding of the recentred
      // origin): a tangent ray, one double root at the vertex.
      real dc = 32 * kEps * (quadric_f_scale(c, o) + norm(grad_o) * (r.origin_norm + norm(o)));
      if (disc < -(4 * qabs(a) * dc + 32 * kEps * b * b)) return {};
      roots[count++] = -b / (2 * a);
      polish = false;
    } else {
      real q2 = -(b + copysignq(sqrtq(disc), b)) / 2;
      if (q2 == 0) {
        roots[count++] = 0;  // b == 0 and c == 0: a double root at the foot
        polish = false;
      } else {
        roots[count++] = q2 / a;
        roots[count++] = cc / q2;
        if (disc == 0) polish = false;
      }
    }
  }
  for (int k = 0; k < count && polish; ++k) {
    real s = roots[k];
    real fs = quadric_f(c, o + s * d);
    for (int it = 0; it < 3 && fs != 0 && std::isfinite(static_cast<double>(s)); ++it) {
      real slope = dot(quadric_grad(c, o + s * d), d);
      if (slope == 0) break;
      real s2 = s - fs / slope;
      real f2 = quadric_f(c, o + s2 * d);
      if (!(qabs(f2) < qabs(fs))) break;
      s = s2;
      fs = f2;
    }
    roots[k] = s;
  }
  if (count == 2 && roots[1] < roots[0]) std::swap(roots[0], roots[1]);
  for (int k = 0; k < count; ++k) {
    real s = roots[k];
    if (isinfq(s) || isnanq(s)) continue;
    real t = r.t0 + s;
    if (!(t > tmin)) continue;
    Vec p = o + s * d;
    bool inside = true;
    for (int i = 0; i < 3; ++i) inside = inside && q.lo[i] <= at(p, i) && at(p, i) <= q.hi[i];
    if (!inside) continue;
    LocalHit h;
    h.hit = true;
    h.t = t;
    h.n = quadric_grad(c, p);
    h.minus_dir = h.n.x == 0 && h.n.y == 0 && h.n.z == 0;
    return h;
  }
  return {};
}

LocalHit box_hit(const real* half, const Vec& o_local, const Vec& d, real tmin) {
  Recentred r = recentre(o_local, d);
  real near = -kInf, far = kInf;
  int near_axis = 0, far_axis = 0;
  for (int i = 0; i < 3; ++i) {
    real di = at(d, i), oi = at(r.o, i), h = half[i];
    if (di == 0) {
      if (!(qabs(oi) <= h)) return {};
      continue;
    }
    real t0 = (-h - oi) / di, t1 = (h - oi) / di;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > near) {
      near = t0;
      near_axis = i;
    }
    if (t1 < far) {
      far = t1;
      far_axis = i;
    }
  }
  if (!(near <= far)) return {};
  real hmax = qmax(half[0], qmax(half[1], half[2]));
  real snap = 64 * kEps * (hmax + r.origin_norm);
  for (int pass = 0; pass < 2; ++pass) {
    real s = pass == 0 ? near : far;
    int axis = pass == 0 ? near_axis : far_axis;
    real t = r.t0 + s;
    if (!(t > tmin)) continue;
    Vec p = r.o + s * d;
    for (int i = 0; i < 3; ++i) {
      real h = half[i];
      if (i == axis) {
        bool entering = pass == 0;
        at(p, i) = ((at(d, i) > 0) == entering) ? -h : h;
      } else {
        real v = qmin(qmax(at(p, i), -h), h);
        if (h - qabs(v) <= snap) v = copysignq(h, v);  // an edge within rounding: the spec's tie rule
        at(p, i) = v;
      }
    }
    int a = 0;
    for (int i = 1; i < 3; ++i)
      if (qabs(at(p, i)) / half[i] > qabs(at(p, a)) / half[a]) a = i;
    LocalHit hit;
    hit.hit = true;
    hit.t = t;
    at(hit.n, a) = at(p, a) < 0 ? -1 : 1;
    return hit;
  }
  return {};
}

LocalHit ring_hit(real inner, real outer, const Vec& o_local, const Vec& d, real tmin) {
  if (d.y == 0) return {};  // parallel (or in the plane: zero thickness)
  Recentred r = recentre(o_local, d);
  real s = -r.o.y / d.y;
  real t = r.t0 + s;
  if (!(t > tmin)) return {};
  Vec p = r.o + s * d;
  real rho2 = p.x * p.x + p.z * p.z;
  if (rho2 < inner * inner || rho2 > outer * outer) return {};
  LocalHit h;
  h.hit = true;
  h.t = t;
  h.n = {0, 1, 0};
  return h;
}

// --- torus

struct TorusSample {
  real g;   // signed distance to the tube surface
  real dg;  // dg/ds
};

struct TorusRay {
  Vec o, d;
  real R, r;
  TorusSample at(real s) const {
    Vec p = o + s * d;
    real rho = sqrtq(p.x * p.x + p.z * p.z);
    real u = rho - R;
    real dist = sqrtq(u * u + p.y * p.y);
    TorusSample e{dist - r, 0};
    if (dist > 0) {
      real drho = rho > 0 ? (p.x * d.x + p.z * d.z) / rho : 0;
      e.dg = (u * drho + p.y * d.y) / dist;
    }
    return e;
  }
};

// The root of g in [a, b] (g(a), g(b) of opposite signs, neither 0):
// safeguarded Newton-bisection to full quad precision.
real torus_root(const TorusRay& tr, real a, real ga, real b) {
  real lo = a, hi = b;  // g(lo) has the sign of ga
  real sign = ga < 0 ? -1 : 1;
  real x = (a + b) / 2;
  TorusSample e = tr.at(x);
  for (int it = 0; it < 400; ++it) {
    if (e.g == 0) return x;
    if (sign * e.g > 0)
      lo = x;
    else
      hi = x;
    real next;
    bool newton = e.dg != 0;
    if (newton) {
      next = x - e.g / e.dg;
      newton = (next - lo) * (next - hi) < 0;  // strictly inside the bracket
    }
    if (!newton) next = (lo + hi) / 2;
    if (next == x || next == lo || next == hi) break;
    real step = qabs(next - x);
    x = next;
    e = tr.at(x);
    if (step <= 4 * kEps * (qabs(x) + tr.R)) {
      // Converged: one more Newton step if it lowers |g|.
      if (e.dg != 0) {
        real x2 = x - e.g / e.dg;
        TorusSample e2 = tr.at(x2);
        if (qabs(e2.g) < qabs(e.g)) x = x2;
      }
      return x;
    }
  }
  return x;
}

// The point of [a, b] where sigma * g has an interior minimum (sigma * g'
// going from < 0 to >= 0), by bisection on g'; false when there is none.
bool torus_extremum(const TorusRay& tr, real sigma, real a, const TorusSample& ea, real b, const TorusSample& eb,
                    real& m) {
  if (!(sigma * ea.dg < 0 && sigma * eb.dg >= 0)) return false;
  real lo = a, hi = b;
  for (int it = 0; it < 400; ++it) {
    real mid = (lo + hi) / 2;
    if (mid == lo || mid == hi) break;
    if (sigma * tr.at(mid).dg < 0)
      lo = mid;
    else
      hi = mid;
  }
  real glo = sigma * tr.at(lo).g, ghi = sigma * tr.at(hi).g;
  m = glo <= ghi ? lo : hi;
  return true;
}

LocalHit torus_hit(real R, real r, const Vec& o_local, const Vec& d, real tmin) {
  Recentred rc = recentre(o_local, d);
  real rb = (R + r) * (1 + real(1e-6));  // bounding sphere, slightly enlarged
  real m2 = dot(rc.o, rc.o);
  if (!(m2 < rb * rb)) return {};
  real half = sqrtq(rb * rb - m2);
  real s_start = qmax(-half, tmin - rc.t0);
  if (!(s_start < half)) return {};
  TorusRay tr{rc.o, d, R, r};
  // Feature scale: the tube radius, or the hole's half width for a fat torus
  // (near the surface |g''| <= 1/r + 1/(R - r) <= 2 / scale).
  const real scale = qmin(r, R - r);
  const real h = qmax(scale / 64, 1024 * kEps * (R + r));  // the floor only matters for absurdly thin tubes
  const real flag = 4 * h * h / scale;  // 4x the deepest dip two samples h apart can hide
  const real tol = 32 * kEps * (R + r + rc.origin_norm);

  auto hit_at = [&](real s) {
    LocalHit out;
    out.hit = true;
    out.t = rc.t0 + s;
    Vec p = rc.o + s * d;
    // The spec's normal: the gradient of (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + z^2).
    real k = 4 * (dot(p, p) + R * R - r * r), l = 8 * R * R;
    out.n = {k * p.x - l * p.x, k * p.y, k * p.z - l * p.z};
    return out;
  };
  auto accept = [&](real s) { return rc.t0 + s > tmin; };

  real sa = s_start;
  TorusSample ea = tr.at(sa);
  real sigma = ea.g < 0 ? -1 : 1;
  if (ea.g == 0) {
    if (accept(sa)) return hit_at(sa);
    // On the surface at tmin: the side the ray moves into.
    sigma = ea.dg < 0 ? -1 : (ea.dg > 0 ? 1 : (tr.at(sa + h / 1024).g < 0 ? -1 : 1));
  }
  while (sa < half) {
    real step = qmax(h, real(0.9) * qabs(ea.g));
    real sb = qmin(sa + step, half);
    TorusSample eb = tr.at(sb);
    if (sigma * eb.g < 0) {
      real s = torus_root(tr, sa, ea.g == 0 ? sigma : ea.g, sb);
      if (accept(s)) return hit_at(s);
    } else {
      if (qmin(qabs(ea.g), qabs(eb.g)) <= flag) {
        real m;
        if (torus_extremum(tr, sigma, sa, ea, sb, eb, m)) {
          real gm = tr.at(m).g;
          if (qabs(gm) <= tol) {
            if (accept(m)) return hit_at(m);  // tangent: a double root
          } else if (sigma * gm < 0) {
            real s = torus_root(tr, sa, ea.g == 0 ? sigma : ea.g, m);
            if (accept(s)) return hit_at(s);
            s = torus_root(tr, m, gm, sb);
            if (accept(s)) return hit_at(s);
          }
        }
      }
      if (eb.g == 0 && accept(sb)) return hit_at(sb);
    }
    sa = sb;
    ea = eb;
    if (ea.g != 0) sigma = ea.g < 0 ? -1 : 1;
  }
  return {};
}

// ---------------------------------------------------------------- distance

real box_distance(const real* half, const Vec& p) {
  real out2 = 0, inside = kInf;
  bool outside = false;
  for (int i = 0; i < 3; ++i) {
    real e = qabs(at(p, i)) - half[i];
    if (e > 0) {
      outside = true;
      out2 += e * e;
    }
    inside = qmin(inside, -e);
  }
  return outside ? sqrtq(out2) : inside;
}

}  // namespace

// ---------------------------------------------------------------- ExactObject

ExactObject::ExactObject(const nlohmann::json& object) : object_(object) {
  if (!object.is_object()) throw std::invalid_argument("object: must be a JSON object");
  auto it = object.find("type");
  if (it == object.end() || !it->is_string()) throw std::invalid_argument("type: required string");
  type_ = it->get<std::string>();
  try {
    Shape s = parse_shape(type_, object);
    validate(type_, object, s);
    center_ = {0, 0, 0};
    if (auto c = object.find("center"); c != object.end()) center_ = vec3(*c, "center");
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rotation_[i][j] = i == j ? 1 : 0;
    if (auto r = object.find("rotation"); r != object.end()) rotation_from_json(*r, rotation_);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("object (") + type_ + ")." + e.what());
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("object (") + type_ + "): " + e.what());
  }
}

ExactHit ExactObject::intersect(const ExactRay& ray) const {
  Shape s = parse_shape(type_, object_);
  ExactHit out;
  if (type_ == "plane") {
    real nd = dot(s.normal, ray.dir);
    if (nd == 0) return out;
    real t = dot(s.normal, s.point - ray.origin) / nd;
    if (!(t > ray.tmin) || isinfq(t) || isnanq(t)) return out;
    out.hit = true;
    out.t = t;
    out.normal = normalized(s.normal);
    return out;
  }
  Vec o = apply_transposed(rotation_, ray.origin - center_);
  Vec d = apply_transposed(rotation_, ray.dir);
  LocalHit h;
  if (type_ == "box")
    h = box_hit(s.half, o, d, ray.tmin);
  else if (type_ == "torus")
    h = torus_hit(s.major, s.minor, o, d, ray.tmin);
  else if (type_ == "ring")
    h = ring_hit(s.inner, s.outer, o, d, ray.tmin);
  else
    h = quadric_hit(s.quadric, o, d, ray.tmin);  // sphere, quadric, cylinder, cone
  if (!h.hit) return out;
  out.hit = true;
  out.t = h.t;
  out.normal = h.minus_dir ? Vec{-ray.dir.x, -ray.dir.y, -ray.dir.z} : normalized(apply(rotation_, h.n));
  return out;
}

real ExactObject::distance_to_surface(const Vec& world_point) const {
  Shape s = parse_shape(type_, object_);
  if (type_ == "plane") return qabs(dot(s.normal, world_point - s.point)) / norm(s.normal);
  Vec p = apply_transposed(rotation_, world_point - center_);
  if (type_ == "sphere") return qabs(norm(p) - s.radius);
  if (type_ == "box") return box_distance(s.half, p);
  if (type_ == "ring") {
    real rho = sqrtq(p.x * p.x + p.z * p.z);
    real e = rho < s.inner ? s.inner - rho : (rho > s.outer ? rho - s.outer : 0);
    return sqrtq(e * e + p.y * p.y);
  }
  if (type_ == "torus") {
    // Exact (the distance to the core circle minus r), not only first order.
    real u = sqrtq(p.x * p.x + p.z * p.z) - s.major;
    return qabs(sqrtq(u * u + p.y * p.y) - s.minor);
  }
  real f = quadric_f(s.quadric.c, p);
  real g = norm(quadric_grad(s.quadric.c, p));
  if (f == 0) return 0;
  return g > 0 ? qabs(f) / g : kInf;
}

real ExactObject::size() const {
  Shape s = parse_shape(type_, object_);
  if (type_ == "sphere") return s.radius;
  if (type_ == "box") return qmax(s.half[0], qmax(s.half[1], s.half[2]));
  if (type_ == "torus") return s.major + s.minor;
  if (type_ == "ring") return s.outer;
  if (type_ == "cylinder" || type_ == "cone") return qmax(s.radius, s.height);
  if (type_ == "quadric") {
    real m = 0;
    for (int i = 0; i < 3; ++i) {
      if (isinfq(s.quadric.lo[i]) || isinfq(s.quadric.hi[i])) return 1;
      m = qmax(m, qmax(qabs(s.quadric.lo[i]), qabs(s.quadric.hi[i])));
    }
    return m > 0 ? m : 1;
  }
  return 1;  // plane
}

ExactSceneHit closest_hit(const std::vector<ExactObject>& objects, const ExactRay& ray) {
  ExactSceneHit best;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    ExactHit h = objects[i].intersect(ray);
    if (h.hit && (best.object < 0 || h.t < best.t)) {
      best.object = static_cast<int>(i);
      best.t = h.t;
      best.normal = h.normal;
    }
  }
  return best;
}

ExactRay make_ray(const double origin[3], const double dir[3], double tmin) {
  ExactRay ray;
  ray.origin = {origin[0], origin[1], origin[2]};
  Vec d{dir[0], dir[1], dir[2]};
  real n = norm(d);
  if (!(n > 0) || isinfq(n)) throw std::invalid_argument("make_ray: direction must be non-zero and finite");
  ray.dir = (1 / n) * d;
  ray.tmin = tmin;
  return ray;
}

std::string to_string(real value, int digits) {
  digits = std::clamp(digits, 1, 60);
  char buf[128];
  int n = quadmath_snprintf(buf, sizeof buf, "%.*Qg", digits, value);
  if (n < 0) return "?";
  return std::string(buf, static_cast<std::size_t>(std::min<int>(n, sizeof buf - 1)));
}

}  // namespace prism::stability
