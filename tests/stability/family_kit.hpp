// What a primitive's stiff families are made of (plugins/<type>/<type>_cases.cpp):
// double vectors, unit directions that stay unit in double, the rotation of
// the scene format, the suite's portable random numbers, rays aimed at
// points, and the builder that turns a parameter sweep into cases
// (families.hpp). Geometry here is plain double: a family only has to land
// rays near the hard spots; the right answer is the oracle's business.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "families.hpp"

namespace prism::stability {

constexpr double kPi = 3.14159265358979323846;

struct V {
  double x = 0, y = 0, z = 0;
};
inline V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V operator-(V a) { return {-a.x, -a.y, -a.z}; }
inline V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(V a) { return std::sqrt(dot(a, a)); }
inline V normalize(V a) { return (1.0 / length(a)) * a; }
inline nlohmann::json to_json(V a) { return nlohmann::json::array({a.x, a.y, a.z}); }

// `prism trace` normalises a direction on read as dir / sqrt(x*x + y*y + z*z)
// in double. A direction whose double length is exactly 1 passes unchanged,
// so the ray the backend traces is bit for bit the ray the oracle solves. A
// zero component stays zero (only the largest one is ever nudged).
V unit_in_double(V d);

// A local-to-world rotation, built the way the scene format defines
// {"axis": a, "degrees": deg} (right-hand rule about the normalised axis).
struct Rotation {
  V axis{0, 1, 0};
  double degrees = 0;
  bool identity = true;
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Rotation() = default;
  Rotation(V a, double deg);
  V apply(V v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  nlohmann::json json() const { return {{"axis", to_json(axis)}, {"degrees", degrees}}; }
};

extern const Rotation kTilted;  // the rotation of the "rotated" families
extern const V kCenterA;        // a centre off the origin that many families use

// mt19937_64 is specified to the bit; the doubles are drawn from its output
// directly (the standard distributions are not portable).
class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}
  double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double range(double a, double b) { return a + (b - a) * uniform(); }
  double sign() { return uniform() < 0.5 ? -1.0 : 1.0; }
  int index(int n) { return std::min(n - 1, int(uniform() * n)); }
  V unit();
  V tangent(V n);                      // a unit vector perpendicular to `n` (unit), uniform in angle
  V cone(V n, double lo, double hi);  // a unit vector whose cosine with `n` lies in [lo, hi]

 private:
  std::mt19937_64 engine_;
};

// `object` with its "center" and (unless the identity) its "rotation".
nlohmann::json placed(nlohmann::json object, V center, const Rotation& rot);

// A ray with its direction made unit in double (unit_in_double).
Ray make_ray(V origin, V dir, double tmin = 0);
// A ray from `L` before `target` along `dir` (the target is hit at t ≈ L).
Ray ray_to(V target, V dir, double L);

struct SurfacePoint {
  V p, n;  // local point and outward unit normal
};

// One object of a type with its placement, and a sampler of its surface, for
// the families every type shares (families.cpp).
struct Shape {
  nlohmann::json object;
  V center;  // world = center + rot(local)
  Rotation rot;
  V mid;            // local middle of the object (what "far from it" is measured from)
  double size = 1;  // bounding radius about `mid`
  std::function<SurfacePoint(Rng&)> sample;

  V world(V local) const { return center + rot.apply(local); }
  V world_dir(V local) const { return normalize(rot.apply(local)); }
};

// A type's object of characteristic size `s` (radius, largest half size,
// ...) at `center` turned by `rot`: fills object, mid, size and sample.
using ShapeMaker = std::function<void(Shape& shape, double s)>;

// ---------------------------------------------------------------- the family builder

struct Sweep {
  std::string key;           // parameter name, e.g. "angle"
  std::vector<double> full;  // every value
  double quick;              // the one quick mode uses
};

using CaseMaker = std::function<Case(double value, int rays, Rng& rng)>;

struct Builder {
  Mode mode;
  std::vector<Family>* out;
  int rays() const { return mode == Mode::quick ? 48 : 256; }
  // One family "<primitive>.<name>": a case per value of the sweep (the
  // quick value only in quick mode), each drawn from its own fixed seed.
  void add(const std::string& primitive, const std::string& name, const std::string& description, const Sweep& sweep,
           const CaseMaker& make);
};

}  // namespace prism::stability
