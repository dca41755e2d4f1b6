// Exact answers for the stability suite: the first hit of a ray on one of the
// scene format's primitives, in quad precision (__float128, ~34 digits), with
// a Newton polish of the root on the original implicit equation. Independent
// of the plugins: different algebra, far more precision.
//
// Objects are given as the scene file gives them (one entry of "objects"),
// numbers read as double (as Prism reads them) and then widened exactly.
// Each type's own part comes from its folder (plugins/<type>/<type>_cases.cpp).
#pragma once

#include <quadmath.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace prism::stability {

using real = __float128;

struct Vec {
  real x = 0, y = 0, z = 0;
};

struct OracleShape;  // a type's own part of the oracle (exact_kit.hpp)

struct ExactRay {
  Vec origin;
  Vec dir;  // unit length (normalise in quad precision before use)
  real tmin = 0;
};

struct ExactHit {
  bool hit = false;
  real t = 0;
  Vec normal;  // outward unit normal in world space, as the spec defines it
};

class ExactObject {
 public:
  // `object`: {"type": "torus", "center": [...], "rotation": {...}, ...}.
  // Throws std::invalid_argument for a type or field it does not know (a
  // type is known when a case module has its oracle: primitive_cases.hpp).
  explicit ExactObject(const nlohmann::json& object);

  // The first hit with t > ray.tmin, per the spec's definition of the shape
  // (clipping, both sides, the far root when the near one is clipped away).
  ExactHit intersect(const ExactRay& ray) const;

  // Distance of a world point from the surface, in world units (for the
  // "reported point off the surface" measure): exact for sphere, plane, box,
  // ring and torus; |f| / |grad f| at the point (first order) for quadrics.
  real distance_to_surface(const Vec& world_point) const;

  // The object's size: radius, largest half size, R + r, outer radius, ...;
  // for an unbounded plane or quadric, 1.
  real size() const;

  const std::string& type() const { return type_; }

 private:
  std::string type_;
  std::shared_ptr<const OracleShape> shape_;
  Vec center_;
  real rotation_[3][3];  // local -> world
};

// The closest hit over `objects` with t > tmin (ties: the lower index);
// object = -1 on a miss.
struct ExactSceneHit {
  int object = -1;
  real t = 0;
  Vec normal;
};
ExactSceneHit closest_hit(const std::vector<ExactObject>& objects, const ExactRay& ray);

// Helpers for the suite.
ExactRay make_ray(const double origin[3], const double dir[3], double tmin);  // dir normalised in quad precision
std::string to_string(real value, int digits = 20);

}  // namespace prism::stability
