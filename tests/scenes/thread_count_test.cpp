// A backend's image does not depend on how many threads render it: every
// pixel's samples are summed in sample order whatever the tile schedule.
// Nor on the AOVs asked for: the CPU shading lights its points in batches,
// except a sample whose path it hashes (the `path` AOV), lit at once.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>
#include <filesystem>

#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace {

prism::Image render_showcase(prism::Registry& registry, const std::string& backend, const prism::Scene& scene,
                             bool aovs = true) {
  prism::RenderSettings settings;
  settings.image = scene.image;
  settings.image.width = 96;
  settings.image.height = 54;
  settings.image.spp = 2;
  settings.aov_id = aovs;
  settings.aov_path = aovs;
  auto instance = registry.backend(backend)->create();
  instance->prepare(scene);
  return instance->render(settings);
}

class ThreadCount : public testing::TestWithParam<std::string> {};

TEST_P(ThreadCount, OneThreadGivesTheSameBitsAsAll) {
  const std::string backend = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  prism::Scene scene = prism::load_scene(prism::test::source_dir() / "scenes" / "showcase.json", registry);
  prism::Image all_threads = render_showcase(registry, backend, scene);
  prism::Image one_thread;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = render_showcase(registry, backend, scene);
  }
  ASSERT_EQ(all_threads.rgb.size(), one_thread.rgb.size());
  EXPECT_EQ(std::memcmp(all_threads.rgb.data(), one_thread.rgb.data(), all_threads.rgb.size() * sizeof(float)), 0);
  EXPECT_EQ(all_threads.id, one_thread.id);
  EXPECT_EQ(all_threads.path, one_thread.path);
}

TEST_P(ThreadCount, TheImageIsTheSameWithOrWithoutThePathAov) {
  const std::string backend = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  prism::Scene scene = prism::load_scene(prism::test::source_dir() / "scenes" / "showcase.json", registry);
  const prism::Image with_path = render_showcase(registry, backend, scene);
  const prism::Image without = render_showcase(registry, backend, scene, false);
  ASSERT_EQ(with_path.rgb.size(), without.rgb.size());
  EXPECT_EQ(std::memcmp(with_path.rgb.data(), without.rgb.data(), with_path.rgb.size() * sizeof(float)), 0);
  EXPECT_TRUE(without.path.empty());
}

INSTANTIATE_TEST_SUITE_P(Backends, ThreadCount, testing::ValuesIn(prism::test::backend_names()),
                         prism::test::backend_param_name);

}  // namespace
