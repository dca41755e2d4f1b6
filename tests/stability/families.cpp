// The stiff-case generator (see families.hpp). Geometry here is plain double:
// the generator only has to land rays near the hard spots; what the right
// answer is for the doubles it writes is the oracle's business (exact.hpp).
#include "families.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>

namespace prism::stability {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------- vectors

struct V {
  double x = 0, y = 0, z = 0;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator-(V a) { return {-a.x, -a.y, -a.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(V a) { return std::sqrt(dot(a, a)); }
V normalize(V a) { return (1.0 / length(a)) * a; }
nlohmann::json to_json(V a) { return nlohmann::json::array({a.x, a.y, a.z}); }

// `prism trace` normalises a direction on read as dir / sqrt(x*x + y*y + z*z)
// in double. A direction whose double length is exactly 1 passes unchanged,
// so the ray the backend traces is bit for bit the ray the oracle solves. A
// zero component stays zero (only the largest one is ever nudged).
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

// A local-to-world rotation, built the way the scene format defines
// {"axis": a, "degrees": deg} (right-hand rule about the normalised axis).
struct Rotation {
  V axis{0, 1, 0};
  double degrees = 0;
  bool identity = true;
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Rotation() = default;
  Rotation(V a, double deg) : axis(a), degrees(deg), identity(false) {
    const V u = normalize(a);
    const double th = deg * kPi / 180.0, c = std::cos(th), s = std::sin(th), k = 1 - c;
    const double r[3][3] = {{c + u.x * u.x * k, u.x * u.y * k - u.z * s, u.x * u.z * k + u.y * s},
                            {u.y * u.x * k + u.z * s, c + u.y * u.y * k, u.y * u.z * k - u.x * s},
                            {u.z * u.x * k - u.y * s, u.z * u.y * k + u.x * s, c + u.z * u.z * k}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = r[i][j];
  }
  V apply(V v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  nlohmann::json json() const { return {{"axis", to_json(axis)}, {"degrees", degrees}}; }
};

const Rotation kTilted(V{1, 2, 3}, 37);  // the rotation of the "rotated" families

// ---------------------------------------------------------------- random numbers

// mt19937_64 is specified to the bit; the doubles are drawn from its output
// directly (the standard distributions are not portable).
class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}
  double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double range(double a, double b) { return a + (b - a) * uniform(); }
  double sign() { return uniform() < 0.5 ? -1.0 : 1.0; }
  int index(int n) { return std::min(n - 1, int(uniform() * n)); }
  V unit() {
    const double z = range(-1, 1), phi = range(0, 2 * kPi), s = std::sqrt(std::max(0.0, 1 - z * z));
    return {s * std::cos(phi), s * std::sin(phi), z};
  }
  // A unit vector perpendicular to `n` (unit), uniform in angle.
  V tangent(V n) {
    const V a = std::fabs(n.x) < 0.9 ? V{1, 0, 0} : V{0, 1, 0};
    const V t1 = normalize(cross(n, a)), t2 = cross(n, t1);
    const double phi = range(0, 2 * kPi);
    return std::cos(phi) * t1 + std::sin(phi) * t2;
  }
  // A unit vector whose cosine with `n` lies in [lo, hi].
  V cone(V n, double lo, double hi) {
    const double c = range(lo, hi), s = std::sqrt(std::max(0.0, 1 - c * c));
    return c * n + s * tangent(n);
  }

 private:
  std::mt19937_64 engine_;
};

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

// ---------------------------------------------------------------- shapes

struct SurfacePoint {
  V p, n;  // local point and outward unit normal
};

// One object of a type with its placement, and a sampler of its surface, for
// the families every type shares.
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

nlohmann::json placed(nlohmann::json object, V center, const Rotation& rot) {
  object["center"] = to_json(center);
  if (!rot.identity) object["rotation"] = rot.json();
  return object;
}

// Coefficients of the quadric with semi-axes a, b, c: x²/a² + y²/b² + z²/c² = 1.
nlohmann::json ellipsoid(double a, double b, double c) {
  return {1 / (a * a), 1 / (b * b), 1 / (c * c), 0, 0, 0, 0, 0, 0, -1};
}

// The shape of `type` with characteristic size `s` (radius, largest half size, ...).
Shape make_shape(const std::string& type, double s, V center, const Rotation& rot) {
  Shape shape;
  shape.center = center;
  shape.rot = rot;
  if (type == "sphere") {
    shape.object = placed({{"type", "sphere"}, {"radius", s}}, center, rot);
    shape.size = s;
    shape.sample = [s](Rng& rng) {
      const V u = rng.unit();
      return SurfacePoint{s * u, u};
    };
  } else if (type == "plane") {
    // No center or rotation in the format: the point and the rotated +y.
    shape.object = {{"type", "plane"}, {"point", to_json(center)}, {"normal", to_json(rot.apply({0, 1, 0}))}};
    shape.size = s;
    shape.sample = [s](Rng& rng) {
      const double r = s * std::sqrt(rng.uniform()), phi = rng.range(0, 2 * kPi);
      return SurfacePoint{{r * std::cos(phi), 0, r * std::sin(phi)}, {0, rng.sign(), 0}};
    };
  } else if (type == "box") {
    const V h{s, 0.6 * s, 0.35 * s};
    shape.object = placed({{"type", "box"}, {"half_size", to_json(h)}}, center, rot);
    shape.size = length(h);
    shape.sample = [h](Rng& rng) {
      const double area[3] = {h.y * h.z, h.x * h.z, h.x * h.y};
      const double pick = rng.range(0, area[0] + area[1] + area[2]);
      const int a = pick < area[0] ? 0 : pick < area[0] + area[1] ? 1 : 2;
      double p[3] = {rng.range(-0.98, 0.98) * h.x, rng.range(-0.98, 0.98) * h.y, rng.range(-0.98, 0.98) * h.z};
      const double hs[3] = {h.x, h.y, h.z}, sg = rng.sign();
      double n[3] = {0, 0, 0};
      p[a] = sg * hs[a];
      n[a] = sg;
      return SurfacePoint{{p[0], p[1], p[2]}, {n[0], n[1], n[2]}};
    };
  } else if (type == "torus") {
    const double R = s / 1.3, r = 0.3 * R;
    shape.object = placed({{"type", "torus"}, {"major_radius", R}, {"minor_radius", r}}, center, rot);
    shape.size = R + r;
    shape.sample = [R, r](Rng& rng) {
      const double u = rng.range(0, 2 * kPi), v = rng.range(0, 2 * kPi);
      const V n{std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)};
      return SurfacePoint{{(R + r * std::cos(v)) * std::cos(u), r * std::sin(v), (R + r * std::cos(v)) * std::sin(u)},
                          n};
    };
  } else if (type == "ring") {
    const double outer = s, inner = 0.4 * s;
    shape.object = placed({{"type", "ring"}, {"inner_radius", inner}, {"outer_radius", outer}}, center, rot);
    shape.size = outer;
    shape.sample = [inner, outer](Rng& rng) {
      const double lo = 1.01 * inner, hi = 0.99 * outer;
      const double r = std::sqrt(rng.range(lo * lo, hi * hi)), phi = rng.range(0, 2 * kPi);
      return SurfacePoint{{r * std::cos(phi), 0, r * std::sin(phi)}, {0, rng.sign(), 0}};
    };
  } else if (type == "quadric") {
    const double a = s, b = 0.5 * s, c = 0.25 * s;
    shape.object = placed({{"type", "quadric"}, {"coefficients", ellipsoid(a, b, c)}}, center, rot);
    shape.size = a;
    shape.sample = [a, b, c](Rng& rng) {
      const V u = rng.unit();
      return SurfacePoint{{a * u.x, b * u.y, c * u.z}, normalize({u.x / a, u.y / b, u.z / c})};
    };
  } else if (type == "cylinder") {
    const double r = 0.5 * s, h = 2 * s;
    shape.object = placed({{"type", "cylinder"}, {"radius", r}, {"height", h}}, center, rot);
    shape.mid = {0, h / 2, 0};
    shape.size = std::sqrt(r * r + h * h / 4);
    shape.sample = [r, h](Rng& rng) {
      const double phi = rng.range(0, 2 * kPi), y = rng.range(0.02, 0.98) * h;
      return SurfacePoint{{r * std::cos(phi), y, r * std::sin(phi)}, {std::cos(phi), 0, std::sin(phi)}};
    };
  } else if (type == "cone") {
    const double r = 0.5 * s, h = s, k = r / h;
    shape.object = placed({{"type", "cone"}, {"radius", r}, {"height", h}}, center, rot);
    shape.mid = {0, h / 2, 0};
    shape.size = std::sqrt(r * r + h * h / 4);
    shape.sample = [k, h](Rng& rng) {
      const double phi = rng.range(0, 2 * kPi), y = rng.range(0.05, 0.98) * h;
      const V p{k * y * std::cos(phi), y, k * y * std::sin(phi)};
      return SurfacePoint{p, normalize({p.x, -k * k * p.y, p.z})};
    };
  } else {
    throw std::invalid_argument("unknown primitive type '" + type + "'");
  }
  return shape;
}

// The world offset of a shape's middle from its centre (cylinders and cones
// start at their centre and rise along local y).
V shape_mid(const std::string& type, double s, const Rotation& rot) {
  return rot.apply(make_shape(type, s, {0, 0, 0}, rot).mid);
}

Ray make_ray(V origin, V dir, double tmin = 0) {
  const V d = unit_in_double(dir);
  return Ray{{origin.x, origin.y, origin.z}, {d.x, d.y, d.z}, tmin};
}

// A ray from `L` before `target` along `dir` (the target is hit at t ≈ L).
Ray ray_to(V target, V dir, double L) {
  const V d = unit_in_double(dir);
  return make_ray(target - L * d, d);
}

// ---------------------------------------------------------------- the family builder

struct Sweep {
  std::string key;           // parameter name, e.g. "angle"
  std::vector<double> full;  // every value
  double quick;              // the one quick mode uses
};

using CaseMaker = std::function<Case(double value, int rays, Rng& rng)>;

struct Builder {
  Mode mode;
  int rays() const { return mode == Mode::quick ? 48 : 256; }
  std::vector<Family>* out;

  void add(const std::string& primitive, const std::string& name, const std::string& description, const Sweep& sweep,
           const CaseMaker& make) {
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
};

// ---------------------------------------------------------------- families every type has

const V kCenterA{0.25, -0.5, 0.75};

void add_common(Builder& b, const std::string& type) {
  // Rays entering the surface at `angle` to its tangent plane at a sampled
  // point: near-double roots on curved surfaces, tiny n·d on flat ones.
  b.add(type, "grazing", "rays entering the surface at a small angle to its tangent plane (rotated object)",
        {"angle", {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7}, 1e-7}, [type](double angle, int n, Rng& rng) {
          Case c;
          const Shape shape = make_shape(type, 1, kCenterA, kTilted);
          c.objects = nlohmann::json::array({shape.object});
          for (int i = 0; i < n; ++i) {
            const SurfacePoint sp = shape.sample(rng);
            const V P = shape.world(sp.p), N = shape.world_dir(sp.n), T = rng.tangent(N);
            const V d = std::cos(angle) * T - std::sin(angle) * N;
            c.rays.push_back(ray_to(P, d, rng.range(0.5, 3) * shape.size));
          }
          return c;
        });

  // Origins far away, aimed at (or just beside) the object.
  b.add(type, "far", "origins 1e2..1e6 units away aimed at points on or near the surface (rotated object)",
        {"distance", {1e2, 1e3, 1e4, 1e5, 1e6}, 1e6}, [type](double distance, int n, Rng& rng) {
          Case c;
          const Shape shape = make_shape(type, 1, {1.5, -0.5, 2.0}, kTilted);
          c.objects = nlohmann::json::array({shape.object});
          for (int i = 0; i < n; ++i) {
            const V origin = shape.world(shape.mid) + distance * rng.unit();
            const V target = shape.world(shape.sample(rng).p) + 0.1 * shape.size * rng.unit();
            c.rays.push_back(make_ray(origin, target - origin));
          }
          return c;
        });

  if (type != "plane") {
    // A tiny object seen from 1..10 units.
    b.add(type, "tiny", "objects of size 1e-4..1e-1 seen from 1..10 units (rotated object)",
          {"size", {1e-1, 1e-2, 1e-3, 1e-4}, 1e-4}, [type](double size, int n, Rng& rng) {
            Case c;
            const Shape shape = make_shape(type, size, {0.7, 0.2, -0.4}, kTilted);
            c.objects = nlohmann::json::array({shape.object});
            for (int i = 0; i < n; ++i) {
              const V origin = shape.world(shape.mid) + rng.range(1, 10) * rng.unit();
              const V target = shape.world(shape.sample(rng).p) + 0.1 * shape.size * rng.unit();
              c.rays.push_back(make_ray(origin, target - origin));
            }
            return c;
          });
  }

  // A huge object (the ground-sphere case) seen from 0.01..10 units off its
  // surface, looking at points within 20 units; its centre is `size` from the
  // world origin. For the plane: its point that far out.
  b.add(type, "huge", "objects of size 1e2..1e6 seen from 0.01..10 units off their surface (rotated object)",
        {"size", {1e2, 1e3, 1e4, 1e5, 1e6}, 1e5}, [type](double size, int n, Rng& rng) {
          Case c;
          const Shape shape = make_shape(type, size, size * V{0.3, -1.0, 0.2}, kTilted);
          c.objects = nlohmann::json::array({shape.object});
          for (int i = 0; i < n; ++i) {
            const SurfacePoint sp = shape.sample(rng);
            const V P = shape.world(sp.p), N = shape.world_dir(sp.n);
            const V origin = P + std::pow(10.0, rng.range(-2, 1)) * N + rng.range(0, 5) * rng.tangent(N);
            const V target = P + rng.range(0, 20) * rng.unit();
            c.rays.push_back(make_ray(origin, target - origin));
          }
          return c;
        });

  if (type != "plane") {
    // 27 small objects in a grid far from the world origin: which one is hit
    // (wrong object), and the acceleration structures' bounds at large
    // coordinates (the GPU BVH stores float boxes rounded outward).
    b.add(type, "cluster",
          "27 objects of size 1 in a 3x3x3 grid (spacing 2.5) centred 1..1e6 from the origin, rays from 6..30 "
          "away (rotated objects)",
          {"offset", {1, 1e2, 1e4, 1e5, 1e6}, 1e5}, [type](double offset, int n, Rng& rng) {
            Case c;
            const double s = 1, spacing = 2.5;
            const V middle = offset * V{0.6, -0.48, 0.64};
            std::vector<Shape> shapes;
            c.objects = nlohmann::json::array();
            for (int i = 0; i < 27; ++i) {
              const V at = middle + spacing * V{double(i % 3 - 1), double(i / 3 % 3 - 1), double(i / 9 - 1)};
              const Shape shape = make_shape(type, s, at - shape_mid(type, s, kTilted), kTilted);
              shapes.push_back(shape);
              c.objects.push_back(shape.object);
            }
            for (int i = 0; i < n; ++i) {
              const Shape& shape = shapes[size_t(rng.index(27))];
              const V target = shape.world(shape.sample(rng).p) + 0.1 * shape.size * rng.unit();
              const V origin = middle + rng.range(6, 30) * rng.unit();
              c.rays.push_back(make_ray(origin, target - origin));
            }
            return c;
          });
  }

  // Secondary rays: the origin is a surface point (rounded to double), tmin
  // the spec's offset 1e-4 (1 + max|P_i|) times `tmin_factor`; half leave the
  // surface outward, half go in, at least 0.05 off the tangent plane.
  b.add(type, "secondary", "rays from surface points with tmin = factor * 1e-4 (1 + max|P_i|) (rotated object)",
        {"tmin_factor", {1, 1e-1, 1e-2, 1e-3, 1e-4}, 1e-2}, [type](double factor, int n, Rng& rng) {
          Case c;
          const Shape shape = make_shape(type, 1, {12.5, -3.25, 40}, kTilted);
          c.objects = nlohmann::json::array({shape.object});
          for (int i = 0; i < n; ++i) {
            const SurfacePoint sp = shape.sample(rng);
            const V P = shape.world(sp.p), N = shape.world_dir(sp.n);
            const double tmin = factor * 1e-4 * (1 + std::max({std::fabs(P.x), std::fabs(P.y), std::fabs(P.z)}));
            const V d = i % 2 == 0 ? rng.cone(N, 0.05, 1) : rng.cone(N, -1, -0.05);
            c.rays.push_back(make_ray(P, d, tmin));
          }
          return c;
        });
}

// ---------------------------------------------------------------- type-specific families

void add_sphere(Builder& b) {
  // Embree's verify case: a small sphere far from the world origin, rays from
  // inside it. Every ray must hit.
  b.add("sphere", "inside", "rays from inside a radius-1 sphere whose centre is 1..1e6 from the world origin",
        {"center", {1, 1e2, 1e4, 1e6}, 1e6}, [](double m, int n, Rng& rng) {
          Case c;
          const V center = m * V{0.5547, 0.0046, -0.8321};
          c.objects = nlohmann::json::array({{{"type", "sphere"}, {"center", to_json(center)}, {"radius", 1.0}}});
          for (int i = 0; i < n; ++i) {
            const V origin = center + 0.9 * std::cbrt(rng.uniform()) * rng.unit();
            c.rays.push_back(make_ray(origin, rng.unit()));
          }
          return c;
        });
}

void add_box(Builder& b) {
  const V h{1, 0.6, 0.35};
  const double hs[3] = {h.x, h.y, h.z};
  // Aim points on an edge (eta = 0) or `eta` (relative to the size) inside one
  // of its two faces, from directions that see that face from the front.
  b.add("box", "edge", "rays aimed at box edges, or eta * size inside an adjacent face (rotated box)",
        {"eta", {1e-3, 1e-6, 1e-9, 0}, 0}, [h, hs](double eta, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({placed({{"type", "box"}, {"half_size", to_json(h)}}, kCenterA, kTilted)});
          const double size = length(h);
          for (int i = 0; i < n; ++i) {
            const int a = rng.index(3), b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            double p[3];
            p[a] = rng.range(-0.95, 0.95) * hs[a];
            const double s1 = rng.sign(), s2 = rng.sign();
            p[b1] = s1 * hs[b1];
            p[b2] = s2 * hs[b2];
            const bool first = rng.uniform() < 0.5;  // the face the ray aims at: b1 or b2
            const int face = first ? b1 : b2, other = first ? b2 : b1;
            p[other] -= (first ? s2 : s1) * eta * size;
            double nl[3] = {0, 0, 0};
            nl[face] = first ? s1 : s2;
            const V N = normalize(kTilted.apply({nl[0], nl[1], nl[2]}));
            const V P = kCenterA + kTilted.apply({p[0], p[1], p[2]});
            c.rays.push_back(ray_to(P, rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });

  b.add("box", "corner", "rays aimed at box corners, or eta * size inside one of the three faces (rotated box)",
        {"eta", {1e-3, 1e-6, 1e-9, 0}, 0}, [h, hs](double eta, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({placed({{"type", "box"}, {"half_size", to_json(h)}}, kCenterA, kTilted)});
          const double size = length(h);
          for (int i = 0; i < n; ++i) {
            const double s[3] = {rng.sign(), rng.sign(), rng.sign()};
            double p[3] = {s[0] * hs[0], s[1] * hs[1], s[2] * hs[2]};
            const int face = rng.index(3);
            for (int k = 0; k < 3; ++k)
              if (k != face) p[k] -= s[k] * eta * size;
            double nl[3] = {0, 0, 0};
            nl[face] = s[face];
            const V N = normalize(kTilted.apply({nl[0], nl[1], nl[2]}));
            const V P = kCenterA + kTilted.apply({p[0], p[1], p[2]});
            c.rays.push_back(ray_to(P, rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });

  // An axis-aligned box with exactly representable faces: rays lying exactly
  // in a face's plane (d_a = 0, o_a = c_a ± h_a: the slab test's 0/0) and rays
  // running exactly along an edge's line. They touch the closed box.
  b.add("box", "face_plane", "rays lying exactly in a face plane or along an edge line (axis-aligned box)",
        {"case", {0}, 0}, [](double, int n, Rng& rng) {
          Case c;
          const double center[3] = {0.5, -0.25, 1.25}, half[3] = {1, 0.5, 0.25};
          c.objects =
              nlohmann::json::array({{{"type", "box"}, {"center", {0.5, -0.25, 1.25}}, {"half_size", {1, 0.5, 0.25}}}});
          for (int i = 0; i < n; ++i) {
            const int a = rng.index(3), b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            double o[3], d[3];
            o[a] = center[a] + rng.sign() * half[a];  // exact: in the face plane
            d[a] = 0;
            if (i % 3 == 2) {
              // Along the edge line where faces a and b1 meet, running along b2.
              o[b1] = center[b1] + rng.sign() * half[b1];
              d[b1] = 0;
              const double s = rng.sign();
              o[b2] = center[b2] - s * half[b2] * rng.range(1.5, 6);
              d[b2] = s;
            } else {
              // Across the face from outside its extent, toward a point of the face (or just beside it).
              const double tb1 = center[b1] + rng.range(-1.2, 1.2) * half[b1];
              const double tb2 = center[b2] + rng.range(-1.2, 1.2) * half[b2];
              const double phi = rng.range(0, 2 * kPi), L = rng.range(2, 5);
              d[b1] = std::cos(phi);
              d[b2] = std::sin(phi);
              o[b1] = tb1 - L * d[b1];
              o[b2] = tb2 - L * d[b2];
            }
            c.rays.push_back(make_ray({o[0], o[1], o[2]}, {d[0], d[1], d[2]}));
          }
          return c;
        });
}

// The torus at kCenterA, rotated by kTilted, and a point of its surface in
// the local frame (u around the axis, v around the tube).
nlohmann::json tilted_torus(double R, double r) {
  return placed({{"type", "torus"}, {"major_radius", R}, {"minor_radius", r}}, kCenterA, kTilted);
}
V torus_point(double R, double r, double u, double v) {
  return {(R + r * std::cos(v)) * std::cos(u), r * std::sin(v), (R + r * std::cos(v)) * std::sin(u)};
}

void add_torus(Builder& b) {
  const std::vector<double> ratios = {1e-3, 1e-2, 0.1, 0.5, 0.9, 0.99};

  // Random rays at the tube from 3..10 (R + r), across the ratio r/R.
  b.add("torus", "ratio", "rays from 3..10 (R+r) at points near the tube, r/R from 1e-3 to 0.99 (rotated torus)",
        {"r/R", ratios, 1e-3}, [](double ratio, int n, Rng& rng) {
          Case c;
          const double R = 1, r = ratio * R;
          c.objects = nlohmann::json::array({tilted_torus(R, r)});
          for (int i = 0; i < n; ++i) {
            const double u = rng.range(0, 2 * kPi), v = rng.range(0, 2 * kPi);
            const V p = torus_point(R, r, u, v);
            const V target = kCenterA + kTilted.apply(p + 0.3 * r * rng.unit());
            const V origin = kCenterA + rng.range(3, 10) * (R + r) * rng.unit();
            c.rays.push_back(make_ray(origin, target - origin));
          }
          return c;
        });

  // Rays through the hole: a quarter exactly on the axis (the torus is not
  // rotated and its centre is exact, so x and z are exact), the rest parallel
  // or tilted, all staying within 0.9 (R - r) of the axis while inside the
  // slab |y| <= r, so every one must miss.
  b.add("torus", "hole", "rays along the axis and through the hole (must miss), r/R from 1e-3 to 0.99",
        {"r/R", ratios, 0.99}, [](double ratio, int n, Rng& rng) {
          Case c;
          const double R = 1, r = ratio * R;
          const V center{0.5, -0.25, 1.0};
          c.objects = nlohmann::json::array(
              {{{"type", "torus"}, {"center", to_json(center)}, {"major_radius", R}, {"minor_radius", r}}});
          for (int i = 0; i < n; ++i) {
            const double side = rng.sign(), height = r + rng.range(0.5, 5);
            if (i % 4 == 0) {
              c.rays.push_back(make_ray(center + V{0, side * height, 0}, {0, -side, 0}));
              continue;
            }
            const double rho0 = rng.range(0, 0.8) * (R - r), beta = rng.range(0, 2 * kPi);
            const double tilt = i % 4 == 1 ? 0.0 : std::atan(rng.uniform() * (0.9 * (R - r) - rho0) / r);
            const double gamma = rng.range(0, 2 * kPi);
            const V d{std::sin(tilt) * std::cos(gamma), -side * std::cos(tilt), std::sin(tilt) * std::sin(gamma)};
            const V crossing = center + V{rho0 * std::cos(beta), 0, rho0 * std::sin(beta)};
            c.rays.push_back(ray_to(crossing, d, height / std::cos(tilt)));
          }
          return c;
        });

  // Lines tangent to the tube, shifted 5x the ambiguity band off the tangent
  // point (half inward, half outward), at every kind of surface point (outer,
  // inner saddle, top).
  b.add("torus", "tangent", "lines tangent to the tube, 5x the ambiguity band off it, r/R from 1e-3 to 0.99 (rotated)",
        {"r/R", ratios, 1e-3}, [](double ratio, int n, Rng& rng) {
          Case c;
          const double R = 1, r = ratio * R;
          c.objects = nlohmann::json::array({tilted_torus(R, r)});
          for (int i = 0; i < n; ++i) {
            const double u = rng.range(0, 2 * kPi), v = rng.range(0, 2 * kPi);
            const V p = torus_point(R, r, u, v);
            const V N = normalize(kTilted.apply({std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)}));
            const V P = kCenterA + kTilted.apply(p), T = rng.tangent(N);
            const double L = rng.range(1, 3);
            const V start = P - L * T;
            const double shift = (i % 2 ? 1.0 : -1.0) * 5e-7 * (length(start) + L);
            c.rays.push_back(make_ray(start + shift * N, T));
          }
          return c;
        });
}

void add_ring(Builder& b) {
  // Aim points at inner (1 ± eta): outside the hole they hit, inside they miss.
  b.add("ring", "inner", "rays aimed at inner_radius * (1 ± eta), from either side (rotated ring)",
        {"eta", {1e-2, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10}, 1e-5}, [](double eta, int n, Rng& rng) {
          Case c;
          const double inner = 0.5, outer = 1;
          const V center{0.25, 1.5, -0.75};
          c.objects = nlohmann::json::array(
              {placed({{"type", "ring"}, {"inner_radius", inner}, {"outer_radius", outer}}, center, kTilted)});
          for (int i = 0; i < n; ++i) {
            const double rho = inner * (1 + (i % 2 ? eta : -eta)), phi = rng.range(0, 2 * kPi);
            const V P = center + kTilted.apply({rho * std::cos(phi), 0, rho * std::sin(phi)});
            const V N = rng.sign() * normalize(kTilted.apply({0, 1, 0}));
            c.rays.push_back(ray_to(P, rng.cone(-N, 0.1, 1), rng.range(1, 4)));
          }
          return c;
        });
}

void add_quadric(Builder& b) {
  const V center{0.5, -0.25, 1.0};
  // f = eps (x² + z²) + y: almost the plane y = 0. Half the rays are exactly
  // vertical (the t² coefficient is exactly 0: the linear case), half oblique
  // (the t² coefficient is ~eps).
  b.add("quadric", "nearly_linear", "f = eps (x^2 + z^2) + y: t^2 coefficient exactly 0 (vertical rays) or ~eps",
        {"eps", {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12}, 1e-12}, [center](double eps, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({{{"type", "quadric"},
                                              {"center", to_json(center)},
                                              {"coefficients", {eps, 0, eps, 0, 0, 0, 0, 1, 0, 0}},
                                              {"clip_min", {-10, nullptr, -10}},
                                              {"clip_max", {10, nullptr, 10}}}});
          for (int i = 0; i < n; ++i) {
            const double x = rng.range(-9, 9), z = rng.range(-9, 9);
            const V target = center + V{x, -eps * (x * x + z * z), z};
            if (i % 2 == 0) {
              const double side = rng.sign();
              c.rays.push_back(make_ray(V{target.x, center.y + side * rng.range(1, 5), target.z}, {0, -side, 0}));
            } else {
              const double side = rng.sign();
              c.rays.push_back(ray_to(target, rng.cone({0, -side, 0}, 0.05, 1), rng.range(1, 5)));
            }
          }
          return c;
        });

  // x² + z² - k² y² = 1, clipped to |y| <= 3/k: the waist radius is 1, the
  // clipped rims have radius sqrt(10). Rays from outside at surface points,
  // and from inside the tube.
  b.add("quadric", "hyperboloid1", "one sheet x^2 + z^2 - k^2 y^2 = 1, |y| <= 3/k (rotated)",
        {"k", {1e-2, 1e-1, 1, 10, 100}, 100}, [](double k, int n, Rng& rng) {
          Case c;
          const double ym = 3 / k;
          c.objects = nlohmann::json::array({placed({{"type", "quadric"},
                                                     {"coefficients", {1, -k * k, 1, 0, 0, 0, 0, 0, 0, -1}},
                                                     {"clip_min", {nullptr, -ym, nullptr}},
                                                     {"clip_max", {nullptr, ym, nullptr}}},
                                                    kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            if (i % 4 == 3) {
              const V o{rng.range(-0.5, 0.5), rng.range(-0.9, 0.9) * ym, rng.range(-0.5, 0.5)};
              c.rays.push_back(make_ray(kCenterA + kTilted.apply(o), rng.unit()));
              continue;
            }
            const double y = rng.range(-0.95, 0.95) * ym, phi = rng.range(0, 2 * kPi);
            const double rho = std::sqrt(1 + k * k * y * y);
            const V p{rho * std::cos(phi), y, rho * std::sin(phi)};
            const V N = normalize(kTilted.apply({p.x, -k * k * p.y, p.z}));
            c.rays.push_back(ray_to(kCenterA + kTilted.apply(p), rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });

  // k² y² - x² - z² = 1: two sheets 2/k apart, clipped to |x|, |z| <= 3. Rays
  // from the gap between them (hitting a sheet from inside) and from outside.
  b.add("quadric", "hyperboloid2", "two sheets k^2 y^2 - x^2 - z^2 = 1, |x|,|z| <= 3 (rotated)",
        {"k", {1e-2, 1e-1, 1, 10, 100}, 100}, [](double k, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array({placed({{"type", "quadric"},
                                                     {"coefficients", {-1, k * k, -1, 0, 0, 0, 0, 0, 0, -1}},
                                                     {"clip_min", {-3, nullptr, -3}},
                                                     {"clip_max", {3, nullptr, 3}}},
                                                    kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            if (i % 2 == 0) {
              const V o{rng.range(-2, 2), rng.range(-0.5, 0.5) / k, rng.range(-2, 2)};
              const V d = rng.cone({0, rng.sign(), 0}, 0.1, 1);
              c.rays.push_back(make_ray(kCenterA + kTilted.apply(o), kTilted.apply(d)));
              continue;
            }
            const double rho = rng.range(0, 2.8), phi = rng.range(0, 2 * kPi), side = rng.sign();
            const V p{rho * std::cos(phi), side * std::sqrt(1 + rho * rho) / k, rho * std::sin(phi)};
            const V N = normalize(kTilted.apply({-p.x, k * k * p.y, -p.z}));
            c.rays.push_back(ray_to(kCenterA + kTilted.apply(p), rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });

  // x² + q y² + z² = 1: a lens of radius 1 and half-thickness 1/sqrt(q);
  // coefficient ratios up to 1e12.
  b.add("quadric", "ratio", "spheroid x^2 + q y^2 + z^2 = 1: coefficient ratio q up to 1e12 (rotated)",
        {"q", {1, 1e3, 1e6, 1e9, 1e12}, 1e12}, [](double q, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array(
              {placed({{"type", "quadric"}, {"coefficients", {1, q, 1, 0, 0, 0, 0, 0, 0, -1}}}, kCenterA, kTilted)});
          const double sq = std::sqrt(q);
          for (int i = 0; i < n; ++i) {
            const V u = rng.unit();
            const V p{u.x, u.y / sq, u.z};
            const V N = normalize(kTilted.apply({u.x, u.y * sq, u.z}));
            c.rays.push_back(ray_to(kCenterA + kTilted.apply(p), rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });

  // The unit sphere with every coefficient times s: the same surface. Before
  // the plugin normalised its record, 1e-200 traced as noise and 1e200 as
  // nothing, on every backend.
  b.add("quadric", "scaled", "unit sphere s (x^2 + y^2 + z^2 - 1) = 0: every coefficient times s (rotated)",
        {"s", {1e-200, 1e-100, 1e100, 1e200}, 1e-200}, [](double s, int n, Rng& rng) {
          Case c;
          c.objects = nlohmann::json::array(
              {placed({{"type", "quadric"}, {"coefficients", {s, s, s, 0, 0, 0, 0, 0, 0, -s}}}, kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            const V u = rng.unit();
            const V N = normalize(kTilted.apply(u));
            c.rays.push_back(ray_to(kCenterA + kTilted.apply(u), rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });

  // The double cone x² + z² = y² (|y| <= 2, not rotated, apex at an exact
  // centre): rays aimed at the apex itself (eta = 0) or at surface points eta
  // from it, half from inside the cone's solid angle (through the apex the
  // line only touches: a double root that is a robust hit), half from outside.
  b.add("quadric", "cone_apex", "double cone x^2 + z^2 = y^2: rays at the apex (eta = 0) or eta from it",
        {"eta", {1e-1, 1e-3, 1e-6, 1e-9, 0}, 0}, [](double eta, int n, Rng& rng) {
          Case c;
          const V apex{0.25, 0.5, -0.125};
          c.objects = nlohmann::json::array({{{"type", "quadric"},
                                              {"center", to_json(apex)},
                                              {"coefficients", {1, -1, 1, 0, 0, 0, 0, 0, 0, 0}},
                                              {"clip_min", {nullptr, -2, nullptr}},
                                              {"clip_max", {nullptr, 2, nullptr}}}});
          for (int i = 0; i < n; ++i) {
            const double phi = rng.range(0, 2 * kPi), side = rng.sign();
            const V P = apex + (eta / std::sqrt(2.0)) * V{std::cos(phi), side, std::sin(phi)};
            // Inside the solid angle: within 0.8 of the half-angle (45°) of the axis.
            const V d = i % 2 == 0 ? rng.cone({0, rng.sign(), 0}, std::cos(0.8 * kPi / 4), 1)
                                   : rng.cone({0, rng.sign(), 0}, 0, std::cos(1.2 * kPi / 4));
            c.rays.push_back(ray_to(P, d, rng.range(1, 3)));
          }
          return c;
        });
}

void add_cylinder(Builder& b) {
  // Rays inside or outside the tube, nearly parallel to the axis (tilt): the
  // t² coefficient is sin²(tilt). A quarter exactly parallel (not rotated,
  // exact centre: the coefficient is exactly 0 and they must miss). Height
  // 1e7 so most tilted rays reach the wall inside the clip.
  b.add("cylinder", "axial", "rays nearly parallel to the axis (tilt), a quarter exactly parallel; height 1e7",
        {"tilt", {1e-1, 1e-3, 1e-5, 1e-7}, 1e-7}, [](double tilt, int n, Rng& rng) {
          Case c;
          const V center{0.5, -0.25, 1.0};
          c.objects = nlohmann::json::array(
              {{{"type", "cylinder"}, {"center", to_json(center)}, {"radius", 0.5}, {"height", 1e7}}});
          for (int i = 0; i < n; ++i) {
            const bool inside = i % 2 == 0;
            const double rho0 = inside ? rng.range(0, 0.45) : rng.range(0.55, 2), beta = rng.range(0, 2 * kPi);
            const V o = center + V{rho0 * std::cos(beta), rng.range(1, 100), rho0 * std::sin(beta)};
            const double t = i % 4 < 2 ? 0.0 : tilt;
            // Outside: lean toward the axis; inside: any way.
            const double gamma = inside ? rng.range(0, 2 * kPi) : beta + kPi + rng.range(-0.3, 0.3);
            const V d{std::sin(t) * std::cos(gamma), std::cos(t), std::sin(t) * std::sin(gamma)};
            c.rays.push_back(make_ray(o, d));
          }
          return c;
        });

  // Aim points on the tube at the rims: y = eta*h inside or outside the clip
  // at the bottom, h (1 ± eta) at the top.
  b.add("cylinder", "rim", "rays aimed at the open rims, eta * height inside or outside the clip (rotated)",
        {"eta", {1e-2, 1e-4, 1e-6, 1e-8}, 1e-6}, [](double eta, int n, Rng& rng) {
          Case c;
          const double r = 1, h = 2;
          c.objects =
              nlohmann::json::array({placed({{"type", "cylinder"}, {"radius", r}, {"height", h}}, kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            const double phi = rng.range(0, 2 * kPi), off = (i % 2 ? 1.0 : -1.0) * eta * h;
            const double y = i % 4 < 2 ? off : h + off;
            const V p{r * std::cos(phi), y, r * std::sin(phi)};
            const V N = normalize(kTilted.apply({std::cos(phi), 0, std::sin(phi)}));
            c.rays.push_back(ray_to(kCenterA + kTilted.apply(p), rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });
}

void add_cone(Builder& b) {
  // The apex (not rotated, exact centre): rays at the apex itself (eta = 0)
  // or at surface points eta * height from it; half from inside the cone's
  // solid angle (from above, down through the apex: a robust hit at a double
  // root), half from outside.
  b.add("cone", "apex", "rays at the apex (eta = 0) or eta * height from it along the surface",
        {"eta", {1e-1, 1e-3, 1e-6, 1e-9, 0}, 0}, [](double eta, int n, Rng& rng) {
          Case c;
          const double r = 1, h = 2, half_angle = std::atan(r / h);
          const V apex{0.25, 0.5, -0.125};
          c.objects =
              nlohmann::json::array({{{"type", "cone"}, {"center", to_json(apex)}, {"radius", r}, {"height", h}}});
          for (int i = 0; i < n; ++i) {
            const double phi = rng.range(0, 2 * kPi);
            const V gen = normalize({r / h * std::cos(phi), 1, r / h * std::sin(phi)});
            const V P = apex + eta * h * gen;
            const V d = i % 2 == 0 ? rng.cone({0, -1, 0}, std::cos(0.8 * half_angle), 1)
                                   : rng.cone({0, -1, 0}, -1, std::cos(1.2 * half_angle));
            c.rays.push_back(ray_to(P, d, rng.range(1, 3)));
          }
          return c;
        });

  b.add("cone", "rim", "rays aimed at the open base rim, height (1 ± eta) (rotated)",
        {"eta", {1e-2, 1e-4, 1e-6, 1e-8}, 1e-6}, [](double eta, int n, Rng& rng) {
          Case c;
          const double r = 1, h = 2, k = r / h;
          c.objects =
              nlohmann::json::array({placed({{"type", "cone"}, {"radius", r}, {"height", h}}, kCenterA, kTilted)});
          for (int i = 0; i < n; ++i) {
            const double phi = rng.range(0, 2 * kPi), y = h * (1 + (i % 2 ? eta : -eta));
            const V p{k * y * std::cos(phi), y, k * y * std::sin(phi)};
            const V N = normalize(kTilted.apply({p.x, -k * k * p.y, p.z}));
            c.rays.push_back(ray_to(kCenterA + kTilted.apply(p), rng.cone(-N, 0.05, 1), rng.range(1, 4)));
          }
          return c;
        });
}

}  // namespace

const std::vector<std::string>& primitive_types() {
  static const std::vector<std::string> types = {"sphere", "plane",   "box",      "torus",
                                                 "ring",   "quadric", "cylinder", "cone"};
  return types;
}

std::vector<Family> make_families(Mode mode, const std::string& primitive) {
  const auto& types = primitive_types();
  if (!primitive.empty() && std::find(types.begin(), types.end(), primitive) == types.end())
    throw std::invalid_argument("unknown primitive type '" + primitive + "'");
  std::vector<Family> families;
  Builder b{mode, &families};
  for (const std::string& type : types) {
    if (!primitive.empty() && type != primitive) continue;
    add_common(b, type);
    if (type == "sphere") add_sphere(b);
    if (type == "box") add_box(b);
    if (type == "torus") add_torus(b);
    if (type == "ring") add_ring(b);
    if (type == "quadric") add_quadric(b);
    if (type == "cylinder") add_cylinder(b);
    if (type == "cone") add_cone(b);
  }
  return families;
}

nlohmann::json scene_json(const nlohmann::json& objects) {
  nlohmann::json scene;
  scene["prism"] = 1;
  scene["camera"] = {{"position", {0, 0, -5}}, {"look_at", {0, 0, 0}}};
  scene["image"] = {{"width", 8}, {"height", 8}};
  scene["lights"] = nlohmann::json::array();
  scene["objects"] = objects;
  return scene;
}

std::string rays_csv(const std::vector<Ray>& rays) {
  std::string out = "ox,oy,oz,dx,dy,dz,tmin\n";
  char line[512];
  for (const Ray& r : rays) {
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", r.origin[0], r.origin[1],
                  r.origin[2], r.dir[0], r.dir[1], r.dir[2], r.tmin);
    out += line;
  }
  return out;
}

}  // namespace prism::stability
