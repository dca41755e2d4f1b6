// Running `prism` (or any program) as a subprocess with its output in files.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace prism::stability {

struct ProcessResult {
  bool started = false;          // false: posix_spawn failed (`err` says why)
  bool exited = false;           // it exited normally (not killed by a signal)
  int status = -1;               // exit status when it exited
  int signal = 0;                // the signal that killed it otherwise
  std::string out, err;          // what it wrote to stdout and stderr
  std::string command;           // the command line, for messages
  std::string describe() const;  // "exit status 2: <stderr>" and the like
};

// Runs argv[0] with argv (the inherited environment, stdin from /dev/null),
// its stdout and stderr captured through files in `scratch`.
ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& scratch);

std::string read_text(const std::filesystem::path& file);
void write_text(const std::filesystem::path& file, const std::string& text);

}  // namespace prism::stability
