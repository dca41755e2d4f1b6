// The `prism conform` report, from a hand-made RunResult: the heat map's
// colours, results.json and results.csv read back, index.html's content, and
// (where chromium is installed) the page as a browser loads and draws it.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conform/conform.hpp"
#include "prism/image_file.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace prism::conform {
namespace {

constexpr int kWidth = 16, kHeight = 12;
constexpr float kThreshold = 0.016f;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
const std::string kOddSceneName = "odd <&> \"name\", 2";
const std::string kSkipReason = "no Vulkan device on this machine";

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

size_t count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) result.push_back(line);
  return result;
}

// A gradient, so every pixel of the reference differs from its neighbours.
Image reference_image() {
  Image image;
  image.width = kWidth;
  image.height = kHeight;
  image.rgb.assign(kWidth * kHeight * 3, 0.0f);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      float* p = &image.rgb[(y * kWidth + x) * 3];
      p[0] = float(x) / kWidth;
      p[1] = float(y) / kHeight;
      p[2] = 0.25f;
    }
  return image;
}

void offset_block(Image& image, int x0, int y0, int w, int h, float by) {
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) image.rgb[(y * image.width + x) * 3] += by;
}

// The reference with a block just over the threshold (red in the heat map),
// a block far over it (white) and one NaN pixel (magenta).
Image bad_image() {
  Image image = reference_image();
  offset_block(image, 2, 2, 4, 3, 0.02f);
  offset_block(image, 10, 6, 3, 3, 0.5f);
  image.rgb[(11 * kWidth + 15) * 3 + 1] = kNaN;
  return image;
}

BackendResult good_backend() {
  BackendResult b;
  b.backend = "good";
  b.status = "pass";
  b.device = "CPU, 16 threads";
  b.precision = "double";
  b.render_ms = 12.5;
  b.metrics = {0, 0, std::numeric_limits<double>::infinity(), 0, 192, 0, 150, 0, 42, 0, 0};
  b.sweep = {{1, 2.5, 0.05, 0.03}, {4, 9.0, 0.025, 0.015}, {16, 35.0, 0.0125, 0.0075}};
  b.image = reference_image();
  return b;
}

BackendResult bad_backend() {
  BackendResult b;
  b.backend = "bad";
  b.status = "fail";
  b.reason = "21 pixels over the threshold";
  b.device = "NVIDIA H200";
  b.precision = "float";
  b.render_ms = 3.25;
  b.compile_ms = 140.75;
  b.metrics = {0.0123, 0.0456, 26.8, 0.5, 192, 21, 150, 13, 42, 8, 1};
  b.attribution = {{3, "torus (object 3)", 19, 0.9047619}, {-1, "background", 2, 0.0952381}};
  b.sweep = {{1, 0.0, 0.0, 0.0}};  // degenerate: zero time and error on log axes
  b.image = bad_image();
  return b;
}

BackendResult skipped_backend() {
  BackendResult b;
  b.backend = "vulkan";
  b.status = "skipped";
  b.reason = kSkipReason;
  return b;
}

SceneResult scene(const std::string& name) {
  SceneResult s;
  s.name = name;
  s.file = "scenes/conformance/" + name + ".json";
  s.image = {kWidth, kHeight, 4, 5};
  s.reference_backend = "reference";
  s.reference_ms = 250.5;
  s.reference = reference_image();
  s.stable.assign(kWidth * kHeight, 1);
  s.backends = {good_backend(), bad_backend(), skipped_backend()};
  s.reference_sweep = {{1, 60.0, 0.04, 0.02}, {4, 240.0, 0.02, 0.01}, {16, 960.0, 0.01, 0.005}};
  s.sweep_reference = "out/reference-256spp.exr";
  return s;
}

RunResult synthetic_run() {
  RunResult run;
  run.scenes = {scene("torus"), scene(kOddSceneName)};
  run.wall_ms = 1234.5;
  run.started = "2024-05-01T12:34:56Z";
  return run;
}

// Images the report shows: per scene the reference, and the picture and heat
// map of the two backends that rendered (the skipped one has neither).
constexpr size_t kImagesInReport = 2 * (1 + 2 + 2);

Image one_row(std::vector<float> rgb) {
  Image image;
  image.width = int(rgb.size() / 3);
  image.height = 1;
  image.rgb = std::move(rgb);
  return image;
}

void expect_pixel(const Image& image, int x, float r, float g, float b) {
  const float* p = &image.rgb[x * 3];
  EXPECT_NEAR(p[0], r, 1e-6) << "pixel " << x;
  EXPECT_NEAR(p[1], g, 1e-6) << "pixel " << x;
  EXPECT_NEAR(p[2], b, 1e-6) << "pixel " << x;
}

// The reference is zero where the image carries the test difference, so the
// difference is exact in float.
struct HeatMapCase {
  Image reference = one_row({0.2f, 0.4f, 0.6f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  Image image = one_row({0.2f, 0.4f, 0.6f,           // no difference: black
                         0, kThreshold, 0,           // exactly the threshold: red
                         -8 * kThreshold, 0, 0,      // 8x the threshold: white
                         0.3f, kNaN, 0.3f,           // NaN: magenta
                         kInf, 0, 0,                 // Inf: magenta
                         0, 0, kThreshold * 0.6f});  // 0.6x the threshold: blue, see LiteralColours
};

TEST(ConformHeatMap, LiteralColours) {
  const HeatMapCase c;
  const Image map = heat_map(c.reference, c.image, kThreshold);
  ASSERT_EQ(map.width, 6);
  ASSERT_EQ(map.height, 1);
  ASSERT_EQ(map.rgb.size(), 18u);
  expect_pixel(map, 0, 0, 0, 0);
  expect_pixel(map, 1, 1, 0, 0);
  expect_pixel(map, 2, 1, 1, 1);
  expect_pixel(map, 3, 1, 0, 1);
  expect_pixel(map, 4, 1, 0, 1);
  // 0.6x the threshold sits log10(0.6 / 0.001) / 3 = 0.92605 of the way from
  // the floor (1/1000 of it) to the threshold: sRGB (0, 0.6, 1) x 0.92605 =
  // (0, 0.55563, 0.92605), linear (0, 0.269192, 0.839950).
  expect_pixel(map, 5, 0, 0.2691919f, 0.8399497f);
}

TEST(ConformHeatMap, PngShowsTheDesignedColours) {
  const HeatMapCase c;
  const fs::path png = prism::test::fresh_temp_dir() / "heat.png";
  write_image(heat_map(c.reference, c.image, kThreshold), png);
  const ImageFile file = read_image_file(png);
  ASSERT_EQ(file.width, 6);
  ASSERT_GE(file.channels, 3);
  const auto byte = [&](int x, int channel) { return std::lround(file.pixels[x * file.channels + channel] * 255); };
  const std::vector<std::array<long, 3>> expected = {{0, 0, 0},     {255, 0, 0},   {255, 255, 255},
                                                     {255, 0, 255}, {255, 0, 255}, {0, 142, 236}};
  for (int x = 0; x < 6; ++x)
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(byte(x, ch), expected[x][ch]) << "pixel " << x << " channel " << ch;
}

TEST(ConformHeatMap, GrowsFromRedToWhiteAboveTheThreshold) {
  const Image reference = one_row({0, 0, 0, 0, 0, 0, 0, 0, 0});
  const Image image = one_row({1.5f * kThreshold, 0, 0, 4 * kThreshold, 0, 0, 100 * kThreshold, 0, 0});
  const Image map = heat_map(reference, image, kThreshold);
  EXPECT_EQ(map.rgb[0], 1.0f);
  EXPECT_GT(map.rgb[1], 0.0f);  // towards yellow
  EXPECT_EQ(map.rgb[2], 0.0f);
  EXPECT_EQ(map.rgb[4], 1.0f);  // past yellow, towards white
  EXPECT_GT(map.rgb[5], 0.0f);
  expect_pixel(map, 2, 1, 1, 1);  // clamped at white
}

// Errors far below the threshold still show: 1/500 of it is log10(2) / 3 =
// 0.10034 of the way up from black, sRGB (0, 0.0602, 0.10034), linear
// (0, 0.0049174, 0.0100762); 1/1000 of it and less are black.
TEST(ConformHeatMap, SmallErrorsShowOnALogScale) {
  const Image reference = one_row({0, 0, 0, 0, 0, 0, 0, 0, 0});
  const Image image = one_row({kThreshold / 500, 0, 0, kThreshold / 1000, 0, 0, kThreshold / 5000, 0, 0});
  const Image map = heat_map(reference, image, kThreshold);
  expect_pixel(map, 0, 0, 0.0049174f, 0.0100762f);
  expect_pixel(map, 1, 0, 0, 0);
  expect_pixel(map, 2, 0, 0, 0);
}

TEST(ConformHeatMap, RefusesImagesOfDifferentSizes) {
  EXPECT_THROW(heat_map(reference_image(), one_row({0, 0, 0}), kThreshold), std::invalid_argument);
}

TEST(ConformResults, JsonHoldsEveryNumber) {
  const fs::path file = prism::test::fresh_temp_dir() / "results.json";
  write_results_json(synthetic_run(), file);
  const auto json = nlohmann::json::parse(read_text(file));

  EXPECT_EQ(json["started"], "2024-05-01T12:34:56Z");
  EXPECT_EQ(json["wall_ms"], 1234.5);
  EXPECT_EQ(json["passed"], false);
  EXPECT_EQ(json["caps"]["threshold"], 0.016);
  EXPECT_EQ(json["caps"]["stable_over_gpu"], 0.0005);
  EXPECT_EQ(json["caps"]["stable_over_double"], 0.0);
  EXPECT_EQ(json["caps"]["all_over"], 0.005);

  ASSERT_EQ(json["scenes"].size(), 2u);
  const auto& torus = json["scenes"][0];
  EXPECT_EQ(torus["name"], "torus");
  EXPECT_EQ(torus["file"], "scenes/conformance/torus.json");
  EXPECT_EQ(torus["settings"], nlohmann::json::parse(R"({"width":16,"height":12,"spp":4,"max_depth":5})"));
  EXPECT_EQ(torus["reference_ms"], 250.5);
  EXPECT_EQ(torus["sweep_reference"], "out/reference-256spp.exr");
  EXPECT_EQ(torus["reference_sweep"][2]["render_ms"], 960.0);
  EXPECT_EQ(json["scenes"][1]["name"], kOddSceneName);

  ASSERT_EQ(torus["backends"].size(), 3u);
  const auto& good = torus["backends"][0];
  EXPECT_TRUE(good["metrics"]["psnr"].is_null()) << "an infinite PSNR is written as null";
  EXPECT_EQ(good["precision"], "double");
  EXPECT_EQ(good["sweep"][1],
            nlohmann::json::parse(R"({"spp":4,"render_ms":9.0,"rms_error":0.025,"mean_error":0.015})"));

  const auto& bad = torus["backends"][1];
  EXPECT_EQ(bad["status"], "fail");
  EXPECT_EQ(bad["reason"], "21 pixels over the threshold");
  EXPECT_EQ(bad["device"], "NVIDIA H200");
  EXPECT_EQ(bad["render_ms"], 3.25);
  EXPECT_EQ(bad["compile_ms"], 140.75);
  EXPECT_EQ(bad["metrics"], nlohmann::json::parse(R"({"mean_error":0.0123,"rms_error":0.0456,"psnr":26.8,
      "max_error":0.5,"pixels":192,"pixels_over":21,"stable_pixels":150,"stable_over":13,"edge_pixels":42,
      "edge_over":8,"nonfinite":1})"));
  EXPECT_EQ(bad["attribution"][0], nlohmann::json::parse(R"json({"object_id":3,"label":"torus (object 3)","pixels":19,
      "fraction":0.9047619})json"));

  const auto& skipped = torus["backends"][2];
  EXPECT_EQ(skipped["status"], "skipped");
  EXPECT_EQ(skipped["reason"], kSkipReason);
}

TEST(ConformResults, CsvHasAHeaderAndARowPerSceneAndBackend) {
  const fs::path dir = prism::test::fresh_temp_dir();
  write_results_csv(synthetic_run(), dir / "results.csv");

  const std::vector<std::string> rows = lines(read_text(dir / "results.csv"));
  ASSERT_EQ(rows.size(), 1u + 2 * 3);
  EXPECT_EQ(rows[0],
            "scene,backend,status,width,height,spp,render_ms,compile_ms,mean_error,rms_error,psnr,max_error,pixels,"
            "pixels_over,stable_pixels,stable_over,edge_pixels,edge_over,nonfinite,top_attribution");
  EXPECT_EQ(rows[2],
            "torus,bad,fail,16,12,4,3.25,140.75,0.0123,0.0456,26.8,0.5,192,21,150,13,42,8,1,"
            "torus (object 3): 90 %");
  EXPECT_EQ(rows[4].rfind("\"odd <&> \"\"name\"\", 2\",good,pass,", 0), 0u) << rows[4];

  // Sweep points: the reference's three and the backends' four, per scene.
  const std::vector<std::string> sweep = lines(read_text(dir / "results_sweep.csv"));
  ASSERT_EQ(sweep.size(), 1u + 2 * 7);
  EXPECT_EQ(sweep[0], "scene,backend,spp,render_ms,rms_error,mean_error");
  EXPECT_EQ(sweep[1], "torus,reference,1,60,0.04,0.02");
}

// The report of the synthetic run, written once per test into its own folder.
class ConformReport : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = prism::test::fresh_temp_dir() / "report";
    write_report(synthetic_run(), dir_);
    html_ = read_text(dir_ / "index.html");
  }
  fs::path dir_;
  std::string html_;
};

TEST_F(ConformReport, WritesThePageAndTheResultsAndNothingElse) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"index.html", "results.csv", "results.json", "results_sweep.csv"}));
  const std::string leftover_prefix = "prism-report-" + std::to_string(::getpid()) + "-";
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    EXPECT_NE(entry.path().filename().string().rfind(leftover_prefix, 0), 0u) << entry.path();
}

TEST_F(ConformReport, PageIsSelfContained) {
  EXPECT_EQ(html_.find("http://"), std::string::npos);
  EXPECT_EQ(html_.find("https://"), std::string::npos);
  EXPECT_FALSE(std::regex_search(html_, std::regex(R"((src|href)\s*=\s*(?!["']?(data:|#)))", std::regex::icase)))
      << "every src= is a data URI and every href= an anchor in the page";
  EXPECT_EQ(count(html_, "<img "), kImagesInReport);
  EXPECT_EQ(count(html_, "src=\"data:image/png;base64,"), kImagesInReport);
  EXPECT_NE(html_.find("image-rendering: pixelated"), std::string::npos);
}

TEST_F(ConformReport, PageShowsResultsReasonsAndCharts) {
  EXPECT_NE(html_.find(kSkipReason), std::string::npos);
  EXPECT_NE(html_.find("torus (object 3): 90 %"), std::string::npos);
  EXPECT_NE(html_.find("<svg"), std::string::npos);
  EXPECT_EQ(count(html_, "<svg class=\"chart\""), 2u);
  EXPECT_NE(html_.find("odd &lt;&amp;&gt; &quot;name&quot;, 2"), std::string::npos);
  EXPECT_EQ(html_.find(kOddSceneName), std::string::npos) << "the scene name is escaped everywhere";
  EXPECT_NE(html_.find("RMS 0.0456 · 3.25 ms"), std::string::npos) << "error is shown beside time";
  EXPECT_NE(html_.find("2024-05-01T12:34:56Z"), std::string::npos);
  EXPECT_NE(html_.find(">FAIL<"), std::string::npos);
  EXPECT_NE(html_.find(">SKIPPED<"), std::string::npos);
}

TEST_F(ConformReport, ChartsHaveOnlyFiniteCoordinates) {
  for (size_t at = html_.find("<svg"); at != std::string::npos; at = html_.find("<svg", at + 1)) {
    const std::string svg = html_.substr(at, html_.find("</svg>", at) - at);
    EXPECT_EQ(svg.find("nan"), std::string::npos) << svg;
    EXPECT_EQ(svg.find("inf"), std::string::npos) << svg;
  }
}

// good: 12.5 ms against the reference's 250.5 in both scenes, 20.04x;
// bad: 3.25 ms, 77.08x, but it fails; vulkan: skipped everywhere.
TEST(ConformSummary, PerBackendOverTheRun) {
  const std::vector<BackendSummary> s = summarize(synthetic_run());
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].backend, "good");
  EXPECT_EQ(s[0].passed, 2);
  EXPECT_EQ(s[0].compared, 2);
  EXPECT_NEAR(s[0].speedup, 20.04, 1e-9);
  EXPECT_EQ(s[0].worst_max_error, 0.0);
  EXPECT_EQ(s[0].first_frame_ms, 12.5);
  EXPECT_TRUE(s[0].passes());
  EXPECT_EQ(s[1].backend, "bad");
  EXPECT_EQ(s[1].failed, 2);
  EXPECT_NEAR(s[1].speedup, 250.5 / 3.25, 1e-9);
  EXPECT_EQ(s[1].worst_max_error, 0.5);
  EXPECT_EQ(s[1].worst_rms_error, 0.0456);
  EXPECT_EQ(s[1].compile_ms, 281.5);     // 140.75 in each scene
  EXPECT_EQ(s[1].first_frame_ms, 144.0);  // 140.75 + 3.25
  EXPECT_FALSE(s[1].passes());
  EXPECT_EQ(s[2].backend, "vulkan");
  EXPECT_EQ(s[2].skipped, 2);
  EXPECT_EQ(s[2].speedup, 0.0);
  EXPECT_FALSE(s[2].passes());
  EXPECT_EQ(fastest_passing(s), "good");
  EXPECT_EQ(fastest_line(s), "fastest backend that passes here: good");
}

TEST(ConformSummary, InResultsJson) {
  const fs::path dir = prism::test::fresh_temp_dir();
  write_results_json(synthetic_run(), dir / "results.json");
  const nlohmann::json json = nlohmann::json::parse(read_text(dir / "results.json"));
  EXPECT_EQ(json["fastest_passing"], "good");
  ASSERT_EQ(json["backends"].size(), 3u);
  EXPECT_EQ(json["backends"][1]["backend"], "bad");
  EXPECT_EQ(json["backends"][1]["failed"], 2);
  EXPECT_EQ(json["backends"][1]["first_frame_ms"], 144.0);
  EXPECT_EQ(json["backends"][1]["passes"], false);
  EXPECT_EQ(json["scenes"][0]["backends"][1]["first_frame_ms"], 144.0);
}

TEST(ConformSummary, NoPassingBackend) {
  RunResult run = synthetic_run();
  for (SceneResult& scene : run.scenes) scene.backends = {bad_backend(), skipped_backend()};
  EXPECT_EQ(fastest_line(summarize(run)), "fastest backend that passes here: none");
}

TEST(ConformSummary, TheFasterOfTwoPassingBackends) {
  RunResult run = synthetic_run();
  BackendResult quick = good_backend();
  quick.backend = "quick";
  quick.render_ms = 2.5;
  for (SceneResult& scene : run.scenes) scene.backends.push_back(quick);
  EXPECT_EQ(fastest_passing(summarize(run)), "quick");
}

TEST_F(ConformReport, SummaryAtTheTop) {
  const size_t summary = html_.find("<p class=\"fastest\" id=\"fastest\">fastest backend that passes here: good</p>");
  ASSERT_NE(summary, std::string::npos);
  EXPECT_LT(summary, html_.find("<section id=\"scene-0\">"));
  EXPECT_NE(html_.find("<td>good</td>"), std::string::npos);
  EXPECT_NE(html_.find("<td>20×</td>"), std::string::npos) << "good's speed against the reference";
  EXPECT_NE(html_.find("<td>77×</td>"), std::string::npos) << "bad's speed against the reference";
  EXPECT_NE(html_.find("2 pass"), std::string::npos);
  EXPECT_NE(html_.find("2 fail"), std::string::npos);
  EXPECT_NE(html_.find("2 skipped"), std::string::npos);
}

TEST_F(ConformReport, HeatMapScaleIsPrinted) {
  EXPECT_NE(html_.find("log scale"), std::string::npos);
  EXPECT_NE(html_.find(">≤ 1.6e-05</span>"), std::string::npos);
  EXPECT_NE(html_.find(">0.00016</span>"), std::string::npos);
  EXPECT_NE(html_.find(">0.0016</span>"), std::string::npos);
  EXPECT_NE(html_.find(">0.016<br>threshold</span>"), std::string::npos);
  EXPECT_NE(html_.find(">≥ 0.128</span>"), std::string::npos);
}

// Both scenes of the synthetic run have a failing backend: open. A scene
// where everything passed starts collapsed.
TEST(ConformReportSections, PassingScenesAreCollapsedFailingOnesOpen) {
  RunResult run = synthetic_run();
  run.scenes[1].backends = {good_backend(), skipped_backend()};
  const fs::path dir = prism::test::fresh_temp_dir() / "report";
  write_report(run, dir);
  const std::string html = read_text(dir / "index.html");
  EXPECT_NE(html.find("<section id=\"scene-0\"><details open><summary>"), std::string::npos);
  EXPECT_NE(html.find("<section id=\"scene-1\"><details><summary>"), std::string::npos);
}

TEST(ConformSize, ParsesWidthByHeight) {
  EXPECT_EQ(parse_size("320x180"), (std::pair<int, int>{320, 180}));
  EXPECT_EQ(parse_size("1x16384"), (std::pair<int, int>{1, 16384}));
  for (const char* bad : {"320", "x180", "320x", "0x180", "320x0", "16385x1", "-3x4", "3x4x5", "99999999999x1", "a1x2"}) {
    try {
      parse_size(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("--size: expected WIDTHxHEIGHT with each side in [1, 16384] "
                                                   "(e.g. 320x180), got '") + bad + "'");
    }
  }
}

TEST(ConformReportDegenerate, SceneWithoutAnyImage) {
  RunResult run;
  SceneResult empty;
  empty.name = "nothing rendered";
  empty.image = {kWidth, kHeight, 1, 1};
  empty.backends = {skipped_backend()};
  empty.backends[0].sweep = {{1, -5.0, -1.0, 0.0}};
  run.scenes = {empty, SceneResult{}};
  const fs::path dir = prism::test::fresh_temp_dir() / "nested" / "report";
  write_report(run, dir);
  const std::string html = read_text(dir / "index.html");
  EXPECT_NE(html.find("no reference image"), std::string::npos);
  EXPECT_EQ(count(html, "<img "), 0u);
  EXPECT_EQ(count(html, "<svg class=\"chart\""), 1u);
}

// ---------------------------------------------------------------------------
// In a browser

std::string find_chromium() {
  for (const char* name : {"chromium", "chromium-browser"})
    if (std::system(("command -v " + std::string(name) + " >/dev/null 2>&1").c_str()) == 0) return name;
  return "";
}

std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

class ConformReportInBrowser : public ConformReport {
 protected:
  void SetUp() override {
    chromium_ = find_chromium();
    if (chromium_.empty()) {
      const char* required = std::getenv("PRISM_REQUIRE_CHROMIUM");
      if (required && std::string(required) == "1") FAIL() << "PRISM_REQUIRE_CHROMIUM=1 but chromium is not on PATH";
      GTEST_SKIP() << "chromium is not installed (apt-get install chromium); the browser checks did not run";
    }
    ConformReport::SetUp();
  }

  // Runs headless chromium on the report with `arguments`; returns its stdout.
  // Its own HOME and profile keep it off the user's and let tests run in parallel.
  std::string run_chromium(const std::string& arguments) {
    const fs::path work = dir_.parent_path();
    const fs::path out = work / "chromium.out", log = work / "chromium.log";
    const std::string command = "HOME=" + shell_quoted(work.string()) + " timeout 60 " + chromium_ +
                                " --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir=" +
                                shell_quoted((work / "profile").string()) + " " + arguments + " " +
                                shell_quoted("file://" + (dir_ / "index.html").string()) + " >" +
                                shell_quoted(out.string()) + " 2>" + shell_quoted(log.string());
    const int status = std::system(command.c_str());
    EXPECT_EQ(status, 0) << command << "\n" << read_text(log);
    return read_text(out);
  }

  std::string chromium_;
};

std::string body_attribute(const std::string& dom, const std::string& name) {
  std::smatch match;
  const std::regex pattern("<body[^>]*\\s" + name + "=\"([^\"]*)\"");
  return std::regex_search(dom, match, pattern) ? match[1].str() : "(missing)";
}

TEST_F(ConformReportInBrowser, LoadsEveryImageAndChart) {
  const std::string dom = run_chromium("--dump-dom");
  EXPECT_EQ(body_attribute(dom, "data-images-loaded"), std::to_string(count(html_, "<img ")));
  const std::string charts = body_attribute(dom, "data-charts");
  ASSERT_TRUE(std::regex_match(charts, std::regex("[0-9]+"))) << charts;
  EXPECT_GE(std::stoi(charts), 1);
}

TEST_F(ConformReportInBrowser, ShowsTheFastestPassingBackend) {
  const std::string dom = run_chromium("--dump-dom");
  EXPECT_EQ(body_attribute(dom, "data-fastest"), "fastest backend that passes here: good");
}

TEST_F(ConformReportInBrowser, ScreenshotIsNotBlank) {
  const fs::path shot = dir_.parent_path() / "shot.png";
  run_chromium("--screenshot=" + shell_quoted(shot.string()) + " --window-size=1280,1600");
  const ImageFile image = read_image_file(shot);
  ASSERT_GE(image.channels, 3);
  const float* background = &image.pixels[0];  // the page's top-left corner
  long differing = 0, saturated_red = 0;
  for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
    const float* px = &image.pixels[p * image.channels];
    const float difference =
        std::max({std::abs(px[0] - background[0]), std::abs(px[1] - background[1]), std::abs(px[2] - background[2])});
    differing += difference > 0.1f;
    saturated_red += px[0] > 0.7f && px[1] < 0.3f && px[2] < 0.3f;
  }
  const double pixels = double(image.width) * image.height;
  EXPECT_GE(differing / pixels, 0.05) << "the page looks blank; see " << shot;
  EXPECT_GE(saturated_red, 200) << "no red from a heat map or a FAIL cell; see " << shot;
}

}  // namespace
}  // namespace prism::conform
