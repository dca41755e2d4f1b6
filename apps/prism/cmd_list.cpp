// prism list: every backend and primitive plugin found, its version, and
// whether it can run here (or why not).
#include <cstdio>

#include "commands.hpp"
#include "prism/registry.hpp"

namespace prism::cli {

namespace {

int run_list() {
  Registry registry;
  std::printf("plugin search path:\n");
  for (const auto& folder : registry.search_path()) std::printf("  %s\n", folder.c_str());
  std::string kind;
  for (const auto& report : registry.scan_all()) {
    if (report.kind != kind) {
      kind = report.kind;
      std::printf("%s:\n", kind == "backend" ? "backends" : "primitive plugins");
    }
    if (!report.error.empty()) {
      std::printf("  %-10s  failed to load: %s (%s)\n", report.name.c_str(), report.error.c_str(), report.path.c_str());
      continue;
    }
    std::string status;
    if (kind == "backend") status = (report.usable ? "usable: " : "not usable here: ") + report.detail;
    std::printf("  %-10s  %-8s %s (%s)\n", report.name.c_str(), report.version.c_str(), status.c_str(),
                report.path.c_str());
  }
  return 0;
}

}  // namespace

Command add_list_command(CLI::App& app) {
  app.add_subcommand("list", "List backends and primitive plugins, and whether each can run here");
  return run_list;
}

}  // namespace prism::cli
