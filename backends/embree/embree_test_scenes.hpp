// Helpers for embree_test.cpp: random scenes of every primitive type whose
// plugin is installed, random rays, and the brute-force double oracle.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

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

// The types of the format whose plugin loads here.
inline std::vector<std::string> available_types() {
  std::vector<std::string> found;
  for (const char* type : {"sphere", "plane", "box", "torus", "ring", "quadric", "cylinder", "cone"}) {
    if (has_primitive(type)) found.emplace_back(type);
  }
  return found;
}

inline Scene load(const std::string& objects_json) {
  const std::string json = R"({"prism": 1, "camera": {"position": [0, 0, -30], "look_at": [0, 0, 0]},
    "lights": [{"type": "point", "position": [5, 20, -10]}], "objects": [)" +
                           objects_json + "]}";
  return load_scene_from_string(json, ".", registry(), "<embree test>");
}

using Rng = std::mt19937_64;

inline double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

inline std::string num(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

inline std::string vec(double x, double y, double z) { return "[" + num(x) + ", " + num(y) + ", " + num(z) + "]"; }

inline std::string random_vec(Rng& rng, double lo, double hi) {
  return vec(uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi));
}

// Where objects go: centres in offset + [-8, 8]^3 * scale, sizes times scale.
struct Placement {
  glm::dvec3 offset{0};
  double scale = 1;
};

// A random centre; a random rotation two times in three (else axis-aligned,
// where box faces coincide with the BVH's boxes).
inline std::string random_frame(Rng& rng, const Placement& at) {
  const glm::dvec3 c = at.offset + at.scale * glm::dvec3(uniform(rng, -8, 8), uniform(rng, -8, 8), uniform(rng, -8, 8));
  std::string frame = "\"center\": " + vec(c.x, c.y, c.z);
  if (rng() % 3 == 0) return frame;
  return frame + ", \"rotation\": {\"axis\": " + random_vec(rng, 0.1, 1) + ", \"degrees\": " + num(uniform(rng, 0, 360)) +
         "}";
}

// One object of `type` with random parameters, as JSON.
inline std::string random_object(Rng& rng, const std::string& type, const Placement& at = {}) {
  const double s = at.scale * uniform(rng, 0.2, 1.5);
  std::string body;
  if (type == "sphere") body = "\"radius\": " + num(s);
  if (type == "box") body = "\"half_size\": " + vec(s, s * uniform(rng, 0.1, 1), s * uniform(rng, 0.1, 1));
  if (type == "torus") body = "\"major_radius\": " + num(s) + ", \"minor_radius\": " + num(s * uniform(rng, 0.05, 0.5));
  if (type == "ring") body = "\"inner_radius\": " + num(s * 0.4) + ", \"outer_radius\": " + num(s);
  if (type == "cylinder" || type == "cone") body = "\"radius\": " + num(s) + ", \"height\": " + num(2 * s);
  if (type == "quadric") {
    // Half the time a clipped hyperboloid (bounded), else an unclipped ellipsoid (brute force).
    if (rng() % 2 == 0) {
      body = "\"coefficients\": [1, -1, 1, 0, 0, 0, 0, 0, 0, " + num(-0.25 * s * s) + "], \"clip_min\": " +
             vec(-s, -s, -s) + ", \"clip_max\": " + vec(s, s, s);
    } else {
      body = "\"coefficients\": [" + num(1 / (s * s)) + ", 2, 3, 0, 0, 0, 0, 0, 0, -1]";
    }
  }
  if (type == "plane") {
    const glm::dvec3 p = at.offset + at.scale * glm::dvec3(uniform(rng, -12, 12), uniform(rng, -12, 12), uniform(rng, -12, 12));
    return R"({"type": "plane", "point": )" + vec(p.x, p.y, p.z) + ", \"normal\": " + random_vec(rng, -1, 1) + "}";
  }
  return "{\"type\": \"" + type + "\", " + random_frame(rng, at) + ", " + body + "}";
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
      // Planes are rare: a scene full of them tests little of the BVH.
      std::string type = types[rng() % types.size()];
      if (type == "plane" && rng() % 4 != 0) type = types[0];
      objects.push_back(random_object(rng, type, at));
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
