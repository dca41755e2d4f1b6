// The stability suite's oracle: exact first hits in quad precision. Each
// type's own part (its fields, its hit, its distance) lives in its folder,
// plugins/<type>/<type>_cases.cpp, found through tests/cases/primitive_cases.hpp;
// the frame, the rotation and the closest hit are here.
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
//   other sign splits the piece into two brackets.#include "exact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "exact_kit.hpp"
#include "primitive_cases.hpp"

namespace prism::stability {
namespace {

using json = nlohmann::json;

const real kPi = acosq(-1);

// ---------------------------------------------------------------- rotation

void rotation_from_json(const json& r, real m[3][3]) {
  if (!r.is_object()) ObjectFields::fail("rotation", "must be an object");
  if (r.contains("quaternion")) {
    if (r.size() != 1) ObjectFields::fail("rotation", "either quaternion or axis and degrees");
    auto q = json_numbers(r["quaternion"], "rotation.quaternion", 4);
    real n = sqrtq(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n == 0) ObjectFields::fail("rotation.quaternion", "must be non-zero");
    real w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    real rows[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                       {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                       {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = rows[i][j];
    return;
  }
  for (auto it = r.begin(); it != r.end(); ++it)
    if (it.key() != "axis" && it.key() != "degrees") ObjectFields::fail("rotation." + it.key(), "unknown field");
  if (!r.contains("axis") || !r.contains("degrees"))
    ObjectFields::fail("rotation", "needs axis and degrees (or quaternion)");
  Vec axis = json_vec3(r["axis"], "rotation.axis");
  if (axis.x == 0 && axis.y == 0 && axis.z == 0) ObjectFields::fail("rotation.axis", "must be non-zero");
  axis = normalized(axis);
  real degrees = fmodq(json_number(r["degrees"], "rotation.degrees"), 360);  // exact
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

const prism::cases::PrimitiveCases& cases_of(const std::string& type) {
  const prism::cases::PrimitiveCases* cases = prism::cases::find_primitive_cases(type);
  if (!cases || !cases->oracle) ObjectFields::fail("type", "unknown object type '" + type + "'");
  return *cases;
}

}  // namespace

// ---------------------------------------------------------------- ExactObject

ExactObject::ExactObject(const nlohmann::json& object) {
  if (!object.is_object()) throw std::invalid_argument("object: must be a JSON object");
  auto it = object.find("type");
  if (it == object.end() || !it->is_string()) throw std::invalid_argument("type: required string");
  type_ = it->get<std::string>();
  try {
    const prism::cases::PrimitiveCases& cases = cases_of(type_);
    ObjectFields fields(object);
    shape_ = std::make_shared<OracleShape>(cases.oracle(fields));
    std::set<std::string> common = {"type", "material"};
    if (cases.transformable) common.insert({"center", "rotation"});
    for (const std::string& key : fields.unknown_fields(common))
      ObjectFields::fail(key, "unknown field for a " + type_);
    if (object.contains("material") && !object["material"].is_string())
      ObjectFields::fail("material", "must be a string");
    center_ = {0, 0, 0};
    if (auto c = object.find("center"); c != object.end()) center_ = json_vec3(*c, "center");
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
  ExactHit out;
  Vec o = apply_transposed(rotation_, ray.origin - center_);
  Vec d = apply_transposed(rotation_, ray.dir);
  LocalHit h = shape_->hit(o, d, ray.tmin);
  if (!h.hit) return out;
  out.hit = true;
  out.t = h.t;
  out.normal = h.minus_dir ? Vec{-ray.dir.x, -ray.dir.y, -ray.dir.z} : normalized(apply(rotation_, h.n));
  return out;
}

real ExactObject::distance_to_surface(const Vec& world_point) const {
  return shape_->distance(apply_transposed(rotation_, world_point - center_));
}

real ExactObject::size() const { return shape_->size; }

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
