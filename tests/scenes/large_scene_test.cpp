// The 100,000-sphere scene on every backend but the reference: it builds,
// renders, and a sample of its rays agrees with the reference backend's
// brute force. A separate program (label "large"): loading 100,000 objects
// takes a second, and minutes in the sanitizer build.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace {

// 100,000 spheres on a jittered 50 x 40 x 50 grid, as bench/make_spheres writes them.
std::string sphere_field_json() {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4), radius(0.2, 0.6);
  std::string json = R"({"prism": 1, "camera": {"position": [0, 0, 120], "look_at": [0, 0, 0]},
    "lights": [{"type": "directional", "direction": [-1, -2, -1]}], "objects": [)";
  json.reserve(100000 * 90);
  char buffer[160];
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 40; ++j)
      for (int k = 0; k < 50; ++k) {
        std::snprintf(buffer, sizeof buffer, "%s{\"type\":\"sphere\",\"center\":[%.6f,%.6f,%.6f],\"radius\":%.6f}",
                      (i + j + k) ? "," : "", 2.0 * i - 49 + jitter(rng), 2.0 * j - 39 + jitter(rng),
                      2.0 * k - 49 + jitter(rng), radius(rng));
        json += buffer;
      }
  return json + "]}";
}

class LargeScene : public testing::TestWithParam<std::string> {};

TEST_P(LargeScene, HundredThousandSpheresRenderAndAgreeWithReference) {
  const std::string backend = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  const prism::Scene scene = prism::load_scene_from_string(sphere_field_json(), ".", registry);
  ASSERT_EQ(scene.objects.size(), 100000u);
  auto instance = registry.backend(backend)->create();
  instance->prepare(scene);
  prism::RenderSettings settings;
  settings.image = prism::ImageSettings{160, 90, 1, 3};
  settings.aov_id = true;
  const prism::Image image = instance->render(settings);
  ASSERT_EQ(image.rgb.size(), 160u * 90u * 3u);
  EXPECT_TRUE(std::ranges::none_of(image.rgb, [](float v) { return !std::isfinite(v); }));
  EXPECT_GT(std::ranges::count_if(image.id, [](float id) { return id >= 0; }), 160 * 90 / 2);
  // Rays from outside the field toward random points inside it, against brute force.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<prism::TraceQuery> rays;
  for (int i = 0; i < 60; ++i) {
    glm::dvec3 origin(unit(rng) * 120, unit(rng) * 120, 120);
    glm::dvec3 target(unit(rng) * 50, unit(rng) * 40, unit(rng) * 50);
    rays.push_back({origin, glm::normalize(target - origin), 0.0});
  }
  const auto got = instance->trace(rays);
  auto reference = registry.backend("reference")->create();
  reference->prepare(scene);
  const auto want = reference->trace(rays);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(got[i].id, want[i].id) << "ray " << i;
    if (want[i].id >= 0) {
      EXPECT_NEAR(got[i].t, want[i].t, 1e-9 * want[i].t) << "ray " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, LargeScene, testing::ValuesIn(prism::test::backends_except("reference")),
                         prism::test::backend_param_name);

}  // namespace
