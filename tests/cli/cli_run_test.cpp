// The happy paths, on every backend found: `prism trace` against answers
// worked out by hand, `prism render` to PNG and EXR, and --stats.

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "cli_harness.hpp"
#include "prism/image_file.hpp"
#include "test_support.hpp"

namespace prism::cli_test {
namespace {

using nlohmann::json;

// The backends to run: those built, plus those PRISM_REQUIRE_BACKENDS names
// (a required one that is missing fails rather than being skipped).
std::vector<std::string> backends_to_test() {
  std::vector<std::string> names = backends_built();
  for (const auto& name : prism::test::required_backends())
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

// A backend that cannot run on this machine (and is not required) is
// skipped; anything else that goes wrong is a failure.
bool cannot_run_here(const RunResult& r, const std::string& backend) {
  return !prism::test::backend_required(backend) && r.exited && r.status == 1 &&
         contains_any(r.err, "cannot run here|failed to start");
}

// The trace scene: sphere of radius 1 at the origin (id 0), the plane y = -2
// with normal +y (id 1), a point light at (0, 5, 0) with a visible sphere of
// radius 0.5 (id -2).
std::string trace_scene() {
  SceneText s;
  s.lights = R"([{"type": "point", "position": [0, 5, 0], "radius": 0.5}])";
  return s.text();
}

struct Expected {
  double t;
  int id;
  double nx, ny, nz;
};
constexpr double kInf = INFINITY;

// Line 1 is the header; ray i is on line i + 2.
const char* const kRays =
    "ox,oy,oz,dx,dy,dz,tmin\n"
    "0,0,-5,0,0,1\n"          // the sphere from outside
    "0,0,0,1,0,0\n"           // the sphere from inside: the outward normal
    "0,0,-5,0,0,-1\n"         // a miss
    "-5,0,0,3,0,0\n"          // direction of length 3: t is still a distance
    "0,0,-5,0,0,1,4.5\n"      // tmin skips the near side of the sphere
    "0,2,0,0,1,0\n"           // the light's sphere from below
    "3,0,0,0,-1,0\n"          // the plane from above
    "3,-5,0,0,2,0\n"          // the plane from below: normal as given, not facing
    "0,0,-5,0.1,0.1,1\n"      // a t that needs 17 digits
    "0,0,-5,0,0,1,10\n"       // tmin beyond every hit: a miss
    "0,7,0,0,-1,0\n"          // the light's sphere from above
    "0,0,-5,0,0,2,4.5\n";     // tmin is a distance too, whatever the direction's length
// t = 5/sqrt(1.02) - sqrt(25/1.02 - 24); the point (0.1, 0.1, 1)/sqrt(1.02)*t + (0, 0, -5) is the normal.
constexpr double kTOblique = 4.2367321675879549;
const std::vector<Expected> kExpected = {
    {4, 0, 0, 0, -1},
    {1, 0, 1, 0, 0},
    {kInf, -1, 0, 0, 0},
    {4, 0, -1, 0, 0},
    {6, 0, 0, 0, 1},
    {2.5, -2, 0, -1, 0},
    {2, 1, 0, 1, 0},
    {3, 1, 0, 1, 0},
    {kTOblique, 0, 0.41949899459874531, 0.41949899459874531, -0.80501005401254692},
    {kInf, -1, 0, 0, 0},
    {1.5, -2, 0, 1, 0},
    {6, 0, 0, 0, 1},
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

double number(const std::string& text) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  EXPECT_TRUE(end != text.c_str() && *end == '\0') << "'" << text << "' is not a number";
  return v;
}

void check_trace_output(const std::string& out, double tolerance) {
  const auto lines = lines_of(out);
  ASSERT_EQ(lines.size(), kExpected.size()) << out;
  for (size_t i = 0; i < lines.size(); ++i) {
    SCOPED_TRACE("ray on line " + std::to_string(i + 2) + ": " + lines[i]);
    const Expected& e = kExpected[i];
    if (e.id == -1) {
      EXPECT_EQ(lines[i], "inf,-1,0,0,0");
      continue;
    }
    const auto f = fields_of(lines[i]);
    ASSERT_EQ(f.size(), 5u);
    EXPECT_NEAR(number(f[0]), e.t, tolerance * e.t);
    EXPECT_EQ(f[1], std::to_string(e.id));
    EXPECT_NEAR(number(f[2]), e.nx, tolerance);
    EXPECT_NEAR(number(f[3]), e.ny, tolerance);
    EXPECT_NEAR(number(f[4]), e.nz, tolerance);
  }
}

// --stats: the backend, exactly the primitive plugins the scene uses, the
// kernel features, the rays and the time of every phase.
void check_stats(const fs::path& file, const std::string& backend, std::optional<uint64_t> rays) {
  ASSERT_TRUE(fs::exists(file));
  json stats;
  ASSERT_NO_THROW(stats = json::parse(read_file(file))) << read_file(file);
  SCOPED_TRACE(stats.dump(2));
  EXPECT_EQ(stats.value("backend", ""), backend);
  ASSERT_TRUE(stats.contains("plugins_loaded") && stats["plugins_loaded"].is_array());
  std::multiset<std::string> loaded;
  for (const auto& p : stats["plugins_loaded"]) loaded.insert(p.is_string() ? p.get<std::string>() : p.dump());
  EXPECT_EQ(loaded, (std::multiset<std::string>{"plane", "sphere"}));
  ASSERT_TRUE(stats.contains("kernel_features"));
  EXPECT_TRUE(stats["kernel_features"].is_array());
  ASSERT_TRUE(stats.contains("rays") && stats["rays"].is_number_integer());
  if (rays)
    EXPECT_EQ(stats["rays"].get<uint64_t>(), *rays);
  else
    EXPECT_GT(stats["rays"].get<uint64_t>(), 0u);
  ASSERT_TRUE(stats.contains("ms") && stats["ms"].is_object());
  for (const char* phase : {"load", "build", "compile", "render", "total"}) {
    ASSERT_TRUE(stats["ms"].contains(phase) && stats["ms"][phase].is_number()) << phase;
    EXPECT_GE(stats["ms"][phase].get<double>(), 0.0) << phase;
  }
  const double total = stats["ms"]["total"].get<double>();
  EXPECT_GE(total, stats["ms"]["load"].get<double>());
  EXPECT_GE(total, stats["ms"]["render"].get<double>());
}

class Trace : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    scene_ = write("scene.json", trace_scene()).string();
    rays_ = write("rays.csv", kRays).string();
  }
  RunResult trace(const std::string& backend, const std::string& rays, const std::string& out,
                  std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"trace", scene_, "-b", backend, "--rays", rays, "-o", path(out).string()};
    args.insert(args.end(), more.begin(), more.end());
    return run(args);
  }
  std::string scene_, rays_;
};

TEST_F(Trace, KnownAnswersOnEveryBackend) {
  const auto backends = backends_to_test();
  ASSERT_FALSE(backends.empty()) << "no backend in " << default_plugin_folder();
  for (const auto& backend : backends) {
    SCOPED_TRACE("backend " + backend);
    const std::string out = backend + ".csv", stats = backend + ".json";
    RunResult r = trace(backend, rays_, out, {"--stats", path(stats).string()});
    if (cannot_run_here(r, backend)) {
      std::printf("skipping backend %s: %s", backend.c_str(), r.err.c_str());
      continue;
    }
    ASSERT_TRUE(ExitedWith(r, 0));
    check_trace_output(read_file(path(out)), 1e-8);  // 9 significant digits
    check_stats(path(stats), backend, kExpected.size());
    // %.9g by default: 9 significant digits.
    EXPECT_EQ(fields_of(lines_of(read_file(path(out)))[8])[0], "4.23673217");
  }
}

// --digits 17 prints enough digits to read the double back: the t of ray 9
// read back is the exact answer to within a few ulps, where the default 9
// digits are 2.4e-9 away from it.
TEST_F(Trace, Digits17RoundTrips) {
  for (const auto& backend : backends_to_test()) {
    SCOPED_TRACE("backend " + backend);
    RunResult r17 = trace(backend, rays_, backend + "17.csv", {"--digits", "17"});
    if (cannot_run_here(r17, backend)) continue;
    ASSERT_TRUE(ExitedWith(r17, 0));
    RunResult r9 = trace(backend, rays_, backend + "9.csv");
    ASSERT_TRUE(ExitedWith(r9, 0));
    const std::string out17 = read_file(path(backend + "17.csv")), out9 = read_file(path(backend + "9.csv"));
    check_trace_output(out17, 1e-13);
    const auto f17 = fields_of(lines_of(out17).at(8)), f9 = fields_of(lines_of(out9).at(8));
    ASSERT_EQ(f17.size(), 5u);
    ASSERT_EQ(f9.size(), 5u);
    const double t17 = number(f17[0]), t9 = number(f9[0]);
    EXPECT_NEAR(t17, kTOblique, 1e-14) << f17[0];
    EXPECT_GT(std::abs(t9 - kTOblique), 1e-9) << f9[0];
    // The 17-digit text is what %.17g gives for the double it reads back as,
    // and the 9-digit text is that double rounded to 9 digits.
    char again[64];
    std::snprintf(again, sizeof again, "%.17g", t17);
    EXPECT_EQ(f17[0], again);
    std::snprintf(again, sizeof again, "%.9g", t17);
    EXPECT_EQ(f9[0], again);
    for (int c = 2; c < 5; ++c) {
      std::snprintf(again, sizeof again, "%.9g", number(f17[size_t(c)]));
      EXPECT_EQ(f9[size_t(c)], again) << "normal component " << c - 2;
    }
  }
}

// Ids: equal t goes to the lower object id, and to an object over a light's
// sphere; light k's sphere is -2-k; a light without radius is invisible.
TEST_F(Trace, IdsOfTiesAndLightSpheres) {
  SceneText s;
  s.objects = R"([{"type": "sphere", "radius": 1}, {"type": "sphere", "radius": 1}])";
  s.lights = R"([{"type": "point", "position": [0, 5, 0]},
                 {"type": "point", "position": [0, 0, 0], "radius": 1},
                 {"type": "point", "position": [5, 0, 0], "radius": 0.5}])";
  const fs::path scene = write("ids.json", s.text());
  const fs::path rays = write("ids.csv",
                              "0,0,-5,0,0,1\n"     // objects 0 and 1 and light 1's sphere, all at t = 4
                              "5,5,0,0,-1,0\n"     // light 2's sphere
                              "0,10,0,0,-1,0\n");  // through light 0 (no sphere) onto the spheres
  for (const auto& backend : backends_to_test()) {
    SCOPED_TRACE("backend " + backend);
    RunResult r = run({"trace", scene.string(), "-b", backend, "--rays", rays.string(), "-o",
                       path(backend + ".csv").string()});
    if (cannot_run_here(r, backend)) continue;
    ASSERT_TRUE(ExitedWith(r, 0));
    const auto lines = lines_of(read_file(path(backend + ".csv")));
    ASSERT_EQ(lines.size(), 3u);
    const std::vector<Expected> expected = {{4, 0, 0, 0, -1}, {4.5, -4, 0, 1, 0}, {9, 0, 0, 1, 0}};
    for (size_t i = 0; i < 3; ++i) {
      SCOPED_TRACE(lines[i]);
      const auto f = fields_of(lines[i]);
      ASSERT_EQ(f.size(), 5u);
      EXPECT_NEAR(number(f[0]), expected[i].t, 1e-8);
      EXPECT_EQ(f[1], std::to_string(expected[i].id));
      EXPECT_NEAR(number(f[2]), expected[i].nx, 1e-8);
      EXPECT_NEAR(number(f[3]), expected[i].ny, 1e-8);
      EXPECT_NEAR(number(f[4]), expected[i].nz, 1e-8);
    }
  }
}

TEST_F(Trace, DigitsSetsSignificantDigits) {
  RunResult r = trace("reference", rays_, "out.csv", {"--digits", "3"});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(fields_of(lines_of(read_file(path("out.csv")))[8])[0], "4.24");
}

TEST_F(Trace, HeaderIsOptionalAndCrlfIsAccepted) {
  const fs::path rays = write("plain.csv", "0,0,-5,0,0,1\r\n0,0,-5,0,0,-1\r\n");
  RunResult r = trace("reference", rays.string(), "out.csv");
  ASSERT_TRUE(ExitedWith(r, 0));
  const auto lines = lines_of(read_file(path("out.csv")));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(fields_of(lines[0])[0], "4");
  EXPECT_EQ(lines[1], "inf,-1,0,0,0");
}

TEST_F(Trace, EmptyRayFileGivesEmptyOutput) {
  const fs::path rays = write("empty.csv", "ox,oy,oz,dx,dy,dz\n");
  RunResult r = trace("reference", rays.string(), "out.csv");
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(read_file(path("out.csv")), "");
}

// --precision float on the reference backend runs each plugin's float entry.
// A unit sphere seen from z = -100000000.5: float rounds that origin to -1e8
// (a multiple of 8, the float spacing there), and t = 1e8 - 1 = 99999999 to
// 1e8; double keeps the half. From z = -5 both give 4 exactly.
TEST_F(CliTest, PrecisionFloatOnReferenceIntersectsInFloat) {
  SceneText s;
  s.objects = R"([{"type": "sphere", "radius": 1}])";
  s.lights = "[]";
  const fs::path scene = write("sphere.json", s.text());
  const fs::path rays = write("rays.csv", "0,0,-5,0,0,1\n0,0,-100000000.5,0,0,1\n");
  for (const std::string precision : {"float", "double"}) {
    SCOPED_TRACE(precision);
    const fs::path out = path(precision + ".csv"), stats = path(precision + ".json");
    RunResult r = run({"trace", scene.string(), "-b", "reference", "--rays", rays.string(), "-o", out.string(),
                       "--digits", "17", "--precision", precision, "--stats", stats.string()});
    ASSERT_TRUE(ExitedWith(r, 0));
    const auto lines = lines_of(read_file(out));
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(fields_of(lines[0])[0], "4");
    EXPECT_EQ(fields_of(lines[1])[0], precision == "float" ? "100000000" : "99999999.5");
    EXPECT_EQ(nlohmann::json::parse(read_file(stats))["info"]["precision"], precision);
  }
}

TEST_F(CliTest, PrecisionFloatOnADoubleOnlyBackendExitsTwo) {
  const auto built = backends_built();
  if (std::find(built.begin(), built.end(), "embree") == built.end()) GTEST_SKIP() << "embree is not built";
  const fs::path scene = write("scene.json", SceneText{}.text());
  const fs::path rays = write("rays.csv", "0,0,-5,0,0,1\n");
  RunResult r = run({"trace", scene.string(), "-b", "embree", "--rays", rays.string(), "-o", path("out.csv").string(),
                     "--precision", "float"});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"--precision float", "embree", "computes in double only"}));
  EXPECT_FALSE(fs::exists(path("out.csv")));
}

// A value that is not auto, float or double: exit 2 naming the flag, on
// every command that takes it.
TEST_F(CliTest, PrecisionBogusExitsTwoOnEveryCommand) {
  const fs::path scene = write("scene.json", SceneText{}.text());
  const fs::path rays = write("rays.csv", "0,0,-5,0,0,1\n");
  const std::vector<std::vector<std::string>> commands = {
      {"trace", scene.string(), "--rays", rays.string(), "-o", path("out.csv").string()},
      {"render", scene.string(), "-o", path("out.png").string()},
      {"bench", scene.string(), "--frames", "1", "--warmup", "1"},
      {"conform", scene.string(), "-b", "reference"},
      {"list", scene.string()}};
  for (std::vector<std::string> args : commands) {
    SCOPED_TRACE(args[0]);
    args.insert(args.end(), {"--precision", "bogus"});
    RunResult r = run(args);
    EXPECT_TRUE(ExitedWith(r, 2));
    EXPECT_TRUE(StderrHas(r, {"--precision", "bogus"}));
  }
}

// `prism list SCENE` says which precision the GPU kernels give each object
// and why: double for the far camera's bounded objects (the plane stays
// float), float for every object of the showcase.
TEST_F(CliTest, ListWithASceneShowsEachObjectsGpuPrecision) {
  RunResult far = run({"list", (prism::test::source_dir() / "scenes/conformance/far_camera.json").string()});
  ASSERT_TRUE(ExitedWith(far, 0));
  EXPECT_NE(far.out.find("--precision auto: double world\n"), std::string::npos) << far;
  EXPECT_NE(far.out.find("  object 0 (plane): float\n"), std::string::npos) << far;
  EXPECT_NE(far.out.find("  object 1 (sphere): double: hit-point error ~"), std::string::npos) << far;
  EXPECT_NE(far.out.find("  object 3 (torus): double: "), std::string::npos) << far;
  RunResult showcase = run({"list", (prism::test::source_dir() / "scenes/showcase.json").string()});
  ASSERT_TRUE(ExitedWith(showcase, 0));
  EXPECT_NE(showcase.out.find("--precision auto: float world\n"), std::string::npos) << showcase;
  EXPECT_EQ(showcase.out.find(": double"), std::string::npos) << showcase;
  RunResult forced = run({"list", (prism::test::source_dir() / "scenes/conformance/far_camera.json").string(),
                          "--precision", "float"});
  EXPECT_NE(forced.out.find("--precision float: float world\n"), std::string::npos) << forced;
}

// A bad line: exit 2, the message names the file and the line number, and
// no output is written.
class BadRays : public Trace, public ::testing::WithParamInterface<std::pair<std::string, std::string>> {};

TEST_P(BadRays, RejectedWithLineNumber) {
  const auto& [name, text] = GetParam();
  const fs::path rays = write("bad.csv", text);
  const auto before = list_folder(dir());
  RunResult r = trace("reference", rays.string(), "out.csv", {"--stats", path("stats.json").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"bad.csv:3|bad.csv, line 3|bad.csv: line 3"}));
  EXPECT_EQ(list_folder(dir()), before) << r;
}

INSTANTIATE_TEST_SUITE_P(
    Csv, BadRays,
    ::testing::Values(std::make_pair("five_fields", "ox,oy,oz,dx,dy,dz\n0,0,-5,0,0,1\n0,0,-5,0,0\n0,0,-5,0,0,1\n"),
                      std::make_pair("eight_fields", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-5,0,0,1,0,0\n"),
                      std::make_pair("not_a_number", "ox,oy,oz,dx,dy,dz\n0,0,-5,0,0,1\n0,0,-5,0,zero,1\n"),
                      std::make_pair("empty_field", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,,0,0,1\n"),
                      std::make_pair("trailing_comma", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-5,0,0,1,\n"),
                      std::make_pair("zero_direction", "ox,oy,oz,dx,dy,dz,tmin\n0,0,-5,0,0,1\n1,2,3,0,0,0\n"),
                      std::make_pair("nan", "0,0,-5,0,0,1\n0,0,-5,0,0,1\nnan,0,-5,0,0,1\n"),
                      std::make_pair("infinite_origin", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-inf,0,0,1\n"),
                      std::make_pair("overflow", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-5,1e999,0,1\n"),
                      std::make_pair("header_not_first", "0,0,-5,0,0,1\n0,0,-5,0,0,1\nox,oy,oz,dx,dy,dz\n")),
    [](const auto& info) { return info.param.first; });

// ------------------------------------------------------------------ render

// The render scene is SceneText's default: camera at (0, 0, -5) looking at
// the sphere, light at (0, 5, -5). With an odd size the centre pixel's ray
// is exactly +z: it hits the sphere at (0, 0, -1), normal (0, 0, -1), lit at
// cos = 4/sqrt(41), so its value is 0.8 * 4/sqrt(41) = 0.49975604 linear,
// round(255 * srgb(0.49975604)) = 187 in the PNG.
constexpr int kW = 33, kH = 25;
constexpr double kCentreLinear = 0.49975603804353946;

class Render : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    scene_ = write("scene.json", SceneText{}.text()).string();
  }
  std::string scene_;
};

// Any image file, read through the core's image module (OpenImageIO).
std::optional<prism::ImageFile> read_image(const fs::path& file) {
  try {
    return prism::read_image_file(file);
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
    return std::nullopt;
  }
}

float pixel_at(const prism::ImageFile& image, int x, int y, int c) {
  return image.pixels[(size_t(y) * image.width + x) * image.channels + c];
}

TEST_F(Render, PngOnEveryBackend) {
  const auto backends = backends_to_test();
  ASSERT_FALSE(backends.empty());
  std::vector<std::string> outputs = {"scene.json"};
  for (const auto& backend : backends) {
    SCOPED_TRACE("backend " + backend);
    const std::string png = backend + ".png", stats = backend + ".json";
    RunResult r = run({"render", scene_, "-b", backend, "-o", path(png).string(), "--width", std::to_string(kW),
                       "--height", std::to_string(kH), "--stats", path(stats).string()});
    if (cannot_run_here(r, backend)) {
      std::printf("skipping backend %s: %s", backend.c_str(), r.err.c_str());
      continue;
    }
    ASSERT_TRUE(ExitedWith(r, 0));
    outputs.insert(outputs.end(), {png, stats});
    auto image = read_image(path(png));
    ASSERT_TRUE(image);
    EXPECT_EQ(image->width, kW);
    EXPECT_EQ(image->height, kH);
    EXPECT_EQ(image->channels, 3);
    EXPECT_EQ(image->format, prism::PixelFormat::UInt8);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(std::lround(pixel_at(*image, kW / 2, kH / 2, c) * 255), 187) << "centre, channel " << c;
      EXPECT_EQ(pixel_at(*image, 0, 0, c), 0.0f) << "top-left (background), channel " << c;
    }
    check_stats(path(stats), backend, std::nullopt);
  }
  // Only the outputs are left in the folder: no temporary files.
  std::sort(outputs.begin(), outputs.end());
  EXPECT_EQ(list_folder(dir()), outputs);
}

TEST_F(Render, SizeComesFromTheSceneWithoutFlags) {
  RunResult r = run({"render", scene_, "-b", "reference", "-o", path("out.png").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  auto image = read_image(path("out.png"));
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 8);
  EXPECT_EQ(image->height, 6);
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"out.png", "scene.json"}));
}

TEST_F(Render, ExrWithAovs) {
  std::vector<std::string> outputs = {"scene.json"};
  for (const auto& backend : backends_to_test()) {
    SCOPED_TRACE("backend " + backend);
    const std::string exr = backend + ".exr";
    RunResult r = run({"render", scene_, "-b", backend, "-o", path(exr).string(), "--width", std::to_string(kW),
                       "--height", std::to_string(kH), "--aov", "id,path"});
    if (cannot_run_here(r, backend)) continue;
    ASSERT_TRUE(ExitedWith(r, 0));
    auto image = read_image(path(exr));
    ASSERT_TRUE(image);
    EXPECT_EQ(image->width, kW);
    EXPECT_EQ(image->height, kH);
    EXPECT_EQ(image->channel_names, (std::vector<std::string>{"R", "G", "B", "id", "path"}));
    ASSERT_EQ(image->channels, 5);
    EXPECT_EQ(image->format, prism::PixelFormat::Float);
    // Linear values, not sRGB.
    EXPECT_NEAR(pixel_at(*image, kW / 2, kH / 2, 0), kCentreLinear, 1e-6);
    // id: the sphere in the centre, a miss in the top corners, the plane at the bottom.
    EXPECT_EQ(pixel_at(*image, kW / 2, kH / 2, 3), 0.0f);
    EXPECT_EQ(pixel_at(*image, 0, 0, 3), -1.0f);
    EXPECT_EQ(pixel_at(*image, kW - 1, 0, 3), -1.0f);
    EXPECT_EQ(pixel_at(*image, kW / 2, kH - 1, 3), 1.0f);
    // path: a hash stored as a float holding an integer; a miss differs from a hit.
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float p = pixel_at(*image, x, y, 4);
        ASSERT_TRUE(std::isfinite(p) && p == std::floor(p)) << "path at " << x << "," << y << " is " << p;
      }
    EXPECT_NE(pixel_at(*image, 0, 0, 4), pixel_at(*image, kW / 2, kH / 2, 4));
    outputs.push_back(exr);
  }
  std::sort(outputs.begin(), outputs.end());
  EXPECT_EQ(list_folder(dir()), outputs);
}

// --aov depth normal albedo (space-separated here, comma-separated above):
// the camera at (0,0,-5) looks at the unit sphere, so the centre pixel
// (16, 12: its ray is exactly (0,0,1)) meets it at (0,0,-1): Z = 4, N =
// (0,0,-1), albedo the default material's 0.8; a top corner misses: Z = inf,
// N and albedo 0.
TEST_F(Render, ExrWithFirstHitAovs) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<std::string> outputs = {"scene.json"};
  for (const auto& backend : backends_to_test()) {
    SCOPED_TRACE("backend " + backend);
    const std::string exr = backend + ".exr";
    RunResult r = run({"render", scene_, "-b", backend, "-o", path(exr).string(), "--width", std::to_string(kW),
                       "--height", std::to_string(kH), "--aov", "depth", "normal", "albedo"});
    if (cannot_run_here(r, backend)) continue;
    ASSERT_TRUE(ExitedWith(r, 0));
    auto image = read_image(path(exr));
    ASSERT_TRUE(image);
    // A reader may list the channels in its own order: look them up by name.
    const std::vector<std::string> names = {"Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B"};
    std::vector<std::string> sorted = image->channel_names;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted, (std::vector<std::string>{"B", "G", "N.X", "N.Y", "N.Z", "R", "Z", "albedo.B", "albedo.G",
                                                "albedo.R"}));
    const std::vector<float> centre = {4, 0, 0, -1, 0.8f, 0.8f, 0.8f}, miss = {kInf, 0, 0, 0, 0, 0, 0};
    for (size_t k = 0; k < names.size(); ++k) {
      const int c = int(std::find(image->channel_names.begin(), image->channel_names.end(), names[k]) -
                        image->channel_names.begin());
      EXPECT_NEAR(pixel_at(*image, kW / 2, kH / 2, c), centre[k], 1e-5) << names[k];
      EXPECT_EQ(pixel_at(*image, 0, 0, c), miss[k]) << names[k];
    }
    outputs.push_back(exr);
  }
  std::sort(outputs.begin(), outputs.end());
  EXPECT_EQ(list_folder(dir()), outputs);
}

TEST_F(Render, ExrWithoutAovsHasRgbOnly) {
  RunResult r = run({"render", scene_, "-b", "reference", "-o", path("out.exr").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  auto image = read_image(path("out.exr"));
  ASSERT_TRUE(image);
  EXPECT_EQ(image->channel_names, (std::vector<std::string>{"R", "G", "B"}));
}

// Overwriting an existing output replaces it completely, leaving nothing else.
TEST_F(Render, OverwritesAnExistingOutput) {
  write("out.png", "an older picture\n");
  RunResult r = run({"render", scene_, "-b", "reference", "-o", path("out.png").string(), "--stats",
                     path("stats.json").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(read_image(path("out.png")));
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"out.png", "scene.json", "stats.json"}));
}

// plugins_loaded names only the types the scene uses, though every
// primitive plugin of the build is on the search path.
TEST_F(Render, StatsListOnlyTheSceneTypes) {
  SceneText s;
  s.objects = R"([{"type": "sphere", "radius": 1}, {"type": "sphere", "radius": 0.5, "center": [2, 0, 0]}])";
  const fs::path scene = write("one_type.json", s.text());
  RunResult r = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string(), "--stats",
                     path("stats.json").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  json stats = json::parse(read_file(path("stats.json")));
  EXPECT_EQ(stats["plugins_loaded"], json::array({"sphere"})) << stats.dump(2);
}

// A scene with no objects loads no primitive plugin at all.
TEST_F(Render, EmptySceneLoadsNoPlugin) {
  SceneText s;
  s.objects = "[]";
  s.lights = "";
  const fs::path scene = write("empty.json", s.text());
  RunResult r = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string(), "--stats",
                     path("stats.json").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  json stats = json::parse(read_file(path("stats.json")));
  EXPECT_EQ(stats["plugins_loaded"], json::array()) << stats.dump(2);
}

// A quadric's surface does not change when every coefficient is scaled by
// one factor. The unit sphere scaled by 1e-200 traced as noise and by 1e200
// as nothing, on every backend; the plugin now normalises its record. Ray 1
// meets the sphere head on at t = 4 (from z = 5), ray 2 at 45 degrees from
// (0, -5, 5) towards the origin at t = 5 sqrt(2) - 1, ray 3 misses (x = 2).
TEST_F(CliTest, ScaledQuadricCoefficientsTraceTheSameSphere) {
  const fs::path rays = write("rays.csv", "0,0,5,0,0,-1\n0,-5,5,0,1,-1\n2,0,5,0,0,-1\n");
  for (const char* scale : {"1e-200", "1e-100", "1e100", "1e200"}) {
    SceneText s;
    s.objects = std::string(R"([{"type": "quadric", "coefficients": [)") + scale + ", " + scale + ", " + scale +
                ", 0, 0, 0, 0, 0, 0, -" + scale + "]}]";
    const fs::path scene = write("scaled.json", s.text());
    for (const std::string backend : {"reference", "embree"}) {
      if (!prism::test::require_backend_or_skip(backend)) continue;
      SCOPED_TRACE(std::string(scale) + " on " + backend);
      RunResult r = run({"trace", scene.string(), "-b", backend, "--rays", rays.string(), "-o",
                         path("hits.csv").string(), "--digits", "17"});
      ASSERT_TRUE(ExitedWith(r, 0));
      const auto lines = lines_of(read_file(path("hits.csv")));
      ASSERT_EQ(lines.size(), 3u);
      const auto head_on = fields_of(lines[0]), oblique = fields_of(lines[1]);
      ASSERT_EQ(head_on.size(), 5u);
      ASSERT_EQ(oblique.size(), 5u);
      EXPECT_NEAR(number(head_on[0]), 4.0, 1e-12);
      EXPECT_EQ(head_on[1], "0");
      EXPECT_NEAR(number(head_on[4]), 1.0, 1e-12);
      EXPECT_NEAR(number(oblique[0]), 5.0 * std::sqrt(2.0) - 1.0, 1e-12);
      EXPECT_NEAR(number(oblique[3]), -std::sqrt(0.5), 1e-12);
      EXPECT_NEAR(number(oblique[4]), std::sqrt(0.5), 1e-12);
      EXPECT_EQ(lines[2], "inf,-1,0,0,0");
    }
  }
}

// The GPU backends read texels through a buffer texture and materials
// through a uniform block where they fit (gpu::KernelOptions::texel_sampler,
// material_block), else through the storage buffers: the same stored
// numbers, so the showcase (textured, a cube-map sky, nine materials)
// renders byte for byte the same every way.
class GpuSceneReads : public CliTest, public testing::WithParamInterface<std::string> {};

TEST_P(GpuSceneReads, UniformPathsAndStorageBuffersRenderTheSameImage) {
  if (!prism::test::require_backend_or_skip(GetParam())) return;
  const std::string scene = (prism::test::source_dir() / "scenes/showcase.json").string();
  const auto render = [&](const std::string& out) {
    RunResult r = run({"render", scene, "-b", GetParam(), "--width", "160", "--height", "90", "--spp", "1", "-o",
                       path(out).string(), "--stats", path(out + ".json").string()});
    EXPECT_TRUE(ExitedWith(r, 0));
    return read_file(path(out));
  };
  const std::string uniform = render("uniform.png");
  ::setenv("PRISM_GPU_TEXEL_BUFFER", "0", 1);
  const std::string texels_stored = render("texels_stored.png");
  ::unsetenv("PRISM_GPU_TEXEL_BUFFER");
  ::setenv("PRISM_GPU_MATERIAL_BLOCK", "0", 1);
  const std::string materials_stored = render("materials_stored.png");
  ::unsetenv("PRISM_GPU_MATERIAL_BLOCK");
  EXPECT_FALSE(uniform.empty());
  EXPECT_TRUE(uniform == texels_stored) << "the two texel paths rendered different images";
  EXPECT_TRUE(uniform == materials_stored) << "the two material paths rendered different images";
  // Each run built its own kernel (a different kernel hash).
  const auto kernel_file = [&](const std::string& out) {
    return nlohmann::json::parse(read_file(path(out + ".json")))["info"].value("program_cache_file", "");
  };
  const std::set<std::string> kernels = {kernel_file("uniform.png"), kernel_file("texels_stored.png"),
                                         kernel_file("materials_stored.png")};
  EXPECT_EQ(kernels.size(), 3u);
}

// A CPU driver renders in tiles of about 2^18 samples, a GPU in one of up
// to 2^21 (gpu::tile_budget); PRISM_GPU_TILE_SAMPLES forces either size
// here, and a tile of 64 samples cuts the image into many. Each pixel's
// work is the same whatever the tile, so the image and every AOV plane
// (rgb and id, normal and path, albedo and depth) come back byte for byte.
TEST_P(GpuSceneReads, EveryTileSizeRendersTheSameImageAndAovs) {
  if (!prism::test::require_backend_or_skip(GetParam())) return;
  const std::string scene = (prism::test::source_dir() / "scenes/showcase.json").string();
  const auto render = [&](const std::string& out, const char* tile_samples) {
    ::setenv("PRISM_GPU_TILE_SAMPLES", tile_samples, 1);
    RunResult r = run({"render", scene, "-b", GetParam(), "--width", "160", "--height", "90", "--spp", "2", "--aov",
                       "id,path,depth,normal,albedo", "-o", path(out).string()});
    ::unsetenv("PRISM_GPU_TILE_SAMPLES");
    EXPECT_TRUE(ExitedWith(r, 0));
    return read_file(path(out));
  };
  const std::string one_tile = render("one_tile.exr", "2097152");
  const std::string many_tiles = render("many_tiles.exr", "64");
  EXPECT_FALSE(one_tile.empty());
  EXPECT_TRUE(one_tile == many_tiles) << "one tile and many tiles rendered different images";
}

INSTANTIATE_TEST_SUITE_P(Backends, GpuSceneReads, testing::ValuesIn(prism::test::gpu_backend_names()),
                         prism::test::backend_param_name);

}  // namespace
}  // namespace prism::cli_test
