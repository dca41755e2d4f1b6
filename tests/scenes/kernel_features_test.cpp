// A GPU kernel compiled with every feature forced in (PRISM_KERNEL_FEATURES=all)
// renders a scene to the same image as the kernel specialised to the scene:
// leaving features out changes nothing but speed. Backends without
// specialised kernels pass trivially.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace {

struct Rendered {
  prism::Image image;
  std::vector<std::string> features;
};

Rendered render(prism::Registry& registry, const std::string& backend, const prism::Scene& scene) {
  prism::RenderSettings settings;
  settings.image = scene.image;
  settings.image.width = 160;
  settings.image.height = 90;
  settings.aov_id = true;
  settings.aov_path = true;
  auto instance = registry.backend(backend)->create();
  instance->prepare(scene);
  prism::Image image = instance->render(settings);
  return {std::move(image), instance->stats().kernel_features};
}

class KernelFeatures : public testing::TestWithParam<std::string> {};

TEST_P(KernelFeatures, ForcingEveryFeatureChangesNoPixel) {
  const std::string backend = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  // Mirrors, shadows and a texture: several features absent, so forcing them changes the kernel.
  prism::Scene scene = prism::load_scene(prism::test::source_dir() / "scenes" / "conformance" / "mirror.json", registry);
  ::unsetenv("PRISM_KERNEL_FEATURES");
  Rendered specialised = render(registry, backend, scene);
  ::setenv("PRISM_KERNEL_FEATURES", "all", 1);
  Rendered everything = render(registry, backend, scene);
  ::unsetenv("PRISM_KERNEL_FEATURES");
  if (!specialised.features.empty()) {
    EXPECT_GT(everything.features.size(), specialised.features.size());
  }
  ASSERT_EQ(specialised.image.rgb.size(), everything.image.rgb.size());
  double worst = 0.0;
  for (size_t i = 0; i < specialised.image.rgb.size(); ++i)
    worst = std::max(worst, double(std::abs(specialised.image.rgb[i] - everything.image.rgb[i])));
  std::printf("largest difference %.3g\n", worst);
  EXPECT_EQ(std::memcmp(specialised.image.rgb.data(), everything.image.rgb.data(), specialised.image.rgb.size() * sizeof(float)), 0);
  EXPECT_EQ(specialised.image.id, everything.image.id);
  EXPECT_EQ(specialised.image.path, everything.image.path);
}

INSTANTIATE_TEST_SUITE_P(Backends, KernelFeatures, testing::ValuesIn(prism::test::backend_names()),
                         prism::test::backend_param_name);

}  // namespace
