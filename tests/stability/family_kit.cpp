// The shared pieces of the primitives' stiff families (family_kit.hpp).
#include "family_kit.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace prism::stability {

V unit_in_double(V d) {
  d = normalize(d);
  for (int i = 0; i < 200; ++i) {
    const double len2 = d.x * d.x + d.y * d.y + d.z * d.z;
    if (std::sqrt(len2) == 1.0) return d;
    double* big = std::fabs(d.x) >= std::fabs(d.y) && std::fabs(d.x) >= std::fabs(d.z) ? &d.x
                  : std::fabs(d.y) >= std::fabs(d.z)                                   ? &d.y
                                                                                       : &d.z;
    const double toward = len2 > 1.0 ? 0.0 : 2.0 * *big;  // shrink or grow its magnitude
    *big = std::nextafter(*big, toward);
  }
  throw std::logic_error("unit_in_double: no unit double direction found");
}

Rotation::Rotation(V a, double deg) : axis(a), degrees(deg), identity(false) {
  const V u = normalize(a);
  const double th = deg * kPi / 180.0, c = std::cos(th), s = std::sin(th), k = 1 - c;
  const double r[3][3] = {{c + u.x * u.x * k, u.x * u.y * k - u.z * s, u.x * u.z * k + u.y * s},
                          {u.y * u.x * k + u.z * s, c + u.y * u.y * k, u.y * u.z * k - u.x * s},
                          {u.z * u.x * k - u.y * s, u.z * u.y * k + u.x * s, c + u.z * u.z * k}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = r[i][j];
}

const Rotation kTilted(V{1, 2, 3}, 37);
const V kCenterA{0.25, -0.5, 0.75};

V Rng::unit() {
  const double z = range(-1, 1), phi = range(0, 2 * kPi), s = std::sqrt(std::max(0.0, 1 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

V Rng::tangent(V n) {
  const V a = std::fabs(n.x) < 0.9 ? V{1, 0, 0} : V{0, 1, 0};
  const V t1 = normalize(cross(n, a)), t2 = cross(n, t1);
  const double phi = range(0, 2 * kPi);
  return std::cos(phi) * t1 + std::sin(phi) * t2;
}

V Rng::cone(V n, double lo, double hi) {
  const double c = range(lo, hi), s = std::sqrt(std::max(0.0, 1 - c * c));
  return c * n + s * tangent(n);
}

nlohmann::json placed(nlohmann::json object, V center, const Rotation& rot) {
  object["center"] = to_json(center);
  if (!rot.identity) object["rotation"] = rot.json();
  return object;
}

Ray make_ray(V origin, V dir, double tmin) {
  const V d = unit_in_double(dir);
  return Ray{{origin.x, origin.y, origin.z}, {d.x, d.y, d.z}, tmin};
}

Ray ray_to(V target, V dir, double L) {
  const V d = unit_in_double(dir);
  return make_ray(target - L * d, d);
}

namespace {

uint64_t seed_of(const std::string& family, const std::string& param) {
  uint64_t h = 14695981039346656037ull;  // FNV-1a
  for (char c : family + "|" + param) {
    h ^= uint8_t(c);
    h *= 1099511628211ull;
  }
  return h;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

void Builder::add(const std::string& primitive, const std::string& name, const std::string& description,
                  const Sweep& sweep, const CaseMaker& make) {
  Family family;
  family.name = primitive + "." + name;
  family.primitive = primitive;
  family.description = description;
  const std::vector<double> values = mode == Mode::quick ? std::vector<double>{sweep.quick} : sweep.full;
  for (double value : values) {
    const std::string param = sweep.key + "=" + number(value);
    Rng rng(seed_of(family.name, param));
    Case c = make(value, rays(), rng);
    c.param = param;
    family.cases.push_back(std::move(c));
  }
  out->push_back(std::move(family));
}

}  // namespace prism::stability
