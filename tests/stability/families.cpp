// The stiff-case generator (see families.hpp): the families every type
// shares are here, built on each type's object; each type's own families
// and its object come from its folder (plugins/<type>/<type>_cases.cpp),
// found through tests/cases/primitive_cases.hpp. Geometry here is plain
// double: the generator only has to land rays near the hard spots; what the
// right answer is for the doubles it writes is the oracle's business
// (exact.hpp).
#include "families.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "family_kit.hpp"
#include "primitive_cases.hpp"

namespace prism::stability {

namespace {

// The cases of a type the suite covers (one with an oracle and an object).
const prism::cases::PrimitiveCases& cases_of(const std::string& type) {
  const prism::cases::PrimitiveCases* cases = prism::cases::find_primitive_cases(type);
  if (!cases || !cases->oracle || !cases->shape) throw std::invalid_argument("unknown primitive type '" + type + "'");
  return *cases;
}

// The shape of `type` with characteristic size `s` (radius, largest half size, ...).
Shape make_shape(const std::string& type, double s, V center, const Rotation& rot) {
  Shape shape;
  shape.center = center;
  shape.rot = rot;
  cases_of(type).shape(shape, s);
  return shape;
}

// The world offset of a shape's middle from its centre (cylinders and cones
// start at their centre and rise along local y).
V shape_mid(const std::string& type, double s, const Rotation& rot) {
  return rot.apply(make_shape(type, s, {0, 0, 0}, rot).mid);
}

// ---------------------------------------------------------------- families every type has

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

  if (cases_of(type).bounded) {
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

  if (cases_of(type).bounded) {
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

}  // namespace

const std::vector<std::string>& primitive_types() {
  static const std::vector<std::string> types = [] {
    std::vector<std::string> out;
    for (const prism::cases::PrimitiveCases* cases : prism::cases::all_primitive_cases())
      if (cases->oracle && cases->shape) out.push_back(cases->type);
    return out;
  }();
  return types;
}

namespace {

// The families float cannot do, named after "<primitive>." (every type has
// them): the one place that says so. Their float rows are measured and
// reported, not held to the float caps; docs/numerics.md ("What float cannot
// do") gives the figures. Float misclassifies no ray in any family; what it
// cannot meet is the t cap where t is tiny against the numbers the ray
// carries: rays grazing a surface at 1e-4..1e-7 rad (t error p99 up to ~7e-4),
// rays tangent to a torus's tube (2.2e-4 at r/R = 0.5: grazing by another
// name) and huge objects seen from close by (size 1e2..1e6 from 0.01..10
// units: ~1e-3).
const std::vector<std::string> kDoubleOnlyFamilies = {"grazing", "huge", "tangent"};

bool double_only(const Family& family) {
  const std::string own_name = family.name.substr(family.primitive.size() + 1);
  return std::find(kDoubleOnlyFamilies.begin(), kDoubleOnlyFamilies.end(), own_name) != kDoubleOnlyFamilies.end();
}

}  // namespace

std::vector<Family> make_families(Mode mode, const std::string& primitive) {
  const auto& types = primitive_types();
  if (!primitive.empty() && std::find(types.begin(), types.end(), primitive) == types.end())
    throw std::invalid_argument("unknown primitive type '" + primitive + "'");
  std::vector<Family> families;
  Builder b{mode, &families};
  for (const std::string& type : types) {
    if (!primitive.empty() && type != primitive) continue;
    add_common(b, type);
    if (const auto& own = cases_of(type).families) own(b);
  }
  for (Family& family : families) family.double_only = double_only(family);
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
