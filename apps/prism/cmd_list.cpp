// prism list: every backend and primitive plugin found, its version, and
// whether it can run here (or why not).
#include <cstdio>

#include "commands.hpp"
#include "prism/registry.hpp"

namespace prism::cli {

namespace {

// Two files of one name: the first in the search path is the one used, and
// it hides the others. Said on both lines, so that a plugin in
// PRISM_PLUGIN_PATH never replaces a built-in one silently.
std::string override_note(const std::vector<PluginReport>& reports, const PluginReport& report) {
  std::string note;
  bool before = true;
  for (const PluginReport& other : reports) {
    if (&other == &report) {
      before = false;
      continue;
    }
    if (other.kind != report.kind || other.name != report.name) continue;
    if (before) return " [not used: overridden by " + other.path.string() + "]";
    note += (note.empty() ? " [overrides " : ", ") + other.path.string();
  }
  return note.empty() ? "" : note + "]";
}

int run_list() {
  Registry registry;
  std::printf("plugin search path:\n");
  for (const auto& folder : registry.search_path()) std::printf("  %s\n", folder.c_str());
  std::string kind;
  const std::vector<PluginReport> reports = registry.scan_all();
  for (const auto& report : reports) {
    if (report.kind != kind) {
      kind = report.kind;
      std::printf("%s:\n", kind == "backend" ? "backends" : "primitive plugins");
    }
    const std::string note = override_note(reports, report);
    if (!report.error.empty()) {
      std::printf("  %-10s  failed to load: %s (%s)%s\n", report.name.c_str(), report.error.c_str(),
                  report.path.c_str(), note.c_str());
      continue;
    }
    std::string status;
    if (kind == "backend") status = (report.usable ? "usable: " : "not usable here: ") + report.detail;
    std::printf("  %-10s  %-8s %s (%s)%s\n", report.name.c_str(), report.version.c_str(), status.c_str(),
                report.path.c_str(), note.c_str());
  }
  return 0;
}

}  // namespace

Command add_list_command(CLI::App& app) {
  app.add_subcommand("list", "List backends and primitive plugins, and whether each can run here");
  return run_list;
}

}  // namespace prism::cli
