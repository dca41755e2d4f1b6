// The light buffers (embree_view_buffers.hpp) against the brute-force
// double oracle: camera rays from the eye, shadow rays toward point and
// directional lights shaped as the shading makes them (offset origins,
// rays that end next to the light), with and without buffers.
#include <gtest/gtest.h>

#include "embree_device.hpp"
#include "embree_query.hpp"
#include "embree_test_scenes.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

Device& device() {
  static Device instance;
  return instance;
}

// The format's offset for a hit at p.
double offset_epsilon(const glm::dvec3& p) {
  return 1e-4 * (1.0 + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
}

// A point on some object (where a random ray from `eye` lands), with the
// outward normal there; false when the ray misses.
bool random_surface_point(Rng& rng, const Scene& scene, const glm::dvec3& eye, glm::dvec3& point, glm::dvec3& normal) {
  const Ray ray = random_ray(rng, scene, 1.0, eye);
  const Hit hit = brute_closest(scene, ray, 0.0);
  if (!hit.found()) return false;
  const SurfacePoint s = surface_of(scene.objects[size_t(hit.id)], ray, hit.prim);
  point = s.position;
  normal = glm::dot(s.normal, ray.dir) < 0 ? s.normal : -s.normal;
  return true;
}

// A shadow ray toward `light` from a surface point, as the shading makes it.
Ray shadow_ray(const Light& light, const glm::dvec3& point, const glm::dvec3& normal, double& tmax) {
  const glm::dvec3 origin = point + offset_epsilon(point) * normal;
  if (light.type == Light::Type::Directional) {
    tmax = kInfinity;
    return {origin, -light.direction};
  }
  tmax = glm::length(light.position - origin);
  return {origin, glm::normalize(light.position - point)};
}

Light random_light(Rng& rng) {
  Light light;
  if (rng() % 2 == 0) {
    light.type = Light::Type::Directional;
    light.direction = random_unit(rng);
  } else {
    light.position = glm::dvec3(uniform(rng, -12, 12), uniform(rng, -12, 12), uniform(rng, -12, 12));
  }
  return light;
}

struct Counts {
  int rays = 0, hits = 0, blocked = 0;
};

void check_camera_rays(Rng& rng, const Scene& scene, EmbreeQuery& query, Counts& counts) {
  const glm::dvec3 eye = 14.0 * random_unit(rng);
  query.prepare_views(eye);
  for (int i = 0; i < 1500; ++i) {
    const Ray ray = random_ray(rng, scene, 0.0, eye);
    const Hit want = brute_closest(scene, ray, 0.0);
    const Hit got = query.camera_closest(ray);
    ASSERT_EQ(got.id, want.id) << "eye (" << eye.x << "," << eye.y << "," << eye.z << ")";
    if (want.found()) {
      ASSERT_EQ(got.t, want.t);
    }
    ++counts.rays;
    counts.hits += want.found();
  }
}

void check_shadow_rays(Rng& rng, Scene& scene, EmbreeQuery& query, Counts& counts) {
  scene.lights = {random_light(rng), random_light(rng), random_light(rng)};
  const glm::dvec3 eye = 14.0 * random_unit(rng);
  query.prepare_views(eye);
  for (int i = 0; i < 1500; ++i) {
    glm::dvec3 point, normal;
    if (!random_surface_point(rng, scene, eye, point, normal)) continue;
    for (size_t k = 0; k < scene.lights.size(); ++k) {
      double tmax = 0;
      const Ray ray = shadow_ray(scene.lights[k], point, normal, tmax);
      const bool want = brute_occluded(scene, ray, tmax);
      const int32_t blocker = query.light_occluder(k, ray, tmax);
      ASSERT_EQ(blocker != kMissId, want) << "light " << k;
      if (want) {
        ASSERT_TRUE(blocks(scene.objects[size_t(blocker)], ray, tmax));
      }
      ++counts.rays;
      counts.blocked += want;
    }
  }
}

TEST(EmbreeViews, CameraRaysMatchBruteForce) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  Rng rng(11);
  Counts counts;
  for (int s = 0; s < 8; ++s) {
    const Scene scene = load(random_objects_json(rng, types, 12 + 6 * s));
    EmbreeQuery query(scene, device());
    ASSERT_NO_FATAL_FAILURE(check_camera_rays(rng, scene, query, counts));
    ASSERT_TRUE(query.has_views());
  }
  EXPECT_GT(counts.hits, 6000);
}

TEST(EmbreeViews, ShadowRaysMatchBruteForce) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  Rng rng(12);
  Counts counts;
  for (int s = 0; s < 8; ++s) {
    Scene scene = load(random_objects_json(rng, types, 12 + 6 * s));
    EmbreeQuery query(scene, device());
    ASSERT_NO_FATAL_FAILURE(check_shadow_rays(rng, scene, query, counts));
    ASSERT_TRUE(query.has_views());
  }
  EXPECT_GT(counts.rays, 20000);
  EXPECT_GT(counts.blocked, 4000);
}

// A light inside an object's sphere, on an object's box, and shadow rays
// that graze objects on their way to the light.
TEST(EmbreeViews, LightsInsideAndGrazingRays) {
  REQUIRE_PRIMITIVE("sphere");
  Scene scene = load(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1},
                         {"type": "sphere", "center": [3, 0, 0], "radius": 0.5},
                         {"type": "sphere", "center": [0, 3, 0], "radius": 0.001})");
  EmbreeQuery query(scene, device());
  Light inside;
  inside.position = {3, 0.3, 0};  // in the second sphere
  Light on_box;
  on_box.position = {0, 1, 0};  // on the first sphere's box, at its top
  scene.lights = {inside, on_box};
  query.prepare_views({0, 0, -10});
  Rng rng(13);
  int rays = 0;
  for (size_t k = 0; k < scene.lights.size(); ++k) {
    for (int i = 0; i < 4000; ++i) {
      // Rays toward the light that pass at random small distances from the spheres' silhouettes.
      const glm::dvec3 origin = scene.lights[k].position + uniform(rng, 0.5, 8) * random_unit(rng);
      const Ray ray{origin, glm::normalize(scene.lights[k].position - origin)};
      const double tmax = glm::length(scene.lights[k].position - origin);
      ASSERT_EQ(query.light_occluder(k, ray, tmax) != kMissId, brute_occluded(scene, ray, tmax)) << k;
      ++rays;
    }
  }
  EXPECT_EQ(rays, 8000);
}

// Rays the buffers cannot vouch for take the full query: an end far from
// the light, another direction than the directional light's, a far origin.
TEST(EmbreeViews, RaysOutsideTheBuffersFallBack) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  Rng rng(14);
  Scene scene = load(random_objects_json(rng, types, 30));
  EmbreeQuery query(scene, device());
  Light point;
  point.position = {1, 15, 2};
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::dvec3(0.3, -1, 0.2));
  scene.lights = {point, sun};
  query.prepare_views({0, 0, -30});
  for (int i = 0; i < 3000; ++i) {
    const Ray ray = random_ray(rng, scene, i % 2 == 0 ? 14.0 : 1e7);
    const double tmax = uniform(rng, 0.0, 40.0);
    const bool want = brute_occluded(scene, ray, tmax);
    ASSERT_EQ(query.light_occluder(0, ray, tmax) != kMissId, want);
    ASSERT_EQ(query.light_occluder(1, ray, tmax) != kMissId, want);
    ASSERT_EQ(query.camera_closest(ray).id, brute_closest(scene, ray, 0.0).id);
  }
}

TEST(EmbreeViews, LargeScenesUseTheBvhAlone) {
  REQUIRE_PRIMITIVE("sphere");
  Rng rng(15);
  const Scene scene = load(random_objects_json(rng, {"sphere"}, 200));
  EmbreeQuery query(scene, device());
  query.prepare_views({0, 0, -30});
  EXPECT_FALSE(query.has_views());
}

}  // namespace
}  // namespace prism::embree
