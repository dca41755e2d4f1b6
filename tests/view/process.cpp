#include "process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

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

  std::vector<std::string> args = argv_text;
  std::vector<char*> argv, envp;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (!options.cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, options.cwd.c_str());
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
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
