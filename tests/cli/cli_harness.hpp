// Running the built `prism` binary as a subprocess, each test in a fresh
// temporary folder of its own (the suite runs in parallel under ctest -j).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene_text.hpp"
#include "test_support.hpp"

namespace prism::cli_test {

namespace fs = std::filesystem;

// What one run of `prism` did.
struct RunResult {
  bool exited = false;    // it exited normally (not killed by a signal)
  int status = -1;        // exit status when it exited
  int signal = 0;         // the signal that killed it otherwise
  std::string out, err;   // everything it wrote to stdout and stderr
  std::string command;    // for failure messages
};
std::ostream& operator<<(std::ostream& os, const RunResult& r);
// The outcome of a run the test support captured, and the command it ran.
RunResult run_result(const prism::test::CapturedRun& run, std::string command);

fs::path prism_binary();             // <build>/bin/prism
fs::path default_plugin_folder();    // <build>/lib/prism
fs::path bad_plugin_folder();        // the fault fixtures built by tests/cli

std::string read_file(const fs::path& file);
void write_file(const fs::path& file, const std::string& contents);
// File names in `folder` (not recursive), sorted.
std::vector<std::string> list_folder(const fs::path& folder);

// Backends present in the default plugin folder (libprism_backend_<name>.so),
// sorted: the ones `prism` finds, since the tests run it without PRISM_PLUGIN_PATH.
std::vector<std::string> backends_built();
std::vector<std::string> primitives_built();  // primitive types
// The names after `prefix` of the plugin files built (lib<prefix><name>.so).
std::vector<std::string> plugins_built(const std::string& prefix);

// A test with its own temporary folder: `dir()` for the files a test
// writes (scenes, rays, outputs); captured stdout and stderr live outside
// it, so a test can check that a command left nothing behind in `dir()`.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  const fs::path& dir() const { return work_; }
  fs::path path(const std::string& name) const { return work_ / name; }
  fs::path write(const std::string& name, const std::string& contents);

  // Runs prism with `args`. PRISM_PLUGIN_PATH is removed from the inherited
  // environment unless `plugin_path` is given, so only the build tree's
  // plugins are found.
  RunResult run(const std::vector<std::string>& args, std::optional<std::string> plugin_path = std::nullopt);

 private:
  fs::path root_, work_;
  int runs_ = 0;
};

// Assertion helpers. Each returns a failure that shows the whole run.
::testing::AssertionResult ExitedWith(const RunResult& r, int status);
// Every part must occur in stderr; a part "a|b" is satisfied by either.
::testing::AssertionResult StderrHas(const RunResult& r, const std::vector<std::string>& parts);
bool contains_any(const std::string& text, const std::string& alternatives);

}  // namespace prism::cli_test
