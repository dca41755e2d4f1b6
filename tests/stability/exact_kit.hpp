// What a primitive's oracle is made of (plugins/<type>/<type>_cases.cpp):
// quad-precision vector arithmetic, the recentred ray, a hit in the local
// frame, the reading of an object's own fields, and the clipped general
// quadric that sphere, quadric, cylinder and cone share. exact.cpp does the
// rest for every type (the frame, the rotation, the closest hit); the method
// is described there.
#pragma once

#include <functional>
#include <initializer_list>
#include <set>
#include <string>
#include <vector>

#include "exact.hpp"

namespace prism::stability {

constexpr real kEps = 0x1p-112;  // FLT128_EPSILON (no Q literals: CMAKE_CXX_EXTENSIONS is OFF)
constexpr real kInf = __builtin_huge_valq();

inline Vec operator+(const Vec& a, const Vec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec operator-(const Vec& a, const Vec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec operator*(real s, const Vec& a) { return {s * a.x, s * a.y, s * a.z}; }
inline real dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline real norm(const Vec& a) { return sqrtq(dot(a, a)); }
inline real qabs(real v) { return fabsq(v); }
inline real qmax(real a, real b) { return a > b ? a : b; }
inline real qmin(real a, real b) { return a < b ? a : b; }
inline real& at(Vec& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
inline real at(const Vec& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
inline Vec normalized(const Vec& a) {
  real n = norm(a);
  return n > 0 ? (1 / n) * a : a;
}

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
inline Recentred recentre(const Vec& o, const Vec& d) {
  real t0 = -dot(o, d);
  return {o + t0 * d, d, t0, norm(o)};
}

// One object's own fields, read from its JSON entry as Prism reads them
// (double, then widened exactly). Every field an oracle reads counts as
// known; unknown_fields() names the others, so an oracle's field list is the
// fields it reads and nothing else.
class ObjectFields {
 public:
  explicit ObjectFields(const nlohmann::json& object) : object_(object) {}
  [[noreturn]] static void fail(const std::string& path, const std::string& what);
  bool has(const char* key) const { return object_.contains(key); }
  real number(const char* key);                  // required
  real number(const char* key, real fallback);   // optional
  Vec vec3(const char* key);                     // required
  // Required array of n numbers; `allow_null`: null entries read as +kInf.
  std::vector<real> numbers(const char* key, std::size_t n, bool allow_null = false);
  // The fields no oracle read but `also_known`.
  std::vector<std::string> unknown_fields(const std::set<std::string>& also_known) const;

 private:
  const nlohmann::json& field(const char* key);
  const nlohmann::json& object_;
  std::set<std::string> read_;
};

// Reading a JSON number, vector or array of numbers (`path` names it in errors).
real json_number(const nlohmann::json& j, const std::string& path);
std::vector<real> json_numbers(const nlohmann::json& j, const std::string& path, std::size_t n,
                               bool allow_null = false);
Vec json_vec3(const nlohmann::json& j, const std::string& path);

// A primitive's oracle for one object: its first hit and its distance from a
// point, both in the object's local frame (the world frame for a type that
// is not transformable), and its size (radius, largest half size, R + r,
// ...; 1 for an unbounded one).
struct OracleShape {
  std::function<LocalHit(const Vec& o, const Vec& d, real tmin)> hit;
  std::function<real(const Vec& p)> distance;
  real size = 1;
};

// Reads and checks the type's own fields (throwing std::invalid_argument
// through ObjectFields::fail) and returns its oracle.
using OracleMaker = std::function<OracleShape(ObjectFields& fields)>;

// ---------------------------------------------------------------- the quadric

// f(p) = A x^2 + B y^2 + C z^2 + D xy + E yz + F xz + G x + H y + I z + J,
// clipped to lo <= p <= hi (infinite bounds: unclipped).
struct Quadric {
  real c[10];  // A..J
  real lo[3], hi[3];
};

// A quadric clipped to ymin <= y <= ymax only.
Quadric make_quadric(std::initializer_list<real> coefficients, real ymin, real ymax);

real quadric_f(const real* c, const Vec& p);
Vec quadric_grad(const real* c, const Vec& p);

// The quadratic a s^2 + b s + c in quad with the stable pair q/a, c/q (a ==
// 0 exactly: linear), a discriminant within quad rounding of 0 counted as a
// double root, then up to 3 Newton steps on f itself; the first root with
// t > tmin inside the clip box.
LocalHit quadric_hit(const Quadric& q, const Vec& o_local, const Vec& d, real tmin);

// |f| / |grad f| at p: the distance to first order.
real quadric_distance(const Quadric& q, const Vec& p);

// The oracle of a quadric of size `size`.
OracleShape quadric_oracle(const Quadric& q, real size);

}  // namespace prism::stability
