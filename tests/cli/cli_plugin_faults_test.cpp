// More plugin faults (the fixtures of fixtures/primitive_faulty.cpp and
// fixtures/backend_faulty.cpp, one fault per .so): an entry function that
// throws or returns garbage, a backend whose probe or create throws
// something that is not a std::exception, a primitive whose GLSL does not
// compile, and GPU drivers hidden from the process. Each is reported by
// name with its reason; whatever does not need the faulty part still runs.
#include <cstdlib>
#include <sstream>

#include "cli_harness.hpp"
#include "test_support.hpp"

namespace prism::cli_test {
namespace {

// The line of `prism list` for `name` under `heading` ("backends:" or "primitive plugins:"), or "".
std::string list_line(const std::string& out, const std::string& heading, const std::string& name) {
  std::istringstream in(out);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != ' ') inside = line == heading;
    else if (inside && line.rfind("  " + name + " ", 0) == 0) return line;
  }
  return "";
}

struct Fault {
  const char* name;    // the fixture's type or backend name
  const char* reason;  // what the load error must say
};

const Fault kPrimitiveFaults[] = {
    {"throwing", "entry function threw: deliberate failure in the entry function"},
    {"throwingint", "entry function threw an exception that is not a std::exception"},
    {"nulldesc", "entry function returned no descriptor"},
    {"nullname", "type_name is missing"},
    {"nullfunctions", "missing functions"},
    {"hugerecord", "record_size 2147483632"},
    {"hugefields", "field table of 1000000 fields"},
    {"badfield", "field 0 has no name"},
};

class FaultyPlugins : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    plugins_ = path("plugins");
    fs::create_directory(plugins_);
    for (const auto& entry : fs::directory_iterator(bad_plugin_folder())) {
      const std::string file = entry.path().filename().string();
      if (file.find("_wrongabi") == std::string::npos && file.find("_noentry") == std::string::npos &&
          file.find("_badbounds") == std::string::npos && file.find("_foreignbuild") == std::string::npos &&
          file != "libprism_backend_throwing.so")
        fs::copy_file(entry.path(), plugins_ / file);
    }
    for (const Fault& f : kPrimitiveFaults)
      ASSERT_TRUE(fs::exists(plugins_ / ("libprism_primitive_" + std::string(f.name) + ".so"))) << f.name;
    scene_ = write("scene.json", SceneText{}.text()).string();
  }

  RunResult run_with_plugins(const std::vector<std::string>& args) { return run(args, plugins_.string()); }

  // Renders the base scene with `object` added as objects[2].
  RunResult render_with(const std::string& object, const std::string& backend) {
    SceneText s;
    s.objects = R"([{"type": "sphere", "radius": 1}, {"type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0]}, )" +
                object + "]";
    const fs::path file = write("with.json", s.text());
    return run_with_plugins({"render", file.string(), "-b", backend, "-o", path("out.png").string()});
  }

  fs::path plugins_;
  std::string scene_;
};

TEST_F(FaultyPlugins, ListReportsEachFaultAndCarriesOn) {
  RunResult r = run_with_plugins({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  for (const Fault& f : kPrimitiveFaults) {
    const std::string line = list_line(r.out, "primitive plugins:", f.name);
    EXPECT_NE(line.find("failed to load"), std::string::npos) << f.name << "\n" << r;
    EXPECT_NE(line.find(f.reason), std::string::npos) << f.name << "\n" << r;
  }
  // Its GLSL is only compiled by a GPU backend: to the loader it is a plugin like any other.
  EXPECT_EQ(list_line(r.out, "primitive plugins:", "badglsl").find("failed"), std::string::npos) << r;
  EXPECT_NE(list_line(r.out, "backends:", "entrythrows").find("deliberate failure in the backend entry function"),
            std::string::npos) << r;
  EXPECT_NE(list_line(r.out, "backends:", "nullname").find("descriptor is unusable"), std::string::npos) << r;
  EXPECT_NE(list_line(r.out, "backends:", "probethrows").find("not usable here: probe failed"), std::string::npos)
      << r;
  EXPECT_NE(list_line(r.out, "backends:", "createthrows").find("usable: a faulty backend"), std::string::npos) << r;
  EXPECT_NE(list_line(r.out, "backends:", "reference").find("usable"), std::string::npos) << r;
  for (const char* good : {"sphere", "plane"}) {
    const std::string line = list_line(r.out, "primitive plugins:", good);
    EXPECT_FALSE(line.empty()) << good << "\n" << r;
    EXPECT_EQ(line.find("failed"), std::string::npos) << r;
  }
}

class FaultyPrimitive : public FaultyPlugins, public testing::WithParamInterface<Fault> {};

TEST_P(FaultyPrimitive, SceneUsingItIsRejectedByName) {
  RunResult r = render_with(R"({"type": ")" + std::string(GetParam().name) + R"(", "radius": 1})", "reference");
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"objects[2].type", GetParam().name, GetParam().reason}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

INSTANTIATE_TEST_SUITE_P(Faults, FaultyPrimitive, testing::ValuesIn(kPrimitiveFaults),
                         [](const testing::TestParamInfo<Fault>& info) { return std::string(info.param.name); });

TEST_F(FaultyPlugins, SceneNotUsingThemRendersOnTheCpuBackends) {
  for (const std::string backend : {"reference", "embree"}) {
    if (!prism::test::require_backend_or_skip(backend)) continue;
    RunResult r = run_with_plugins({"render", scene_, "-b", backend, "-o", path(backend + ".png").string()});
    EXPECT_TRUE(ExitedWith(r, 0));
    EXPECT_TRUE(fs::exists(path(backend + ".png")));
  }
}

TEST_F(FaultyPlugins, AutoPassesOverFaultyBackends) {
  RunResult r = run_with_plugins({"render", scene_, "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

TEST_F(FaultyPlugins, BackendWhoseEntryThrowsIsRejected) {
  RunResult r = run_with_plugins({"render", scene_, "-b", "entrythrows", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"entrythrows", "deliberate failure in the backend entry function"}));
}

TEST_F(FaultyPlugins, BackendWhoseProbeThrowsCannotRun) {
  RunResult r = run_with_plugins({"render", scene_, "-b", "probethrows", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"probethrows", "cannot run here", "probe failed"}));
}

TEST_F(FaultyPlugins, BackendWhoseCreateThrowsFailsToStart) {
  RunResult r = run_with_plugins({"render", scene_, "-b", "createthrows", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"createthrows", "failed to start", "not a std::exception"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

// ------------------------------------------------ backends that crash or exit

// crashctor segfaults as its library loads, crashprobe in its probe,
// exitctor calls exit(0) as it loads. Each is probed in a child process:
// `prism list`, `-b auto` and `prism conform` report it and carry on.
TEST_F(FaultyPlugins, ListReportsBackendsThatCrashOrExit) {
  RunResult r = run_with_plugins({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_NE(list_line(r.out, "backends:", "crashctor").find("probe crashed (SIGSEGV)"), std::string::npos) << r;
  EXPECT_NE(list_line(r.out, "backends:", "crashprobe").find("probe crashed (SIGSEGV)"), std::string::npos) << r;
  EXPECT_NE(list_line(r.out, "backends:", "exitctor").find("probe exited with status 0 before reporting"),
            std::string::npos) << r;
  EXPECT_NE(list_line(r.out, "backends:", "reference").find("usable"), std::string::npos) << r;
  EXPECT_FALSE(list_line(r.out, "primitive plugins:", "sphere").empty()) << r;  // the list went on to the end
}

TEST_F(FaultyPlugins, AutoRendersDespiteBackendsThatCrashOrExit) {
  RunResult r = run_with_plugins({"render", scene_, "-b", "auto", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

TEST_F(FaultyPlugins, ConformSkipsBackendsThatCrashOrExit) {
  // A 16x16 sphere keeps the real backends' share of the run short.
  SceneText s;
  s.image = R"({"width": 16, "height": 16})";
  const fs::path small = write("small.json", s.text());
  ::setenv("PRISM_CACHE_DIR", (dir().parent_path() / "cache").c_str(), 1);
  RunResult r = run_with_plugins({"conform", small.string()});
  ::unsetenv("PRISM_CACHE_DIR");
  EXPECT_TRUE(r.exited) << r;  // the status depends on the other faulty backends (createthrows fails)
  for (const char* name : {"crashctor", "crashprobe"})
    EXPECT_NE(r.out.find(name), std::string::npos) << name << "\n" << r;
  EXPECT_NE(r.out.find("probe crashed (SIGSEGV)"), std::string::npos) << r;
  EXPECT_NE(r.out.find("probe exited with status 0 before reporting"), std::string::npos) << r;
}

// ------------------------------------------------ primitives whose answers are wrong

struct WrongAnswer {
  const char* name;     // the fixture's type
  const char* message;  // what the error must say
};

const WrongAnswer kWrongAnswers[] = {
    {"nanhit", "returned a hit at t = nan, outside (tmin, tmax]"},
    {"outsidehit", "outside (tmin, tmax]"},
    {"nansurface", "returned a non-finite surface normal"},
};

class WrongPrimitiveAnswer : public FaultyPlugins, public testing::WithParamInterface<WrongAnswer> {};

// Exit 1 naming the plugin and its object, on both CPU backends: never an
// assertion, a crash or a picture made of a NaN.
TEST_P(WrongPrimitiveAnswer, RenderFailsNamingPluginAndObject) {
  for (const std::string backend : {"reference", "embree"}) {
    if (!prism::test::require_backend_or_skip(backend)) continue;
    RunResult r = render_with(R"({"type": ")" + std::string(GetParam().name) + R"(", "radius": 1, "center": [2, 0, 0]})", backend);
    EXPECT_TRUE(ExitedWith(r, 1)) << backend;
    EXPECT_TRUE(StderrHas(r, {"primitive plugin '" + std::string(GetParam().name) + "'", GetParam().message,
                              "for its object at (2, 0, 0)"})) << backend;
    EXPECT_FALSE(fs::exists(path("out.png"))) << backend;
  }
}

TEST_P(WrongPrimitiveAnswer, TraceFailsNamingPluginAndObject) {
  SceneText s;
  s.objects = R"([{"type": ")" + std::string(GetParam().name) + R"(", "radius": 1}])";
  const fs::path scene = write("one.json", s.text());
  const fs::path rays = write("rays.csv", "ox,oy,oz,dx,dy,dz\n0,0,5,0,0,-1\n");
  RunResult r = run_with_plugins({"trace", scene.string(), "-b", "reference", "--rays", rays.string(), "-o",
                                  path("hits.csv").string()});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"primitive plugin '" + std::string(GetParam().name) + "'", GetParam().message}));
  EXPECT_FALSE(fs::exists(path("hits.csv")));
}

TEST_P(WrongPrimitiveAnswer, PluginCheckFails) {
  const fs::path file = plugins_ / ("libprism_primitive_" + std::string(GetParam().name) + ".so");
  RunResult r = run_with_plugins({"plugin", "check", file.string(), "-b", "embree", "--rays", "200"});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_NE((r.out + r.err).find(GetParam().message), std::string::npos) << r;
}

INSTANTIATE_TEST_SUITE_P(Faults, WrongPrimitiveAnswer, testing::ValuesIn(kWrongAnswers),
                         [](const testing::TestParamInfo<WrongAnswer>& info) { return std::string(info.param.name); });

// ------------------------------------------------ bounding spheres that are not

// A bounding sphere smaller than the primitive: the self-test finds a hit
// point outside it (exit 1). One with a NaN radius: the self-test fails, and
// so does an Embree render (its light buffers read the spheres), naming the
// plugin and the object.
TEST_F(FaultyPlugins, PluginCheckFailsABoundingSphereThatMissesHits) {
  const fs::path file = plugins_ / "libprism_primitive_smallsphere.so";
  RunResult r = run_with_plugins({"plugin", "check", file.string(), "-b", "reference", "--rays", "200"});
  EXPECT_TRUE(ExitedWith(r, 1)) << r;
  EXPECT_NE(r.out.find("bounding sphere (the plugin's, or the box's if smaller): FAIL: misses a hit point"),
            std::string::npos) << r;
}

TEST_F(FaultyPlugins, ABoundingSphereOfNanRadiusIsRefusedNamingThePlugin) {
  const fs::path file = plugins_ / "libprism_primitive_nansphere.so";
  RunResult check = run_with_plugins({"plugin", "check", file.string(), "-b", "reference", "--rays", "200"});
  EXPECT_TRUE(ExitedWith(check, 1)) << check;
  EXPECT_NE(check.out.find("returned a bounding sphere of centre (0, 0, 0) and radius nan"), std::string::npos) << check;
  if (!prism::test::require_backend_or_skip("embree")) return;
  RunResult r = render_with(R"({"type": "nansphere", "radius": 1, "center": [2, 0, 0]})", "embree");
  EXPECT_TRUE(ExitedWith(r, 1)) << r;
  EXPECT_TRUE(StderrHas(r, {"primitive plugin 'nansphere'", "returned a bounding sphere", "for its object at (2, 0, 0)"}))
      << r;
  EXPECT_FALSE(fs::exists(path("out.png")));
}

// ------------------------------------------------ GLSL that does not compile

class BadGlsl : public FaultyPlugins, public testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    FaultyPlugins::SetUp();
    // A fresh program cache (outside dir()): nothing cached elsewhere can
    // hide the compile, and nothing is left in the user's cache.
    ::setenv("PRISM_CACHE_DIR", (dir().parent_path() / "cache").c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("PRISM_CACHE_DIR");
    FaultyPlugins::TearDown();
  }
};

TEST_P(BadGlsl, ErrorNamesThePluginAndTheCompilerMessage) {
  if (!prism::test::require_backend_or_skip(GetParam())) return;
  RunResult r = render_with(R"({"type": "badglsl", "radius": 0.5, "center": [2, 0, 0]})", GetParam());
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"primitive plugin 'badglsl' (line 2 of its source)", "syntax error"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_P(BadGlsl, SceneNotUsingItStillRenders) {
  if (!prism::test::require_backend_or_skip(GetParam())) return;
  RunResult r = run_with_plugins({"render", scene_, "-b", GetParam(), "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

// Its CPU side is sound: only the GPU kernel is broken.
TEST_F(FaultyPlugins, BadGlslPluginRendersOnTheCpu) {
  RunResult r = render_with(R"({"type": "badglsl", "radius": 0.5, "center": [2, 0, 0]})", "reference");
  EXPECT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

INSTANTIATE_TEST_SUITE_P(Gpu, BadGlsl, testing::Values("opengl", "vulkan"));

// ------------------------------------------------ GPU drivers hidden

// Neither EGL nor the Vulkan loader finds a driver: `prism list` says why
// for both GPU backends, the CPU backends and -b auto still render, and a
// render that names a GPU backend ends with exit 1 and the reason.
class NoGpuDrivers : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    for (const char* variable : kVariables) ::setenv(variable, "/nonexistent/driver.json", 1);
    scene_ = write("scene.json", SceneText{}.text()).string();
  }
  void TearDown() override {
    for (const char* variable : kVariables) ::unsetenv(variable);
    CliTest::TearDown();
  }
  static constexpr const char* kVariables[] = {"__EGL_VENDOR_LIBRARY_FILENAMES", "VK_ICD_FILENAMES", "VK_DRIVER_FILES"};
  std::string scene_;
};

TEST_F(NoGpuDrivers, ListSaysWhyAndCpuBackendsRender) {
  RunResult list = run({"list"});
  ASSERT_TRUE(ExitedWith(list, 0));
  for (const std::string& gpu : backends_built()) {
    if (gpu != "opengl" && gpu != "vulkan") continue;
    EXPECT_NE(list_line(list.out, "backends:", gpu).find("not usable here: "), std::string::npos) << list;
    RunResult r = run({"render", scene_, "-b", gpu, "-o", path(gpu + ".png").string()});
    EXPECT_TRUE(ExitedWith(r, 1));
    EXPECT_TRUE(StderrHas(r, {"backend '" + gpu + "' cannot run here: "}));
    EXPECT_FALSE(fs::exists(path(gpu + ".png")));
  }
  for (const std::string& cpu : {std::string("reference"), std::string("embree"), std::string("auto")}) {
    if (cpu == "embree" && !prism::test::require_backend_or_skip(cpu)) continue;
    RunResult r = run({"render", scene_, "-b", cpu, "-o", path(cpu + ".png").string()});
    EXPECT_TRUE(ExitedWith(r, 0));
    EXPECT_TRUE(fs::exists(path(cpu + ".png")));
  }
}

}  // namespace
}  // namespace prism::cli_test
