// Shared test helpers: the backends a test program runs against, and a
// fixture that skips (or, for a required backend, fails) where a backend
// cannot run on this machine.
//
// A test parameterised over backends:
//
//   class MyTest : public prism::test::BackendTest {};
//   TEST_P(MyTest, Case) { Scene s = load(R"({...})"); Image im = render(s); ... }
//   PRISM_INSTANTIATE_BACKEND_TESTS(MyTest);
//
// PRISM_REQUIRE_BACKENDS (comma-separated names) turns "cannot run here"
// from a skip into a failure for the named backends, and makes a named
// backend that is not found at all fail BackendDiscovery tests.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "prism/backend.hpp"
#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism::test {

std::filesystem::path source_dir();  // the repository root
std::filesystem::path binary_dir();  // the build tree

// Backend names the registry finds on its default search path, read once.
const std::vector<std::string>& backend_names();

// The names in PRISM_REQUIRE_BACKENDS (empty entries dropped).
std::vector<std::string> required_backends();
bool backend_required(const std::string& name);

// backend_names() without `name` (e.g. every backend to compare with "reference").
std::vector<std::string> backends_except(const std::string& name);

// The GPU backends (opengl, vulkan) among backend_names().
std::vector<std::string> gpu_backend_names();

// Loads and probes backend `name`. Returns true when it can run here. Otherwise
// it records a skip (or, for a name in PRISM_REQUIRE_BACKENDS or a backend that
// does not load, a failure) and returns false. gtest skips and fatal failures
// in a helper do not leave the calling test, so call it as
//   if (!prism::test::require_backend_or_skip(name)) return;
bool require_backend_or_skip(const std::string& name);

// A gtest-safe parameter name: the backend name with anything but [A-Za-z0-9] as '_'.
std::string backend_param_name(const testing::TestParamInfo<std::string>& info);

// A file's bytes ("" when it cannot be read), and writing them (throws
// std::runtime_error when it cannot).
std::string read_file(const std::filesystem::path& file);
void write_file(const std::filesystem::path& file, const std::string& contents);

// Starts args[0] (a path, or a name looked up on PATH) with `args` and the
// environment `env` (NAME=value entries; empty: this process's), in `cwd`
// when it is not empty, stdin from /dev/null and stdout and stderr going to
// `out_file` and `err_file`. Returns 0 and sets `pid`, or the errno value of
// why it could not start.
int spawn_with_output(const std::vector<std::string>& args, const std::vector<std::string>& env,
                      const std::filesystem::path& out_file, const std::filesystem::path& err_file,
                      const std::filesystem::path& cwd, int& pid);

// What a program run by run_captured did.
struct CapturedRun {
  bool started = false;     // false: it could not be started (`start_error` says why)
  bool exited = false;      // it exited normally (not killed by a signal)
  int status = -1;          // exit status when it exited
  int signal = 0;           // the signal that killed it otherwise
  std::string out, err;     // everything it wrote to stdout and stderr
  std::string start_error;
};

// Runs the program at path args[0] with `args` and the environment `env`
// (NAME=value entries; empty: this process's), stdin from /dev/null, and
// waits for it; stdout and stderr are captured through `out_file` and
// `err_file`, which stay behind for a look after a failure.
CapturedRun run_captured(const std::vector<std::string>& args, const std::vector<std::string>& env,
                         const std::filesystem::path& out_file, const std::filesystem::path& err_file);

// The message of the `Error` that `call` throws, or "(no error)" when it
// throws none (another exception goes through).
template <typename Error, typename Call>
std::string message_of(Call&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A new, empty folder for this test's files (unique per process and test).
std::filesystem::path fresh_temp_dir();

// A 64 KiB tmpfs at a folder of the test's, for full-disk tests: mounting
// needs root, so a fixture skips with the reason mount() gives. Unmounted
// when destroyed.
class SmallDisk {
 public:
  SmallDisk() = default;
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  ~SmallDisk() { unmount(); }
  void unmount();  // before the folder above it is removed
  // Creates and mounts `folder`; empty when mounted, else why not.
  std::string mount(const std::filesystem::path& folder);
  const std::filesystem::path& folder() const { return folder_; }
  // Fills what is left of the disk with one file, "filler"; false when it cannot be created.
  bool fill() const;
  // The names in the disk's folder but the filler, sorted.
  std::vector<std::string> files() const;

 private:
  std::filesystem::path folder_;
  bool mounted_ = false;
};

// The bytes of a PNG file whose header (IHDR, with a valid checksum) says
// `width` x `height` RGB pixels but whose image data is one byte: what a
// reader must refuse from the header alone, before allocating any pixel.
std::string png_claiming_size(uint32_t width, uint32_t height);

// Fixture for tests run once per backend. SetUp loads and probes the backend.
class BackendTest : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override;
  // The backend under test: the test's parameter, unless a test registered
  // by hand (testing::RegisterTest, no parameter) says otherwise.
  virtual std::string backend_name() const { return GetParam(); }

  // Parses a scene; relative texture paths resolve against `base_dir`.
  Scene load(const std::string& json, const std::filesystem::path& base_dir = ".");
  // A fresh backend prepared for `scene`, rendering with `settings` (default: the scene's image).
  Image render(const Scene& scene, const RenderSettings& settings);
  Image render(const Scene& scene);
  std::vector<TraceResult> trace(const Scene& scene, std::span<const TraceQuery> rays,
                                 BackendStats* stats = nullptr);

  Registry registry_;  // declared first: outlives every plugin object made from it

 private:
  std::shared_ptr<const BackendPlugin> plugin_;
};

}  // namespace prism::test

#define PRISM_INSTANTIATE_BACKEND_TESTS(suite)                                              \
  INSTANTIATE_TEST_SUITE_P(Backends, suite, testing::ValuesIn(prism::test::backend_names()), \
                           prism::test::backend_param_name)
