#include "process.hpp"

#include <cstring>

#include "test_support.hpp"

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
  const prism::test::CapturedRun run =
      prism::test::run_captured(args, {}, scratch / "stdout.txt", scratch / "stderr.txt");
  result.started = run.started;
  result.exited = run.exited;
  result.status = run.status;
  result.signal = run.signal;
  result.out = run.out;
  result.err = run.started ? run.err : run.start_error;
  return result;
}

}  // namespace prism::stability
