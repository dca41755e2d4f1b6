// Live updates through the GPU backend plugins (opengl, vulkan), loaded
// through the registry: after each kind of edit, update() then render()
// gives the image a fresh backend prepared on the edited scene gives, bit
// for bit, and the backend's counters show it sent only what changed. A
// backend that cannot run here is skipped, or fails where
// PRISM_REQUIRE_BACKENDS names it.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>

#include "gpu_update_test_scenes.hpp"
#include "prism/backend.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace prism::gpu {
namespace {

using testing_scenes::Options;

constexpr int kSpheres = 300;

class GpuLiveUpdate : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!test::require_backend_or_skip(GetParam())) return;
    plugin_ = registry_.backend(GetParam());
    scene_ = load({.count = kSpheres});
    backend_ = plugin_->create();
    backend_->prepare(scene_);
    first_ = render(*backend_, scene_);
    before_ = backend_->stats().counters;
  }

  Scene load(const Options& o) {
    return load_scene_from_string(testing_scenes::spheres_json(o), ".", registry_, "<test scene>");
  }
  static Image render(Backend& backend, const Scene& scene) {
    RenderSettings settings;
    settings.image = scene.image;
    return backend.render(settings);
  }
  // The independent path: a new backend prepared on the edited scene.
  Image fresh_render(const Scene& scene) {
    std::unique_ptr<Backend> fresh = plugin_->create();
    fresh->prepare(scene);
    return render(*fresh, scene);
  }
  // How much counter `name` grew since SetUp.
  double grew(const char* name) const { return backend_->stats().counters.at(name) - before_.at(name); }

  Registry registry_;  // first: outlives every plugin object made from it
  std::shared_ptr<const BackendPlugin> plugin_;
  Scene scene_;
  std::unique_ptr<Backend> backend_;
  Image first_;
  std::map<std::string, double> before_;
};

// Bit-identical RGB, or the first pixel that differs.
testing::AssertionResult same_image(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
    return testing::AssertionFailure() << "sizes differ";
  for (size_t i = 0; i < a.rgb.size(); ++i)
    if (std::memcmp(&a.rgb[i], &b.rgb[i], sizeof(float)) != 0)
      return testing::AssertionFailure() << "pixel " << i / 3 << " channel " << i % 3 << ": " << a.rgb[i] << " vs "
                                         << b.rgb[i];
  return testing::AssertionSuccess();
}

TEST_P(GpuLiveUpdate, CountersStartAtTheFirstPrepare) {
  EXPECT_EQ(before_.at(counter::kPrepares), 1);
  EXPECT_EQ(before_.at(counter::kUpdates), 0);
  EXPECT_EQ(before_.at(counter::kObjectsUploaded), kSpheres);
  EXPECT_EQ(before_.at(counter::kBvhBuilds), 1);
  EXPECT_EQ(before_.at(counter::kBvhRefits), 0);
  EXPECT_EQ(before_.at(counter::kKernelBuilds), 1);  // the render kernel
}

TEST_P(GpuLiveUpdate, AMovedSphereIsSentAloneAndTheBvhRefitted) {
  const Scene moved = load({.count = kSpheres, .moved = 137});
  scene_.objects[137] = moved.objects[137];
  backend_->update(scene_, {.objects = {137}});
  const Image image = render(*backend_, scene_);
  EXPECT_FALSE(same_image(image, first_));  // the edit shows
  EXPECT_TRUE(same_image(image, fresh_render(moved)));
  EXPECT_EQ(grew(counter::kUpdates), 1);
  EXPECT_EQ(grew(counter::kObjectsUploaded), 1);
  EXPECT_EQ(grew(counter::kBvhRefits), 1);
  EXPECT_EQ(grew(counter::kBvhBuilds), 0);
  EXPECT_EQ(grew(counter::kKernelBuilds), 0);
  EXPECT_EQ(grew(counter::kPrepares), 0);
}

TEST_P(GpuLiveUpdate, AMaterialThatAddsAFeatureRebuildsTheKernel) {
  const Scene glass = load({.count = kSpheres, .red_is_glass = true});
  scene_.materials = glass.materials;
  backend_->update(scene_, {.objects = {}, .materials = true});
  const Image image = render(*backend_, scene_);
  EXPECT_FALSE(same_image(image, first_));
  EXPECT_TRUE(same_image(image, fresh_render(glass)));
  EXPECT_EQ(grew(counter::kKernelBuilds), 1);
  EXPECT_EQ(grew(counter::kObjectsUploaded), 0);
  EXPECT_EQ(grew(counter::kBvhRefits) + grew(counter::kBvhBuilds), 0);
  const auto& features = backend_->stats().kernel_features;
  EXPECT_NE(std::find(features.begin(), features.end(), "dielectrics"), features.end());
}

TEST_P(GpuLiveUpdate, ALightChangeSendsTheLightsAndNoObject) {
  const Scene lit = load({.count = kSpheres, .light_x = -6});
  scene_.lights = lit.lights;
  backend_->update(scene_, {.objects = {}, .lights = true});
  const Image image = render(*backend_, scene_);
  EXPECT_FALSE(same_image(image, first_));
  EXPECT_TRUE(same_image(image, fresh_render(lit)));
  EXPECT_EQ(grew(counter::kObjectsUploaded), 0);
  EXPECT_EQ(grew(counter::kBvhRefits) + grew(counter::kBvhBuilds), 0);
  EXPECT_EQ(grew(counter::kKernelBuilds), 0);
}

TEST_P(GpuLiveUpdate, AnAddedSphereRebuildsTheBvh) {
  const Scene more = load({.count = kSpheres + 1});
  scene_.objects.push_back(more.objects[kSpheres]);
  backend_->update(scene_, {.objects = {}, .objects_added_or_removed = true});
  const Image image = render(*backend_, scene_);
  EXPECT_FALSE(same_image(image, first_));
  EXPECT_TRUE(same_image(image, fresh_render(more)));
  EXPECT_EQ(grew(counter::kBvhBuilds), 1);
  EXPECT_EQ(grew(counter::kBvhRefits), 0);
  EXPECT_EQ(grew(counter::kObjectsUploaded), kSpheres + 1);
  EXPECT_EQ(grew(counter::kKernelBuilds), 0);
}

TEST_P(GpuLiveUpdate, AnAddedLightMakesTheLightBufferAgain) {
  const Scene two = load({.count = kSpheres, .second_light = true});
  scene_.lights = two.lights;
  backend_->update(scene_, {.objects = {}, .lights = true});
  const Image image = render(*backend_, scene_);
  EXPECT_FALSE(same_image(image, first_));
  EXPECT_TRUE(same_image(image, fresh_render(two)));
  EXPECT_EQ(grew(counter::kObjectsUploaded), 0);
  // The light count is in the kernel's source (its lights are read at fixed
  // offsets, gpu/scene.glsl): one more light is one kernel build.
  EXPECT_EQ(grew(counter::kKernelBuilds), 1);
}

TEST_P(GpuLiveUpdate, ABackgroundChangeSendsNoSceneBuffer) {
  const Scene red = load({.count = kSpheres, .background_red = 0.9});
  scene_.background = red.background;
  backend_->update(scene_, {.objects = {}, .environment = true});
  const Image image = render(*backend_, scene_);
  EXPECT_FALSE(same_image(image, first_));
  EXPECT_TRUE(same_image(image, fresh_render(red)));
  EXPECT_EQ(grew(counter::kUpdates), 1);
  EXPECT_EQ(grew(counter::kObjectsUploaded), 0);
  EXPECT_EQ(grew(counter::kBvhRefits) + grew(counter::kBvhBuilds) + grew(counter::kKernelBuilds), 0);
}

TEST_P(GpuLiveUpdate, ARemovedSphereRebuildsTheBvhInTheBuffersItHad) {
  const Scene fewer = load({.count = kSpheres, .removed = 137});
  scene_.objects.erase(scene_.objects.begin() + 137);
  backend_->update(scene_, {.objects = {}, .objects_added_or_removed = true});
  const Image image = render(*backend_, scene_);
  EXPECT_FALSE(same_image(image, first_));
  EXPECT_TRUE(same_image(image, fresh_render(fewer)));
  EXPECT_EQ(grew(counter::kBvhBuilds), 1);
  EXPECT_EQ(grew(counter::kObjectsUploaded), kSpheres - 1);
}

TEST_P(GpuLiveUpdate, ManyEditsInARowStayIdenticalToAFreshPrepare) {
  // Moves, then a light, then scattering that forces a rebuild, then an added sphere.
  const Scene moved = load({.count = kSpheres, .moved = 20});
  scene_.objects[20] = moved.objects[20];
  backend_->update(scene_, {.objects = {20}});
  const Scene scattered = load({.count = kSpheres, .moved = 20, .scattered_every = 3, .light_x = -6});
  scene_.lights = scattered.lights;
  backend_->update(scene_, {.objects = {}, .lights = true});
  SceneChanges scatter;
  for (uint32_t i = 0; i < kSpheres; i += 3) {
    scene_.objects[i] = scattered.objects[i];
    scatter.objects.push_back(i);
  }
  backend_->update(scene_, scatter);
  EXPECT_EQ(grew(counter::kBvhBuilds), 1);  // the scatter passed the refit cost ratio
  EXPECT_EQ(grew(counter::kBvhRefits), 1);  // only the first move was refitted
  EXPECT_TRUE(same_image(render(*backend_, scene_), fresh_render(scattered)));
  EXPECT_EQ(grew(counter::kKernelBuilds), 0);
}

INSTANTIATE_TEST_SUITE_P(GpuBackends, GpuLiveUpdate, testing::Values("opengl", "vulkan"), test::backend_param_name);

}  // namespace
}  // namespace prism::gpu
