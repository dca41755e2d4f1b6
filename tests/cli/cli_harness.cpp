#include "cli_harness.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

extern char** environ;

namespace prism::cli_test {

std::ostream& operator<<(std::ostream& os, const RunResult& r) {
  os << "$ " << r.command << "\n";
  if (r.exited)
    os << "exit status " << r.status << "\n";
  else
    os << "killed by signal " << r.signal << " (" << strsignal(r.signal) << ")\n";
  os << "--- stdout ---\n" << r.out << "--- stderr ---\n" << r.err << "--------------\n";
  return os;
}

fs::path prism_binary() { return fs::path(PRISM_BINARY_DIR) / "bin" / "prism"; }
fs::path default_plugin_folder() { return fs::path(PRISM_BINARY_DIR) / "lib" / "prism"; }
fs::path bad_plugin_folder() { return fs::path(PRISM_CLI_BAD_PLUGIN_DIR); }

std::string read_file(const fs::path& file) { return prism::test::read_file(file); }

void write_file(const fs::path& file, const std::string& contents) { prism::test::write_file(file, contents); }

std::vector<std::string> list_folder(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> backends_built() { return plugins_built("libprism_backend_"); }
std::vector<std::string> primitives_built() { return plugins_built("libprism_primitive_"); }

std::vector<std::string> plugins_built(const std::string& prefix) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(default_plugin_folder(), ec), end; !ec && it != end; it.increment(ec)) {
    std::string file = it->path().filename().string();
    if (file.rfind(prefix, 0) == 0 && it->path().extension() == ".so")
      names.push_back(file.substr(prefix.size(), file.size() - prefix.size() - 3));
  }
  std::sort(names.begin(), names.end());
  return names;
}

void CliTest::SetUp() {
  root_ = prism::test::fresh_temp_dir();
  work_ = root_ / "work";
  fs::create_directories(work_);
  ASSERT_TRUE(fs::exists(prism_binary())) << prism_binary() << " is not built";
}

void CliTest::TearDown() {
  if (HasFailure()) {
    std::printf("(kept the test folder %s)\n", root_.c_str());
    return;
  }
  std::error_code ec;
  fs::remove_all(root_, ec);
}

fs::path CliTest::write(const std::string& name, const std::string& contents) {
  fs::path file = work_ / name;
  write_file(file, contents);
  return file;
}

RunResult CliTest::run(const std::vector<std::string>& args, std::optional<std::string> plugin_path) {
  RunResult result;
  const std::string binary = prism_binary().string();
  std::vector<std::string> argv_text = {binary};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  for (const auto& a : argv_text) result.command += (result.command.empty() ? "" : " ") + a;

  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "PRISM_PLUGIN_PATH=", 18) != 0) env_text.emplace_back(*e);
  if (plugin_path) {
    env_text.push_back("PRISM_PLUGIN_PATH=" + *plugin_path);
    result.command = "PRISM_PLUGIN_PATH=" + *plugin_path + " " + result.command;
  }

  const int n = ++runs_;
  const prism::test::CapturedRun run = prism::test::run_captured(
      argv_text, env_text, root_ / ("stdout." + std::to_string(n)), root_ / ("stderr." + std::to_string(n)));
  if (!run.started) {
    ADD_FAILURE() << run.start_error;
    return result;
  }
  return run_result(run, result.command);
}

RunResult run_result(const prism::test::CapturedRun& run, std::string command) {
  RunResult result;
  result.exited = run.exited;
  result.status = run.status;
  result.signal = run.signal;
  result.out = run.out;
  result.err = run.err;
  result.command = std::move(command);
  return result;
}

::testing::AssertionResult ExitedWith(const RunResult& r, int status) {
  if (!r.exited) return ::testing::AssertionFailure() << "crashed, expected exit status " << status << "\n" << r;
  if (r.status != status)
    return ::testing::AssertionFailure() << "exit status " << r.status << ", expected " << status << "\n" << r;
  return ::testing::AssertionSuccess();
}

bool contains_any(const std::string& text, const std::string& alternatives) {
  size_t start = 0;
  while (true) {
    size_t bar = alternatives.find('|', start);
    std::string part = alternatives.substr(start, bar == std::string::npos ? std::string::npos : bar - start);
    if (text.find(part) != std::string::npos) return true;
    if (bar == std::string::npos) return false;
    start = bar + 1;
  }
}

::testing::AssertionResult StderrHas(const RunResult& r, const std::vector<std::string>& parts) {
  for (const auto& part : parts)
    if (!contains_any(r.err, part))
      return ::testing::AssertionFailure() << "stderr lacks \"" << part << "\"\n" << r;
  return ::testing::AssertionSuccess();
}

}  // namespace prism::cli_test
