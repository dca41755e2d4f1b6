// Faulty plugins: each is reported with its reason, never crashes prism and
// never hides the good plugins. The fixtures (built by tests/cli) are copied
// into the test's folder with a file that is not a shared object at all, and
// PRISM_PLUGIN_PATH points there; the build tree's plugins are still found
// after it.
#include <sstream>

#include "cli_harness.hpp"
#include "prism/registry.hpp"

namespace prism::cli_test {
namespace {

// The lines of `prism list` under a heading ("backends:" or "primitive plugins:").
std::vector<std::string> section(const std::string& out, const std::string& heading) {
  std::vector<std::string> lines;
  std::istringstream in(out);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != ' ') {
      inside = line == heading;
      continue;
    }
    if (inside) lines.push_back(line);
  }
  return lines;
}

// The line of `name` in `lines` (its name is the first word), or "".
std::string entry(const std::vector<std::string>& lines, const std::string& name) {
  for (const auto& line : lines) {
    std::istringstream words(line);
    std::string first;
    words >> first;
    if (first == name) return line;
  }
  return "";
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

class PluginFaults : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    plugins_ = path("plugins");
    fs::create_directory(plugins_);
    for (const char* file : {"libprism_primitive_wrongabi.so", "libprism_primitive_noentry.so",
                             "libprism_backend_wrongabi.so", "libprism_backend_foreignbuild.so"}) {
      ASSERT_TRUE(fs::exists(bad_plugin_folder() / file)) << bad_plugin_folder() / file << " is not built";
      fs::copy_file(bad_plugin_folder() / file, plugins_ / file);
    }
    write_file(plugins_ / "libprism_primitive_garbage.so", "This is not a shared object.\n");
    scene_ = write("scene.json", SceneText{}.text()).string();
  }

  RunResult run_with_plugins(const std::vector<std::string>& args) { return run(args, plugins_.string()); }

  // Renders a scene whose only object is `object`.
  RunResult render_object(const std::string& object, const std::string& backend = "reference") {
    SceneText s;
    s.objects = "[" + object + "]";
    const fs::path file = write("bad.json", s.text());
    return run_with_plugins({"render", file.string(), "-b", backend, "-o", path("out.png").string()});
  }

  fs::path plugins_;
  std::string scene_;
};

// A sphere plugin earlier in PRISM_PLUGIN_PATH replaced the built-in one
// silently. `prism list` says so on both lines, and --stats names both files.
TEST_F(CliTest, APluginThatOverridesABuiltInOneIsSaid) {
  const fs::path mine = path("mine");
  fs::create_directory(mine);
  const fs::path builtin = default_plugin_folder() / "libprism_primitive_sphere.so";
  fs::copy_file(builtin, mine / "libprism_primitive_sphere.so");
  RunResult list = run({"list"}, mine.string());
  ASSERT_TRUE(ExitedWith(list, 0));
  EXPECT_NE(list.out.find("[overrides "), std::string::npos) << list;
  EXPECT_NE(list.out.find("[not used: overridden by " + (mine / "libprism_primitive_sphere.so").string()),
            std::string::npos) << list;

  const fs::path scene = write("scene.json", SceneText{}.text());
  RunResult render = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string(), "--stats",
                          path("stats.json").string()},
                         mine.string());
  ASSERT_TRUE(ExitedWith(render, 0));
  const std::string stats = read_file(path("stats.json"));
  EXPECT_NE(stats.find("\"plugins_overriding\""), std::string::npos) << stats;
  EXPECT_NE(stats.find((mine / "libprism_primitive_sphere.so").string()), std::string::npos) << stats;
}

TEST_F(PluginFaults, ListReportsEachBadPluginWithItsReason) {
  RunResult r = run_with_plugins({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  const auto backends = section(r.out, "backends:");
  const auto primitives = section(r.out, "primitive plugins:");

  const std::string wrongabi = entry(primitives, "wrongabi");
  EXPECT_NE(wrongabi.find("ABI version 999"), std::string::npos) << r;
  const std::string noentry = entry(primitives, "noentry");
  EXPECT_NE(noentry.find("no entry symbol"), std::string::npos) << r;
  const std::string garbage = entry(primitives, "garbage");
  EXPECT_NE(garbage.find("failed to load"), std::string::npos) << r;
  EXPECT_NE(garbage.find("libprism_primitive_garbage.so"), std::string::npos) << r;
  const std::string backend = entry(backends, "wrongabi");
  EXPECT_NE(backend.find("ABI version 999"), std::string::npos) << r;

  // The good plugins are still there, loaded, with their versions.
  const std::string reference = entry(backends, "reference");
  EXPECT_NE(reference.find("usable"), std::string::npos) << r;
  EXPECT_EQ(reference.find("failed"), std::string::npos) << r;
  for (const char* type : {"sphere", "plane"}) {
    const std::string line = entry(primitives, type);
    EXPECT_FALSE(line.empty()) << type << " is not listed\n" << r;
    EXPECT_EQ(line.find("failed"), std::string::npos) << r;
  }
  // The search path shows the fixture folder first.
  EXPECT_NE(r.out.find(plugins_.string()), std::string::npos) << r;
  EXPECT_LT(r.out.find(plugins_.string()), r.out.find(default_plugin_folder().lexically_normal().string())) << r;
}

TEST_F(PluginFaults, ListWithoutBadPluginsReportsNoFailure) {
  RunResult r = run({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_FALSE(entry(section(r.out, "backends:"), "reference").empty()) << r;
  EXPECT_FALSE(entry(section(r.out, "primitive plugins:"), "sphere").empty()) << r;
  EXPECT_TRUE(entry(section(r.out, "primitive plugins:"), "wrongabi").empty()) << r;
  EXPECT_EQ(joined(section(r.out, "primitive plugins:")).find("failed"), std::string::npos) << r;
}

TEST_F(PluginFaults, SceneUsingWrongAbiPluginIsRejected) {
  RunResult r = render_object(R"({"type": "wrongabi"})");
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"objects[0].type", "wrongabi", "ABI version 999"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(PluginFaults, SceneUsingPluginWithoutEntryIsRejected) {
  RunResult r = render_object(R"({"type": "noentry"})");
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"objects[0].type", "noentry", "no entry symbol"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(PluginFaults, SceneUsingGarbagePluginIsRejected) {
  RunResult r = render_object(R"({"type": "garbage"})");
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"objects[0].type", "garbage", "libprism_primitive_garbage.so"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(PluginFaults, TraceOfSceneUsingWrongAbiPluginIsRejected) {
  SceneText s;
  s.objects = R"([{"type": "sphere", "radius": 1}, {"type": "wrongabi"}])";
  const fs::path file = write("bad.json", s.text());
  write("rays.csv", "0,0,-5,0,0,1\n");
  RunResult r = run_with_plugins({"trace", file.string(), "-b", "reference", "--rays", path("rays.csv").string(), "-o",
                                  path("out.csv").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"objects[1].type", "wrongabi", "ABI version 999"}));
  EXPECT_FALSE(fs::exists(path("out.csv")));
}

TEST_F(PluginFaults, MissingPluginNamesWhatWasFound) {
  RunResult r = render_object(R"({"type": "capsule", "radius": 1})");
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"objects[0].type", "capsule", "sphere", "plane"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(PluginFaults, SceneNotUsingBadPluginsStillRenders) {
  RunResult r = run_with_plugins({"render", scene_, "-b", "reference", "-o", path("out.png").string(), "--stats",
                                  path("stats.json").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
  EXPECT_NE(read_file(path("stats.json")).find("\"reference\""), std::string::npos);
}

TEST_F(PluginFaults, NamedWrongAbiBackendIsRejected) {
  RunResult r = run_with_plugins({"render", scene_, "-b", "wrongabi", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"wrongabi", "ABI version 999"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

// -b auto passes over a backend that fails to load (the fixture claims the
// highest speed rank of all, so it would win if it were not skipped).
TEST_F(PluginFaults, AutoBackendSkipsWrongAbiBackend) {
  RunResult r = run_with_plugins({"render", scene_, "-o", path("out.png").string(), "--stats",
                                  path("stats.json").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
  const std::string stats = read_file(path("stats.json"));
  EXPECT_EQ(stats.find("wrongabi"), std::string::npos) << stats;
}

// What the registry says of a backend whose layout fingerprint is not the core's.
constexpr const char* kForeignBuildError =
    "libprism_backend_foreignbuild.so was built against a different Prism, compiler or standard library than this "
    "Prism (its layout fingerprint differs); rebuild it against this Prism's SDK";

TEST_F(PluginFaults, LoadingABackendOfAnotherBuildIsRefused) {
  std::string error;
  EXPECT_EQ(load_backend_plugin(plugins_ / "libprism_backend_foreignbuild.so", error), nullptr);
  EXPECT_EQ(error, kForeignBuildError);
}

TEST_F(PluginFaults, ListReportsABackendOfAnotherBuild) {
  RunResult r = run_with_plugins({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(entry(section(r.out, "backends:"), "foreignbuild"),
            std::string("  foreignbuild  failed to load: ") + kForeignBuildError + " (" +
                (plugins_ / "libprism_backend_foreignbuild.so").string() + ")")
      << r;
}

TEST_F(PluginFaults, NamedBackendOfAnotherBuildIsRejected) {
  RunResult r = run_with_plugins({"render", scene_, "-b", "foreignbuild", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"the backend 'foreignbuild' failed to load: " +
                                (plugins_ / "libprism_backend_foreignbuild.so").string() + ": " + kForeignBuildError}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

// -b auto passes over it too (it claims the highest speed rank of all).
TEST_F(PluginFaults, AutoBackendSkipsBackendOfAnotherBuild) {
  RunResult r = run_with_plugins({"render", scene_, "-o", path("out.png").string(), "--stats",
                                  path("stats.json").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
  EXPECT_EQ(read_file(path("stats.json")).find("foreignbuild"), std::string::npos);
}

// A folder in PRISM_PLUGIN_PATH that does not exist, and empty entries, are harmless.
TEST_F(PluginFaults, MissingSearchFolderIsHarmless) {
  RunResult r = run({"render", scene_, "-b", "reference", "-o", path("out.png").string()},
                    "::" + path("nosuch").string() + ":");
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

}  // namespace
// A backend that throws prism::RuntimeError from render and trace: the
// message reaches the user and the exit status is 1, although the plugin
// that threw it is unloaded before main() catches it (the error's vtable is
// the core's; a copy inside the plugin crashed here with SIGSEGV).
class ThrowingBackend : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    plugins_ = path("plugins");
    fs::create_directory(plugins_);
    const fs::path file = bad_plugin_folder() / "libprism_backend_throwing.so";
    ASSERT_TRUE(fs::exists(file)) << file << " is not built";
    fs::copy_file(file, plugins_ / file.filename());
    scene_ = write("scene.json", SceneText{}.text()).string();
  }
  fs::path plugins_;
  std::string scene_;
};

TEST_F(ThrowingBackend, RenderFailureIsReportedWithExitOne) {
  RunResult r = run({"render", scene_, "-b", "throwing", "-o", path("out.png").string()}, plugins_.string());
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"deliberate failure in render"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

TEST_F(ThrowingBackend, TraceFailureIsReportedWithExitOne) {
  const fs::path rays = write("rays.csv", "0,0,-5,0,0,1\n");
  RunResult r = run({"trace", scene_, "-b", "throwing", "--rays", rays.string(), "-o", path("hits.csv").string()},
                    plugins_.string());
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"deliberate failure in trace"}));
  EXPECT_FALSE(fs::exists(path("hits.csv")));
}

}  // namespace prism::cli_test
