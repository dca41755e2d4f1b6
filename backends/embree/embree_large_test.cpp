// The 100,000-sphere scene through the Embree plugin: it builds, renders a
// small image, and a sample of its rays agrees with the brute-force oracle.
// A separate program (label "large"): loading 100,000 objects takes seconds,
// and minutes in the sanitizer build, which runs only the "unit" tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "embree_test_scenes.hpp"
#include "prism/backend.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

// 100,000 spheres on a jittered 50 x 40 x 50 grid, as bench/make_spheres writes.
std::string sphere_field_json() {
  Rng rng(10);
  std::string json;
  json.reserve(100000 * 80);
  for (int i = 0; i < 50; ++i) {
    for (int j = 0; j < 40; ++j) {
      for (int k = 0; k < 50; ++k) {
        json += (json.empty() ? "" : ",");
        json += "{\"type\": \"sphere\", \"center\": " +
                vec(2.0 * i - 49 + uniform(rng, -0.4, 0.4), 2.0 * j - 39 + uniform(rng, -0.4, 0.4),
                    2.0 * k - 49 + uniform(rng, -0.4, 0.4)) +
                ", \"radius\": " + num(uniform(rng, 0.2, 0.6)) + "}";
      }
    }
  }
  return json;
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

}  // namespace
}  // namespace prism::embree
