// The shared pieces of the primitives' oracles (exact_kit.hpp).
#include "exact_kit.hpp"

#include <cmath>
#include <stdexcept>

namespace prism::stability {

using json = nlohmann::json;

void ObjectFields::fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what);
}

real json_number(const json& j, const std::string& path) {
  if (!j.is_number()) ObjectFields::fail(path, "must be a number");
  double v = j.get<double>();
  if (!std::isfinite(v)) ObjectFields::fail(path, "must be finite");
  return static_cast<real>(v);
}

std::vector<real> json_numbers(const json& j, const std::string& path, std::size_t n, bool allow_null) {
  if (!j.is_array() || j.size() != n)
    ObjectFields::fail(path, "must be an array of " + std::to_string(n) + " numbers");
  std::vector<real> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (allow_null && j[i].is_null())
      out.push_back(kInf);  // the caller picks the sign
    else
      out.push_back(json_number(j[i], path + "[" + std::to_string(i) + "]"));
  }
  return out;
}

Vec json_vec3(const json& j, const std::string& path) {
  auto v = json_numbers(j, path, 3);
  return {v[0], v[1], v[2]};
}

const json& ObjectFields::field(const char* key) {
  auto it = object_.find(key);
  if (it == object_.end()) fail(key, "required");
  read_.insert(key);
  return *it;
}

real ObjectFields::number(const char* key) { return json_number(field(key), key); }

real ObjectFields::number(const char* key, real fallback) {
  read_.insert(key);
  auto it = object_.find(key);
  return it == object_.end() ? fallback : json_number(*it, key);
}

Vec ObjectFields::vec3(const char* key) { return json_vec3(field(key), key); }

std::vector<real> ObjectFields::numbers(const char* key, std::size_t n, bool allow_null) {
  return json_numbers(field(key), key, n, allow_null);
}

std::vector<std::string> ObjectFields::unknown_fields(const std::set<std::string>& also_known) const {
  std::vector<std::string> unknown;
  for (auto it = object_.begin(); it != object_.end(); ++it)
    if (!read_.count(it.key()) && !also_known.count(it.key())) unknown.push_back(it.key());
  return unknown;
}

// ---------------------------------------------------------------- the quadric

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

real quadric_f(const real* c, const Vec& p) {
  return c[0] * p.x * p.x + c[1] * p.y * p.y + c[2] * p.z * p.z + c[3] * p.x * p.y + c[4] * p.y * p.z +
         c[5] * p.x * p.z + c[6] * p.x + c[7] * p.y + c[8] * p.z + c[9];
}

namespace {

// Sum of the terms' magnitudes: the scale of the rounding in quadric_f.
real quadric_f_scale(const real* c, const Vec& p) {
  return qabs(c[0] * p.x * p.x) + qabs(c[1] * p.y * p.y) + qabs(c[2] * p.z * p.z) + qabs(c[3] * p.x * p.y) +
         qabs(c[4] * p.y * p.z) + qabs(c[5] * p.x * p.z) + qabs(c[6] * p.x) + qabs(c[7] * p.y) +
         qabs(c[8] * p.z) + qabs(c[9]);
}

}  // namespace

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

real quadric_distance(const Quadric& q, const Vec& p) {
  real f = quadric_f(q.c, p);
  real g = norm(quadric_grad(q.c, p));
  if (f == 0) return 0;
  return g > 0 ? qabs(f) / g : kInf;
}

OracleShape quadric_oracle(const Quadric& q, real size) {
  OracleShape shape;
  shape.hit = [q](const Vec& o, const Vec& d, real tmin) { return quadric_hit(q, o, d, tmin); };
  shape.distance = [q](const Vec& p) { return quadric_distance(q, p); };
  shape.size = size;
  return shape;
}

}  // namespace prism::stability
