// The plugin registry (core/src/registry.cpp) in this process: finding a
// primitive or backend plugin by name on the search path, the first folder
// that has a loadable file winning, and the errors for an unknown name, an
// ABI-mismatched plugin and a file that holds another type. The plugins are
// the build's own (lib/prism) and the command line tests' fixtures
// (tests/cli/fixtures), copied into folders of each test's own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "prism/errors.hpp"
#include "prism/primitive_abi.h"
#include "prism/registry.hpp"
#include "test_support.hpp"

namespace prism {
namespace {

namespace fs = std::filesystem;

fs::path plugin_dir() { return test::binary_dir() / "lib" / "prism"; }

// `file` copied into `folder` (created) as `name`.
fs::path copy_as(const fs::path& file, const fs::path& folder, const std::string& name) {
  fs::create_directories(folder);
  const fs::path target = folder / name;
  fs::copy_file(file, target, fs::copy_options::overwrite_existing);
  return target;
}

fs::path sphere_plugin() { return plugin_dir() / "libprism_primitive_sphere.so"; }

// The InputError's message of `call`, or "(no error)".
template <typename Call>
std::string input_error_of(Call call) {
  return test::message_of<InputError>(call);
}

// PRISM_PLUGIN_PATH set for one test, restored afterwards.
class PluginPathVariable {
 public:
  explicit PluginPathVariable(const char* value) {
    if (const char* old = std::getenv("PRISM_PLUGIN_PATH")) old_ = old;
    ::setenv("PRISM_PLUGIN_PATH", value, 1);
  }
  ~PluginPathVariable() {
    if (old_) ::setenv("PRISM_PLUGIN_PATH", old_->c_str(), 1);
    else ::unsetenv("PRISM_PLUGIN_PATH");
  }

 private:
  std::optional<std::string> old_;
};

// ---------------------------------------------------------------- lookup by name

TEST(Registry, FindsAPrimitivePluginByItsType) {
  Registry registry({plugin_dir()});
  const auto sphere = registry.primitive("sphere");
  EXPECT_STREQ(sphere->desc().type_name, "sphere");
  EXPECT_EQ(sphere->desc().abi_version, uint32_t(PRISM_PRIMITIVE_ABI_VERSION));
  EXPECT_EQ(sphere->path(), sphere_plugin());
  EXPECT_EQ(registry.primitive("sphere"), sphere) << "loaded once, then kept";
  EXPECT_STREQ(registry.primitive("box")->desc().type_name, "box");
}

TEST(Registry, FindsABackendPluginByItsName) {
  Registry registry({plugin_dir()});
  EXPECT_EQ(registry.backend("reference")->name(), "reference");
}

TEST(Registry, ListsTheTypesAndBackendsOfItsFoldersOnce) {
  const fs::path dir = test::fresh_temp_dir();
  copy_as(sphere_plugin(), dir / "a", "libprism_primitive_sphere.so");
  copy_as(sphere_plugin(), dir / "b", "libprism_primitive_sphere.so");
  copy_as(sphere_plugin(), dir / "b", "libprism_primitive_ball.so");
  copy_as(sphere_plugin(), dir / "b", "libprism_primitive_notes.txt");
  copy_as(plugin_dir() / "libprism_backend_reference.so", dir / "b", "libprism_backend_reference.so");
  Registry registry({dir / "a", dir / "b"});
  EXPECT_EQ(registry.primitive_types_found(), (std::vector<std::string>{"ball", "sphere"}));
  EXPECT_EQ(registry.backend_names_found(), (std::vector<std::string>{"reference"}));
}

// ---------------------------------------------------------------- errors

TEST(Registry, AnUnknownTypeIsAnInputErrorNamingTheTypeAndWhatWasSearched) {
  const fs::path dir = test::fresh_temp_dir();
  copy_as(sphere_plugin(), dir, "libprism_primitive_sphere.so");
  Registry registry({dir, dir / "missing"});
  EXPECT_EQ(input_error_of([&] { registry.primitive("cuboid"); }),
            "unknown object type 'cuboid' (primitive plugins found: sphere; searched " + dir.string() + ", " +
                (dir / "missing").string() + ")");
}

TEST(Registry, AnUnknownBackendIsAnInputErrorNamingIt) {
  const fs::path dir = test::fresh_temp_dir();
  Registry registry({dir});
  EXPECT_EQ(input_error_of([&] { registry.backend("warp"); }),
            "unknown backend 'warp' (backends found: none; searched " + dir.string() + ")");
}

TEST(Registry, ANameWithASlashMatchesNoFile) {
  // "../lib/prism/sphere" from the folder lib/prism/x would otherwise reach the sphere plugin.
  Registry registry({plugin_dir() / "x"});
  EXPECT_TRUE(registry.files_of("primitive", "../sphere").empty());
  EXPECT_NE(input_error_of([&] { registry.primitive("../sphere"); }).find("unknown object type '../sphere'"),
            std::string::npos);
}

TEST(Registry, APrimitivePluginOfAnotherAbiVersionIsRefusedWithItsFileAndTheReason) {
  const fs::path dir = test::fresh_temp_dir();
  const fs::path file = copy_as(PRISM_FIXTURE_PRIMITIVE_WRONGABI, dir, "libprism_primitive_wrongabi.so");
  Registry registry({dir});
  EXPECT_EQ(input_error_of([&] { registry.primitive("wrongabi"); }),
            "the primitive plugin for 'wrongabi' failed to load: " + file.string() +
                ": ABI version 999, this build of Prism needs " + std::to_string(PRISM_PRIMITIVE_ABI_VERSION) +
                " (rebuild the plugin against this Prism's SDK)");
}

TEST(Registry, ABackendPluginOfAnotherAbiVersionIsRefusedWithItsFile) {
  const fs::path dir = test::fresh_temp_dir();
  const fs::path file = copy_as(PRISM_FIXTURE_BACKEND_WRONGABI, dir, "libprism_backend_wrongabi.so");
  Registry registry({dir});
  EXPECT_EQ(input_error_of([&] { registry.backend("wrongabi"); }),
            "the backend 'wrongabi' failed to load: " + file.string() + ": ABI version 999, this build of Prism needs " +
                std::to_string(PRISM_BACKEND_ABI_VERSION));
}

TEST(Registry, AFileThatDeclaresAnotherTypeIsRefusedSayingWhichItDeclares) {
  const fs::path dir = test::fresh_temp_dir();
  const fs::path file = copy_as(sphere_plugin(), dir, "libprism_primitive_ball.so");
  Registry registry({dir});
  EXPECT_EQ(input_error_of([&] { registry.primitive("ball"); }),
            "the primitive plugin for 'ball' failed to load: " + file.string() +
                ": it declares type 'sphere', not 'ball'");
}

// ---------------------------------------------------------------- search order

TEST(Registry, TheFirstFolderOfTheSearchPathWins) {
  const fs::path dir = test::fresh_temp_dir();
  const fs::path first = copy_as(sphere_plugin(), dir / "a", "libprism_primitive_sphere.so");
  const fs::path second = copy_as(sphere_plugin(), dir / "b", "libprism_primitive_sphere.so");
  EXPECT_EQ(Registry({dir / "a", dir / "b"}).files_of("primitive", "sphere"), (std::vector<fs::path>{first, second}));
  EXPECT_EQ(Registry({dir / "a", dir / "b"}).primitive("sphere")->path(), first);
  EXPECT_EQ(Registry({dir / "b", dir / "a"}).primitive("sphere")->path(), second);
}

TEST(Registry, AFileThatFailsToLoadGivesWayToTheNextFolders) {
  const fs::path dir = test::fresh_temp_dir();
  copy_as(PRISM_FIXTURE_PRIMITIVE_WRONGABI, dir / "a", "libprism_primitive_sphere.so");
  const fs::path good = copy_as(sphere_plugin(), dir / "b", "libprism_primitive_sphere.so");
  EXPECT_EQ(Registry({dir / "a", dir / "b"}).primitive("sphere")->path(), good);
}

TEST(Registry, WhenNoFileLoadsEveryFailureIsNamedInSearchOrder) {
  const fs::path dir = test::fresh_temp_dir();
  const fs::path wrong_abi = copy_as(PRISM_FIXTURE_PRIMITIVE_WRONGABI, dir / "a", "libprism_primitive_ball.so");
  const fs::path other_type = copy_as(sphere_plugin(), dir / "b", "libprism_primitive_ball.so");
  const std::string message = input_error_of([&] { Registry({dir / "a", dir / "b"}).primitive("ball"); });
  const size_t first = message.find(wrong_abi.string() + ": ABI version 999");
  const size_t second = message.find(other_type.string() + ": it declares type 'sphere', not 'ball'");
  ASSERT_NE(first, std::string::npos) << message;
  ASSERT_NE(second, std::string::npos) << message;
  EXPECT_LT(first, second) << message;
}

TEST(Registry, PluginPathFoldersComeFirstInTheirOrderThenTheDefaults) {
  PluginPathVariable path("/p/one::/p/two:");
  const std::vector<fs::path> search = Registry::default_search_path();
  ASSERT_GE(search.size(), 3u);
  EXPECT_EQ(search[0], fs::path("/p/one"));
  EXPECT_EQ(search[1], fs::path("/p/two"));
  EXPECT_EQ(search[2], (Registry::core_library_folder() / "prism").lexically_normal());
}

TEST(Registry, ADefaultFolderAlreadyOnThePluginPathIsNotSearchedTwice) {
  const fs::path core_plugins = (Registry::core_library_folder() / "prism").lexically_normal();
  PluginPathVariable path(core_plugins.c_str());
  const std::vector<fs::path> search = Registry::default_search_path();
  EXPECT_EQ(std::count(search.begin(), search.end(), core_plugins), 1);
  EXPECT_EQ(search.front(), core_plugins);
}

}  // namespace
}  // namespace prism
