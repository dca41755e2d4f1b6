// Running `prism` (or any program) as a child process for the viewer tests:
// a chosen working folder and DISPLAY, stdout/stderr captured to files, and
// a time limit after which the child is killed.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace prism::view_test {

namespace fs = std::filesystem;

struct RunResult {
  bool exited = false;     // exited normally (not killed by a signal)
  int status = -1;         // its exit status
  int signal = 0;          // the signal that ended it otherwise
  bool timed_out = false;  // killed by us after the time limit
  std::string out, err, command;
};
std::ostream& operator<<(std::ostream& os, const RunResult& r);

struct RunOptions {
  fs::path cwd;                        // empty: the test's own
  std::optional<std::string> display;  // DISPLAY for the child; nullopt: unset
  fs::path log_dir;                    // where stdout/stderr files go (required)
};

class Child {
 public:
  // Starts `argv` (argv[0] a path or a name looked up on PATH).
  // PRISM_PLUGIN_PATH is removed from the environment, so prism finds the
  // build tree's plugins only.
  Child(const std::vector<std::string>& argv, const RunOptions& options);
  ~Child();  // kills a child still running
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool started() const { return pid_ > 0; }
  bool running();
  // Waits up to `seconds`, then kills it (SIGKILL).
  RunResult wait(double seconds);

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int wstatus_ = 0;
  fs::path out_file_, err_file_;
  std::string command_;
};

RunResult run(const std::vector<std::string>& argv, const RunOptions& options, double seconds = 120);

fs::path prism_binary();  // <build>/bin/prism

}  // namespace prism::view_test
