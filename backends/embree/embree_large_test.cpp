// The 100,000-sphere scene through the Embree plugin: it builds, renders a
// small image, and a sample of its rays agrees with the brute-force oracle.
// A separate program (label "large"): loading 100,000 objects takes seconds,
// and minutes in the sanitizer build, which runs only the "unit" tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "embree_test_scenes.hpp"
#include "prism/backend.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

// Spheres on a jittered nx x ny x nz grid, 2 apart; 50 x 40 x 50 is the
// 100,000-sphere scene bench/make_spheres writes.
std::string sphere_field_json(int nx = 50, int ny = 40, int nz = 50) {
  Rng rng(10);
  std::string json;
  json.reserve(size_t(nx * ny * nz) * 80);
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      for (int k = 0; k < nz; ++k) {
        json += (json.empty() ? "" : ",");
        json += "{\"type\": \"sphere\", \"center\": " +
                vec(2.0 * i - (nx - 1) + uniform(rng, -0.4, 0.4), 2.0 * j - (ny - 1) + uniform(rng, -0.4, 0.4),
                    2.0 * k - (nz - 1) + uniform(rng, -0.4, 0.4)) +
                ", \"radius\": " + num(uniform(rng, 0.2, 0.6)) + "}";
      }
    }
  }
  return json;
}

double median(std::vector<double> v) {
  std::ranges::sort(v);
  return v[v.size() / 2];
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

TEST(EmbreeBackend, HundredThousandSpheresBuildAndRender) {
  REQUIRE_PRIMITIVE("sphere");
  const Scene scene = load(sphere_field_json());
  ASSERT_EQ(scene.objects.size(), 100000u);
  const auto embree = create_backend("embree");
  embree->prepare(scene);
  EXPECT_GT(embree->stats().ms.at("build"), 0.0);
  RenderSettings settings;
  settings.image = ImageSettings{96, 54, 1, 3};
  settings.aov_id = true;
  const Image image = embree->render(settings);
  ASSERT_EQ(image.rgb.size(), 96u * 54u * 3u);
  EXPECT_TRUE(std::ranges::none_of(image.rgb, [](float v) { return std::isnan(v); }));
  EXPECT_GT(std::ranges::count_if(image.id, [](float id) { return id >= 0; }), 96 * 54 / 2);
  // A sample of rays against the oracle (100,000 objects per oracle ray).
  Rng rng(11);
  std::vector<TraceQuery> rays;
  for (int i = 0; i < 60; ++i) {
    const Ray ray = random_ray(rng, scene, 120);
    rays.push_back(TraceQuery{ray.origin, ray.dir, 0.0});
  }
  const auto got = embree->trace(rays);
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit want = brute_closest(scene, Ray{rays[i].origin, rays[i].dir}, 0.0);
    ASSERT_EQ(got[i].id, want.id) << "ray " << i;
    ASSERT_EQ(got[i].t, want.t) << "ray " << i;
  }
}

// What Backend::update saves on 10,000 spheres: a full prepare against a
// one-object update (layered, embree_update.hpp), medians of several.
TEST(EmbreeBackend, TenThousandSpheresOneObjectUpdateAgainstAPrepare) {
  REQUIRE_PRIMITIVE("sphere");
  Scene scene = load(sphere_field_json(25, 16, 25));
  ASSERT_EQ(scene.objects.size(), 10000u);
  // Sphere 5000 at two places near its own, read as the library API reads an edit.
  std::vector<Object> places;
  for (double dx : {0.1, -0.1}) {
    const glm::dvec3 c = scene.objects[5000].center + glm::dvec3(dx, 0.05, 0);
    std::string one = "{\"type\": \"sphere\", \"center\": " + vec(c.x, c.y, c.z) + ", \"radius\": 0.3}";
    places.push_back(load(one).objects[0]);
  }
  const auto embree = create_backend("embree");
  std::vector<double> prepares;
  for (int i = 0; i < 7; ++i) {
    const auto start = std::chrono::steady_clock::now();
    embree->prepare(scene);
    prepares.push_back(ms_since(start));
  }
  std::vector<double> updates;
  SceneChanges changes;
  changes.objects = {5000};
  for (int i = 0; i < 9; ++i) {
    scene.objects[5000] = places[size_t(i % 2)];
    const auto start = std::chrono::steady_clock::now();
    embree->update(scene, changes);
    updates.push_back(ms_since(start));
  }
  std::printf("[   info   ] 10,000 spheres: prepare %.3f ms, one-object update %.4f ms (medians of 7 and 9)\n",
              median(prepares), median(updates));
  EXPECT_EQ(embree->stats().counters.at(counter::kBvhRefits), 9.0);
  EXPECT_EQ(embree->stats().counters.at(counter::kBvhBuilds), 7.0);
  EXPECT_LT(median(updates), median(prepares) / 10);
}

}  // namespace
}  // namespace prism::embree
