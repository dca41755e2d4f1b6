// Helpers for embree_test.cpp: random scenes of every primitive type whose
// plugin is installed (each type's random objects come from its cases
// module, plugins/<type>/<type>_cases.cpp), random rays, and the
// brute-force double oracle.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "primitive_cases.hpp"
#include "prism/backend.hpp"
#include "prism/errors.hpp"
#include "prism/geometry.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"

namespace prism::embree::testing {

inline Registry& registry() {
  static Registry instance;
  return instance;
}

// A backend created through the registry, as `prism` creates it.
inline std::unique_ptr<Backend> create_backend(const std::string& name) { return registry().backend(name)->create(); }

inline bool has_primitive(const std::string& type) {
  try {
    registry().primitive(type);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

// Skips the test when the primitive plugin for `type` is not built here.
#define REQUIRE_PRIMITIVE(type) \
  if (!::prism::embree::testing::has_primitive(type)) GTEST_SKIP() << "primitive plugin '" << (type) << "' not found"

// Every type with random objects in its cases module (tests/cases/primitive_cases.hpp)
// whose plugin loads here, ordered by type: no list of types here.
inline std::vector<std::string> available_types() {
  std::vector<std::string> found;
  for (const cases::PrimitiveCases* type : cases::all_primitive_cases())
    if (type->random_object && has_primitive(type->type)) found.push_back(type->type);
  return found;
}

inline Scene load(const std::string& objects_json) {
  const std::string json = R"({"prism": 1, "camera": {"position": [0, 0, -30], "look_at": [0, 0, 0]},
    "lights": [{"type": "point", "position": [5, 20, -10]}], "objects": [)" +
                           objects_json + "]}";
  return load_scene_from_string(json, ".", registry(), "<embree test>");
}

using Rng = cases::SceneRng;
using cases::num;
using cases::Placement;
using cases::uniform;
using cases::vec;

// One object of `type` with random parameters, as JSON: its cases module's.
inline std::string random_object(Rng& rng, const std::string& type, const Placement& at = {}) {
  const cases::PrimitiveCases* found = cases::find_primitive_cases(type);
  if (!found || !found->random_object) throw std::runtime_error("no random objects for the type '" + type + "'");
  return found->random_object(rng, at);
}

// A type of `types`, each drawn as often as its random_share says.
inline std::string random_type(Rng& rng, const std::vector<std::string>& types) {
  for (;;) {
    const std::string& type = types[rng() % types.size()];
    const cases::PrimitiveCases* found = cases::find_primitive_cases(type);
    const double share = found ? found->random_share : 1;  // none: random_object says so
    if (share >= 1 || uniform(rng, 0, 1) < share) return type;
  }
}

// A random scene of `count` objects of the available types; about one in ten
// repeats an earlier object exactly, so that equal t happens.
inline std::string random_objects_json(Rng& rng, const std::vector<std::string>& types, int count,
                                       const Placement& at = {}) {
  std::vector<std::string> objects;
  for (int i = 0; i < count; ++i) {
    if (!objects.empty() && rng() % 10 == 0) {
      objects.push_back(objects[rng() % objects.size()]);
    } else {
      objects.push_back(random_object(rng, random_type(rng, types), at));
    }
  }
  std::string json;
  for (const auto& o : objects) json += (json.empty() ? "" : ",") + o;
  return json;
}

inline glm::dvec3 random_unit(Rng& rng) {
  for (;;) {
    glm::dvec3 v(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    double l = glm::length(v);
    if (l > 1e-3 && l <= 1) return v / l;
  }
}

// A point of `box`: inside, or (one time in two) on its boundary: a face,
// an edge or a corner, where the object may touch its box.
inline glm::dvec3 point_of_box(Rng& rng, const Box3& b) {
  glm::dvec3 p(uniform(rng, b.lo.x, b.hi.x), uniform(rng, b.lo.y, b.hi.y), uniform(rng, b.lo.z, b.hi.z));
  if (rng() % 2 == 0) {
    const int snapped = 1 + static_cast<int>(rng() % 3);
    for (int k = 0; k < snapped; ++k) {
      const int a = static_cast<int>(rng() % 3);
      p[a] = rng() % 2 ? b.lo[a] : b.hi[a];
    }
  }
  return p;
}

// A ray from origin_center + a random point within origin_scale toward a
// random object's box (so most rays hit or graze something), or (one time
// in four) in a random direction.
inline Ray random_ray(Rng& rng, const Scene& scene, double origin_scale, glm::dvec3 origin_center = glm::dvec3(0)) {
  Ray ray;
  ray.origin = origin_center + origin_scale * random_unit(rng) * uniform(rng, 0.0, 1.0);
  const Object& target = scene.objects[rng() % scene.objects.size()];
  if (target.bounded && rng() % 4 != 0) {
    ray.dir = glm::normalize(point_of_box(rng, target.world_bounds) - ray.origin);
  } else {
    ray.dir = random_unit(rng);
  }
  return ray;
}

// Ground truth: every object in id order, ties to the lower id.
inline Hit brute_closest(const Scene& scene, const Ray& ray, double tmin) {
  Hit best;
  for (size_t id = 0; id < scene.objects.size(); ++id) {
    PrismHit hit;
    if (intersect_object(scene.objects[id], ray, tmin, best.t, hit) && hit.t < best.t) {
      best.t = hit.t;
      best.id = static_cast<int32_t>(id);
      best.prim = hit;
    }
  }
  return best;
}

inline bool brute_occluded(const Scene& scene, const Ray& ray, double tmax) {
  return std::ranges::any_of(scene.objects, [&](const Object& object) {
    PrismHit hit;
    return intersect_object(object, ray, 0.0, tmax, hit) && hit.t < tmax;
  });
}

}  // namespace prism::embree::testing
