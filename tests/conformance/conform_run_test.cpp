// The comparison under `prism conform`, on hand-made images with literal
// expectations: which pixels are stable, what is counted over the threshold,
// the caps, and the attribution of over-threshold pixels to objects.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>

#include "conform/conform.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace prism::conform {
namespace {

// A w x h image with every channel 0.5 and the given path signatures and ids.
Image image_of(int w, int h, std::vector<float> path = {}, std::vector<float> id = {}) {
  Image image;
  image.width = w;
  image.height = h;
  image.rgb.assign(size_t(w) * h * 3, 0.5f);
  image.path = std::move(path);
  image.id = std::move(id);
  return image;
}

// 4 x 3: the left two columns are path 1, the right two path 2. Only the
// pixels whose whole neighbourhood (inside the image) is one path are stable:
// column 0 and column 3.
TEST(ConformStable, OnlyPixelsWhoseNeighbourhoodSharesOnePath) {
  const Image reference = image_of(4, 3, {1, 1, 2, 2, 1, 1, 2, 2, 1, 1, 2, 2});
  EXPECT_EQ(stable_pixels(reference), (std::vector<uint8_t>{1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}));
}

TEST(ConformStable, ASinglePixelOfAnotherPathMakesItsNeighboursEdges) {
  std::vector<float> path(25, 7.0f);
  path[12] = 9.0f;  // the centre of a 5 x 5 image
  const std::vector<uint8_t> stable = stable_pixels(image_of(5, 5, path));
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x)
      EXPECT_EQ(stable[size_t(y) * 5 + x], (std::abs(x - 2) <= 1 && std::abs(y - 2) <= 1) ? 0 : 1) << x << "," << y;
}

TEST(ConformMeasure, CountsPixelsOverTheThresholdAndNonFiniteOnes) {
  const Image reference = image_of(4, 3, {1, 1, 2, 2, 1, 1, 2, 2, 1, 1, 2, 2});
  const std::vector<uint8_t> stable = stable_pixels(reference);
  Image image = reference;
  image.rgb[0 * 3 + 1] += 0.017f;  // (0,0) stable, over
  image.rgb[1 * 3 + 2] -= 0.015f;  // (1,0) edge, under
  image.rgb[6 * 3 + 0] = std::numeric_limits<float>::quiet_NaN();  // (2,1) edge, NaN
  const Metrics m = measure(reference, stable, image, 0.016f);
  EXPECT_EQ(m.pixels, 12);
  EXPECT_EQ(m.pixels_over, 2);
  EXPECT_EQ(m.stable_pixels, 6);
  EXPECT_EQ(m.stable_over, 1);
  EXPECT_EQ(m.edge_pixels, 6);
  EXPECT_EQ(m.edge_over, 1);
  EXPECT_EQ(m.nonfinite, 1);
}

TEST(ConformMeasure, MetricsOfOneChangedValue) {
  const Image reference = image_of(2, 2);
  Image image = reference;
  image.rgb[0] += 0.25f;  // one of 12 values off by 0.25
  const Metrics m = measure(reference, stable_pixels(reference), image, 0.016f);
  EXPECT_NEAR(m.mean_error, 0.25 / 12, 1e-9);
  EXPECT_NEAR(m.rms_error, std::sqrt(0.25 * 0.25 / 12), 1e-7);
  EXPECT_NEAR(m.max_error, 0.25, 1e-9);
  EXPECT_EQ(m.pixels_over, 1);
}

TEST(ConformVerdict, TheCaps) {
  const Caps caps;
  Metrics m;
  m.pixels = 100000;
  m.stable_pixels = 80000;
  m.edge_pixels = 20000;
  EXPECT_EQ(verdict(m, caps, false), "");
  m.stable_over = 40;  // 0.05 % of the stable pixels: at the GPU cap, over the double cap of 0
  m.pixels_over = 40;
  EXPECT_EQ(verdict(m, caps, false), "");
  EXPECT_NE(verdict(m, caps, true).find("40 stable pixels (0.050 %)"), std::string::npos) << verdict(m, caps, true);
  m.stable_over = 41;
  EXPECT_NE(verdict(m, caps, false).find("41 stable pixels"), std::string::npos);
  m.stable_over = 0;
  m.edge_over = 501;  // 0.501 % of all pixels, over the 0.5 % cap
  m.pixels_over = 501;
  EXPECT_NE(verdict(m, caps, false).find("501 pixels (0.501 %)"), std::string::npos) << verdict(m, caps, false);
  m.edge_over = m.pixels_over = 0;
  m.nonfinite = 1;
  EXPECT_NE(verdict(m, caps, false).find("1 NaN or Inf pixel"), std::string::npos);
}

// The conformance torus scene has two tori (objects 0 and 1). A changed pixel
// whose neighbourhood holds object 1 and the background counts for both.
TEST(ConformAttribution, OverPixelsAreBlamedOnTheObjectsAroundThem) {
  Registry registry;
  const Scene scene = load_scene(prism::test::source_dir() / "scenes/conformance/torus.json", registry);
  // 5 x 1: ids background, 1, 1, 0, 0.
  const Image reference = image_of(5, 1, {1, 2, 2, 3, 3}, {-1, 1, 1, 0, 0});
  Image image = reference;
  image.rgb[0 * 3] += 0.1f;  // neighbourhood: background, object 1
  image.rgb[4 * 3] += 0.1f;  // neighbourhood: object 0
  const std::vector<Attribution> blame = attribute(scene, reference, image, 0.016f);
  ASSERT_EQ(blame.size(), 3u);
  for (const Attribution& a : blame) {
    EXPECT_EQ(a.pixels, 1);
    EXPECT_DOUBLE_EQ(a.fraction, 0.5);
  }
  EXPECT_EQ(blame[0].label, "background");
  EXPECT_EQ(blame[1].label, "torus (object 0)");
  EXPECT_EQ(blame[2].label, "torus (object 1)");
}

// The stability suite's table and chart reach the report as written.
TEST(ConformStability, TheSuitesTableAndChartAreShownInTheReport) {
  const std::filesystem::path dir = prism::test::fresh_temp_dir();
  write_text_file_atomically(dir / "stability.csv", "family,backend,p99\n\"grazing, 1e-7\",embree,3e-16\n");
  write_text_file_atomically(dir / "stability.svg", "<?xml version=\"1.0\"?>\n<svg id=\"stability-chart\"></svg>\n");
  RunResult run;
  run.stability = read_stability_results(dir);
  ASSERT_EQ(run.stability->rows.size(), 2u);
  EXPECT_EQ(run.stability->rows[1], (std::vector<std::string>{"grazing, 1e-7", "embree", "3e-16"}));
  write_report(run, dir / "report");
  std::ifstream in(dir / "report" / "index.html");
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("Numerical stability"), std::string::npos);
  EXPECT_NE(page.find("<svg id=\"stability-chart\">"), std::string::npos);
  EXPECT_EQ(page.find("<?xml"), std::string::npos);
  EXPECT_NE(page.find("<td>grazing, 1e-7</td>"), std::string::npos);
}

TEST(ConformStability, AMissingFolderIsBadInput) {
  EXPECT_THROW(read_stability_results(prism::test::fresh_temp_dir()), InputError);
}

}  // namespace
}  // namespace prism::conform
