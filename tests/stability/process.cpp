#include "process.hpp"

#include "test_support.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace prism::stability {

namespace fs = std::filesystem;

std::string read_text(const fs::path& file) { return prism::test::read_file(file); }

void write_text(const fs::path& file, const std::string& text) { prism::test::write_file(file, text); }

std::string ProcessResult::describe() const {
  std::string what = !started ? "could not start"
                     : exited ? "exit status " + std::to_string(status)
                              : "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  std::string tail = err;
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
  return what + (tail.empty() ? "" : ": " + tail);
}

ProcessResult run_process(const std::vector<std::string>& args, const fs::path& scratch) {
  ProcessResult result;
  for (const auto& a : args) result.command += (result.command.empty() ? "" : " ") + a;
  std::vector<std::string> text = args;
  std::vector<char*> argv;
  for (auto& a : text) argv.push_back(a.data());
  argv.push_back(nullptr);

  const fs::path out_file = scratch / "stdout.txt", err_file = scratch / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    result.err = std::string("cannot start ") + argv[0] + ": " + std::strerror(rc);
    return result;
  }
  result.started = true;
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  result.exited = WIFEXITED(wstatus);
  if (result.exited) result.status = WEXITSTATUS(wstatus);
  if (WIFSIGNALED(wstatus)) result.signal = WTERMSIG(wstatus);
  result.out = read_text(out_file);
  result.err = read_text(err_file);
  return result;
}

}  // namespace prism::stability
