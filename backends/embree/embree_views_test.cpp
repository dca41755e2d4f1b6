// The light buffers (embree_view_buffers.hpp) against the brute-force
// double oracle: camera rays from the eye, shadow rays toward point and
// directional lights shaped as the shading makes them (offset origins,
// rays that end next to the light), with and without buffers.
#include <gtest/gtest.h>

#include <cstring>

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
  int rays = 0, hits = 0, blocked = 0, unkeyed = 0;
};

void check_camera_rays(Rng& rng, Scene& scene, EmbreeQuery& query, Counts& counts) {
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

// The rays of a tile: a grid of rows x columns directions across `axis`,
// `spread` apart (in the plane one unit along the axis), from `eye`.
std::vector<Ray> tile_rays(Rng& rng, const glm::dvec3& eye, const glm::dvec3& axis, double spread, int rows, int columns) {
  const glm::dvec3 helper = std::abs(axis.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 across = glm::normalize(glm::cross(axis, helper)), up = glm::cross(axis, across);
  std::vector<Ray> rays;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const double u = spread * (i + uniform(rng, 0, 1)), v = spread * (j + uniform(rng, 0, 1));
      rays.push_back({eye, glm::normalize(axis + u * across + v * up)});
    }
  return rays;
}

// camera_closest_batch against camera_closest, bit for bit (id, t and the
// plugin's hit data): tiles of 16 x 16 rays and odd sizes, narrow and wide,
// aimed at objects or anywhere, rays from everywhere, and a batch with one
// ray not from the eye (which no buffer holds).
void check_camera_batches(Rng& rng, Scene& scene, EmbreeQuery& query, Counts& counts) {
  const glm::dvec3 eye = 14.0 * random_unit(rng);
  query.prepare_views(eye);
  for (int b = 0; b < 24; ++b) {
    const Ray aim = random_ray(rng, scene, 0.0, eye);
    const double spread = std::array{1e-4, 2e-3, 2e-2, 0.2}[size_t(b % 4)];
    std::vector<Ray> rays = b % 6 == 5 ? std::vector<Ray>{} : tile_rays(rng, eye, aim.dir, spread, 16, b % 3 == 0 ? 13 : 16);
    if (b % 6 == 5)
      for (int j = 0; j < 97; ++j) rays.push_back(random_ray(rng, scene, 0.0, eye));
    if (b == 7) rays.back().origin += glm::dvec3(1e-9, 0, 0);
    std::vector<Hit> got(rays.size());
    query.camera_closest_batch(rays, got.data());
    for (size_t j = 0; j < rays.size(); ++j) {
      const Hit want = query.camera_closest(rays[j]);
      ASSERT_EQ(got[j].id, want.id) << "batch " << b << ", ray " << j;
      ASSERT_EQ(got[j].t, want.t);
      ASSERT_EQ(std::memcmp(&got[j].prim, &want.prim, sizeof(PrismHit)), 0);
      ++counts.rays;
      counts.hits += want.found();
    }
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

// Shadow rays in lanes, as the shading casts them: many toward one light,
// their cells looked up at once (light_keys), then answered one by one.
void check_shadow_lanes(Rng& rng, Scene& scene, EmbreeQuery& query, Counts& counts) {
  scene.lights = {random_light(rng), random_light(rng)};
  const glm::dvec3 eye = 14.0 * random_unit(rng);
  query.prepare_views(eye);
  for (size_t k = 0; k < scene.lights.size(); ++k) {
    std::vector<Ray> rays;
    std::vector<double> tmax;
    while (rays.size() < 61) {  // not a multiple of any lane width
      if (rays.size() % 10 == 9) {  // one ray in ten anywhere: no buffer holds most of them
        rays.push_back(random_ray(rng, scene, 10.0));
        tmax.push_back(uniform(rng, 0, 30));
        continue;
      }
      glm::dvec3 point, normal;
      if (!random_surface_point(rng, scene, eye, point, normal)) continue;
      rays.push_back(shadow_ray(scene.lights[k], point, normal, tmax.emplace_back()));
    }
    std::array<std::vector<double>, 3> origin, dir;
    for (const Ray& ray : rays)
      for (int a = 0; a < 3; ++a) {
        origin[size_t(a)].push_back(ray.origin[a]);
        dir[size_t(a)].push_back(ray.dir[a]);
      }
    const RayLanes lanes{{origin[0].data(), origin[1].data(), origin[2].data()},
                         {dir[0].data(), dir[1].data(), dir[2].data()}, tmax.data(), rays.size()};
    std::vector<int32_t> keys(rays.size());
    query.light_keys(k, lanes, keys.data());
    // All at once: some rays not cast, some leaving an object they cannot meet.
    std::vector<uint8_t> cast(rays.size());
    std::vector<int32_t> self(rays.size()), blockers(rays.size());
    for (size_t j = 0; j < rays.size(); ++j) {
      cast[j] = rng() % 8 != 0;
      self[j] = rng() % 3 == 0 ? int32_t(rng() % scene.objects.size()) : kMissId;
    }
    query.keyed_light_occluders(k, lanes, keys.data(), self.data(), cast.data(), blockers.data());
    for (size_t j = 0; j < rays.size(); ++j) {
      const bool want = brute_occluded(scene, rays[j], tmax[j]);
      ASSERT_EQ(query.keyed_light_occluder(k, rays[j], tmax[j], {}, keys[j]) != kMissId, want) << "light " << k;
      const int32_t one = query.keyed_light_occluder(k, rays[j], tmax[j], {self[j], kMissId}, keys[j]);
      ASSERT_EQ(blockers[j], cast[j] ? one : kMissId) << "light " << k << ", ray " << j;
      ++counts.rays;
      counts.blocked += want;
      counts.unkeyed += keys[j] == kNoCell;
    }
  }
}

// `check` on `count` random scenes of every plugin type, 12, 12 + step, ...
// objects: few enough for the light buffers.
template <class Check>
void on_random_scenes(uint64_t seed, int count, int step, Counts& counts, const Check& check) {
  const auto types = available_types();
  Rng rng(seed);
  for (int s = 0; s < count; ++s) {
    Scene scene = load(random_objects_json(rng, types, 12 + step * s));
    EmbreeQuery query(scene, device());
    ASSERT_NO_FATAL_FAILURE(check(rng, scene, query, counts));
    ASSERT_TRUE(query.has_views());
  }
}

TEST(EmbreeViews, CameraRaysMatchBruteForce) {
  REQUIRE_PRIMITIVE("sphere");
  Counts counts;
  on_random_scenes(11, 8, 6, counts, check_camera_rays);
  EXPECT_GT(counts.hits, 6000);
}

TEST(EmbreeViews, CameraBatchesAnswerAsOneRayAtATime) {
  REQUIRE_PRIMITIVE("sphere");
  Counts counts;
  on_random_scenes(19, 8, 6, counts, check_camera_batches);
  EXPECT_GT(counts.rays, 8 * 24 * 200);
  EXPECT_GT(counts.hits, 20000);
}

TEST(EmbreeViews, ShadowRaysMatchBruteForce) {
  REQUIRE_PRIMITIVE("sphere");
  Counts counts;
  on_random_scenes(12, 8, 6, counts, check_shadow_rays);
  EXPECT_GT(counts.rays, 20000);
  EXPECT_GT(counts.blocked, 4000);
}

TEST(EmbreeViews, ShadowRaysInLanesAndBatchesMatchBruteForce) {
  REQUIRE_PRIMITIVE("sphere");
  Counts counts;
  on_random_scenes(16, 16, 3, counts, [](Rng& rng, Scene& scene, EmbreeQuery& query, Counts& c) {
    for (int round = 0; round < 10; ++round) ASSERT_NO_FATAL_FAILURE(check_shadow_lanes(rng, scene, query, c));
  });
  EXPECT_EQ(counts.rays, 16 * 10 * 2 * 61);
  EXPECT_GT(counts.blocked, 2000);
  EXPECT_GT(counts.unkeyed, 1000);
}

// Every lane width looks up the same cells as one ray at a time, for rays
// near and far from a point light, along and across a directional one.
TEST(EmbreeViews, EveryLaneWidthLooksUpTheSameCells) {
  Rng rng(17);
  std::vector<BoundSphere> spheres;
  for (int32_t id = 0; id < 24; ++id)
    spheres.push_back({glm::dvec3(uniform(rng, -8, 8), uniform(rng, -8, 8), uniform(rng, -8, 8)), uniform(rng, 0.1, 2), id});
  const glm::dvec3 apex(1, 9, 2), sun = random_unit(rng);
  const PointBuffer point(apex, spheres, 0.05);
  const ParallelBuffer parallel(sun, spheres, 10.0);
  std::array<std::vector<double>, 3> origin, toward, along;
  std::vector<double> tmax, infinite;
  for (int j = 0; j < 1003; ++j) {
    const glm::dvec3 o(uniform(rng, -20, 20), uniform(rng, -20, 20), uniform(rng, -20, 20));
    // Toward the apex, ending on it, short of it or past it; some along an axis or a face's diagonal.
    glm::dvec3 d = j % 7 == 0 ? glm::dvec3(0, 1, 0) : j % 11 == 0 ? glm::normalize(glm::dvec3(1, 1, 0)) : glm::normalize(apex - o);
    const double t = glm::length(apex - o) + (j % 3 == 0 ? 0.0 : uniform(rng, -0.2, 0.2));
    const glm::dvec3 s = j % 5 == 0 ? random_unit(rng) : sun;
    for (int a = 0; a < 3; ++a) {
      origin[size_t(a)].push_back(o[a]);
      toward[size_t(a)].push_back(d[a]);
      along[size_t(a)].push_back(s[a]);
    }
    tmax.push_back(t);
    infinite.push_back(kInfinity);
  }
  auto lanes = [&](const std::array<std::vector<double>, 3>& dir, const std::vector<double>& t, size_t first,
                   size_t count) {
    return RayLanes{{origin[0].data() + first, origin[1].data() + first, origin[2].data() + first},
                    {dir[0].data() + first, dir[1].data() + first, dir[2].data() + first}, t.data() + first, count};
  };
  const size_t n = tmax.size();
  std::vector<int32_t> point_one(n), parallel_one(n);
  for (size_t j = 0; j < n; ++j) {
    point.cells_toward(lanes(toward, tmax, j, 1), &point_one[j], 2);
    parallel.cells_of(lanes(along, infinite, j, 1), &parallel_one[j], 2);
  }
  int near = 0, inside = 0;
  for (size_t j = 0; j < n; ++j) {
    near += point_one[j] >= 0;
    inside += parallel_one[j] >= 0;
  }
  EXPECT_GT(near, 300);  // the test looks up cells, not only refusals
  EXPECT_GT(inside, 150);
  for (const int width : lane_widths()) {
    std::vector<int32_t> point_cells(n), parallel_cells(n);
    point.cells_toward(lanes(toward, tmax, 0, n), point_cells.data(), width);
    parallel.cells_of(lanes(along, infinite, 0, n), parallel_cells.data(), width);
    EXPECT_EQ(point_cells, point_one) << "width " << width;
    EXPECT_EQ(parallel_cells, parallel_one) << "width " << width;
  }
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
