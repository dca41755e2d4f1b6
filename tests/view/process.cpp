#include "process.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "test_support.hpp"

extern char** environ;

namespace prism::view_test {

namespace {

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool starts_with(const char* text, const char* prefix) { return std::strncmp(text, prefix, std::strlen(prefix)) == 0; }

}  // namespace

std::ostream& operator<<(std::ostream& os, const RunResult& r) {
  os << "$ " << r.command << "\n";
  if (r.timed_out) os << "timed out and was killed\n";
  if (r.exited)
    os << "exit status " << r.status << "\n";
  else
    os << "killed by signal " << r.signal << " (" << strsignal(r.signal) << ")\n";
  return os << "--- stdout ---\n" << r.out << "--- stderr ---\n" << r.err << "--------------\n";
}

fs::path prism_binary() { return fs::path(PRISM_BINARY_DIR) / "bin" / "prism"; }

Child::Child(const std::vector<std::string>& argv_text, const RunOptions& options) {
  static std::atomic<int> serial{0};
  const int n = ++serial;
  out_file_ = options.log_dir / ("stdout." + std::to_string(n));
  err_file_ = options.log_dir / ("stderr." + std::to_string(n));
  if (options.display) command_ = "DISPLAY=" + *options.display + " ";
  else command_ = "(DISPLAY unset) ";
  for (const auto& a : argv_text) command_ += a + " ";
  if (!options.cwd.empty()) command_ += " (in " + options.cwd.string() + ")";

  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (!starts_with(*e, "PRISM_PLUGIN_PATH=") && !starts_with(*e, "DISPLAY=")) env_text.emplace_back(*e);
  if (options.display) env_text.push_back("DISPLAY=" + *options.display);

  int pid = 0;
  const int rc = prism::test::spawn_with_output(argv_text, env_text, out_file_, err_file_, options.cwd, pid);
  if (rc == 0) pid_ = pid;
  else command_ += " [cannot start: " + std::string(std::strerror(rc)) + "]";
}

Child::~Child() {
  if (pid_ > 0 && !reaped_) {
    ::kill(pid_, SIGKILL);
    while (::waitpid(pid_, &wstatus_, 0) < 0 && errno == EINTR) {
    }
  }
}

bool Child::running() {
  if (pid_ <= 0 || reaped_) return false;
  const pid_t r = ::waitpid(pid_, &wstatus_, WNOHANG);
  if (r == pid_) reaped_ = true;
  return !reaped_;
}

RunResult Child::wait(double seconds) {
  RunResult result;
  result.command = command_;
  if (pid_ <= 0) return result;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (running() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (!reaped_) {
    result.timed_out = true;
    ::kill(pid_, SIGKILL);
    while (::waitpid(pid_, &wstatus_, 0) < 0 && errno == EINTR) {
    }
    reaped_ = true;
  }
  result.exited = WIFEXITED(wstatus_);
  if (result.exited) result.status = WEXITSTATUS(wstatus_);
  if (WIFSIGNALED(wstatus_)) result.signal = WTERMSIG(wstatus_);
  result.out = read_file(out_file_);
  result.err = read_file(err_file_);
  return result;
}

RunResult run(const std::vector<std::string>& argv, const RunOptions& options, double seconds) {
  Child child(argv, options);
  return child.wait(seconds);
}

}  // namespace prism::view_test
