// prism list: every backend and primitive plugin found, its version, and
// whether it can run here (or why not); with a scene, the precision the GPU
// kernels would give each of its objects, and why.
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "commands.hpp"
#include "precision.hpp"
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

// The report `-b auto` goes by for each backend name: the first file of the
// search path that loaded (a later one of the same name is hidden by it).
std::vector<const PluginReport*> backends_in_effect(const std::vector<PluginReport>& reports) {
  std::vector<const PluginReport*> in_effect;
  for (const PluginReport& report : reports) {
    if (report.kind != "backend" || !report.error.empty()) continue;
    bool hidden = false;
    for (const PluginReport* earlier : in_effect) hidden = hidden || earlier->name == report.name;
    if (!hidden) in_effect.push_back(&report);
  }
  return in_effect;
}

// Which backend `-b auto` picks here and why: the usable one with the
// highest speed rank; the faster ones passed over, with their reasons.
void print_auto_choice(const std::vector<PluginReport>& reports) {
  const PluginReport* chosen = nullptr;
  for (const PluginReport* report : backends_in_effect(reports))
    if (report->usable && (!chosen || report->speed_rank > chosen->speed_rank)) chosen = report;
  if (!chosen) {
    std::printf("-b auto: no backend can run here (see above why)\n");
    return;
  }
  std::printf("-b auto picks %s here: the usable backend with the highest speed rank (%d)", chosen->name.c_str(),
              chosen->speed_rank);
  std::string passed_over;
  for (const PluginReport* report : backends_in_effect(reports))
    if (!report->usable && report->speed_rank > chosen->speed_rank)
      passed_over += (passed_over.empty() ? "" : ", ") + report->name + " (rank " + std::to_string(report->speed_rank) + ")";
  if (!passed_over.empty()) std::printf("; faster but not usable here: %s", passed_over.c_str());
  std::printf("\n");
}

// The GPU backends' precision rule (gpu/precision.hpp) applied to `file`.
void print_gpu_precision(Registry& registry, const std::string& file, const std::string& precision_text) {
  const Precision precision = precision_flag(precision_text);
  const Scene scene = load_scene(file, registry);
  const gpu::WorldChoice world = gpu::choose_world(scene, precision);
  std::printf("GPU kernels (opengl, vulkan) for %s, --precision %s: %s world\n", file.c_str(), precision_text.c_str(),
              world.float_world ? "float" : "double");
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const gpu::ObjectPrecision& p = world.per_object[i];
    std::printf("  object %zu (%s): %s\n", i, scene.objects[i].desc->type_name,
                p.needs_double ? ("double: " + p.reason).c_str() : "float");
  }
}

int run_list(const std::string& scene, const std::string& precision) {
  if (!scene.empty()) precision_flag(precision);  // bad input before the slow scan
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
  print_auto_choice(reports);
  if (!scene.empty()) print_gpu_precision(registry, scene, precision);
  return 0;
}

}  // namespace

Command add_list_command(CLI::App& app) {
  auto scene = std::make_shared<std::string>();
  auto precision = std::make_shared<std::string>("auto");
  CLI::App* sub = app.add_subcommand("list", "List backends and primitive plugins, and whether each can run here");
  sub->add_option("scene", *scene, "A scene: also say which precision the GPU kernels give each of its objects, and why");
  sub->add_option("--precision", *precision, kPrecisionHelp);
  return [scene, precision] { return run_list(*scene, *precision); };
}

}  // namespace prism::cli
