// Every scene under scenes/ renders to the same picture, up to rounding, on
// every backend as on the reference backend (double precision, brute force).
// Scenes render at their own size and spp, with the reference at the same
// spp, so the comparison measures backend differences, not aliasing.
//
// Every backend: no NaN or Inf pixel, and at most 0.5 % of pixels differ by
// more than 0.016 in any channel (OpenImageIO's ImageBufAlgo::compare).
// Backends that promise double precision end to end (stats info
// "precision": "double": the CPU backends) must render the reference's image
// bit for bit, with equal id and path AOVs.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
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

struct Rendered {
  prism::Image image;
  prism::BackendStats stats;
};

Rendered render(prism::Registry& registry, const std::string& backend, const prism::Scene& scene) {
  prism::RenderSettings settings;
  settings.image = scene.image;
  settings.aov_id = true;
  settings.aov_path = true;
  auto instance = registry.backend(backend)->create();
  instance->prepare(scene);
  prism::Image image = instance->render(settings);
  return {std::move(image), instance->stats()};
}

OIIO::ImageBuf to_imagebuf(const prism::Image& image) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT));
  buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, image.rgb.data());
  return buf;
}

class SceneAgreement : public testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(SceneAgreement, MatchesReferenceUpToRounding) {
  const auto& [backend, file] = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  prism::Scene scene = prism::load_scene(fs::path(PRISM_SOURCE_DIR) / file, registry);
  const prism::Image expected = render(registry, "reference", scene).image;
  const Rendered rendered = render(registry, backend, scene);
  const prism::Image& actual = rendered.image;
  ASSERT_EQ(actual.rgb.size(), expected.rgb.size());
  size_t id_mismatches = 0, nonfinite = 0;
  double worst = 0;
  for (size_t i = 0; i < expected.rgb.size(); ++i) {
    if (!std::isfinite(actual.rgb[i])) ++nonfinite;
    worst = std::max(worst, double(std::abs(actual.rgb[i] - expected.rgb[i])));
  }
  for (size_t p = 0; p < expected.id.size(); ++p) id_mismatches += actual.id[p] != expected.id[p];
  EXPECT_EQ(nonfinite, 0u);
  const OIIO::ImageBuf a = to_imagebuf(actual), b = to_imagebuf(expected);
  // (OIIO 2.4 sets `cmp.error` whenever a pixel fails the threshold: the
  // cap is the count below, as the conformance suite's.)
  const auto cmp = OIIO::ImageBufAlgo::compare(a, b, 0.016f, 0.016f, 0.0f, 0.0f);
  const double pixels = double(actual.width) * actual.height;
  RecordProperty("max_error", std::to_string(cmp.maxerror));
  RecordProperty("pixels_over_0.016", std::to_string(cmp.nfail));
  RecordProperty("id_mismatches", std::to_string(id_mismatches));
  std::printf("%s on %s: max error %.3g, RMS %.3g, PSNR %.1f dB, %llu pixels > 0.016, %zu id mismatches of %.0f\n",
              file.c_str(), backend.c_str(), cmp.maxerror, cmp.rms_error, cmp.PSNR,
              static_cast<unsigned long long>(cmp.nfail), id_mismatches, pixels);
  EXPECT_LE(double(cmp.nfail), 0.005 * pixels) << file << " on " << backend;
  auto precision = rendered.stats.info.find("precision");
  if (precision != rendered.stats.info.end() && precision->second == "double") {
    // Same double-precision intersectors and shading, and the same closest
    // hit (the lower id on ties) whatever structure finds it: the same
    // floats, bit for bit.
    EXPECT_EQ(worst, 0.0) << file << " on " << backend;
    EXPECT_EQ(id_mismatches, 0u) << file << " on " << backend;
    EXPECT_TRUE(actual.path == expected.path) << "path AOV differs: " << file << " on " << backend;
  }
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
