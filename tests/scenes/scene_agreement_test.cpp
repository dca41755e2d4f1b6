// Every scene under scenes/ renders to the same picture, up to rounding, on
// every backend as on the reference backend (double precision, brute force).
// Scenes render at a reduced size so the whole sweep stays quick.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> scene_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(PRISM_SOURCE_DIR) / "scenes"))
    if (entry.path().extension() == ".json") files.push_back(fs::relative(entry.path(), PRISM_SOURCE_DIR).string());
  std::sort(files.begin(), files.end());
  return files;
}

prism::Image render(prism::Registry& registry, const std::string& backend, const prism::Scene& scene) {
  prism::RenderSettings settings;
  settings.image = scene.image;
  // A quarter of the linear size (at least 16 px), one sample: enough to compare every feature.
  settings.image.width = std::max(16, scene.image.width / 4);
  settings.image.height = std::max(16, scene.image.height / 4);
  settings.image.spp = 1;
  settings.aov_id = true;
  auto instance = registry.backend(backend)->create();
  instance->prepare(scene);
  return instance->render(settings);
}

class SceneAgreement : public testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(SceneAgreement, MatchesReferenceUpToRounding) {
  const auto& [backend, file] = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  prism::Scene scene = prism::load_scene(fs::path(PRISM_SOURCE_DIR) / file, registry);
  prism::Image expected = render(registry, "reference", scene);
  prism::Image actual = render(registry, backend, scene);
  ASSERT_EQ(actual.rgb.size(), expected.rgb.size());
  size_t id_mismatches = 0, nan_pixels = 0;
  double worst = 0;
  for (size_t i = 0; i < expected.rgb.size(); ++i) {
    if (std::isnan(actual.rgb[i])) ++nan_pixels;
    worst = std::max(worst, double(std::abs(actual.rgb[i] - expected.rgb[i])));
  }
  for (size_t p = 0; p < expected.id.size(); ++p) id_mismatches += actual.id[p] != expected.id[p];
  EXPECT_EQ(nan_pixels, 0u);
  // Both CPU backends use the same double-precision intersectors and shading:
  // only the order of float rounding may differ.
  EXPECT_LE(worst, 1e-5) << file << " on " << backend;
  EXPECT_EQ(id_mismatches, 0u) << file << " on " << backend;
}

std::string name_of(const testing::TestParamInfo<SceneAgreement::ParamType>& info) {
  std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SceneAgreement,
                         testing::Combine(testing::ValuesIn(prism::test::backends_except("reference")),
                                          testing::ValuesIn(scene_files())),
                         name_of);

}  // namespace
