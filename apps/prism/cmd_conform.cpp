// prism conform [SCENES...] [-b BACKENDS] [--report DIR] [--size WxH] [--sweep] [--stability DIR]
// Every backend's image of every scene against the reference backend's at
// the same settings; exit 1 when any backend fails, 0 otherwise.
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "conform/conform.hpp"
#include "prism/errors.hpp"

namespace prism::cli {

namespace {

namespace fs = std::filesystem;

struct ConformArgs {
  std::vector<std::string> scenes;
  std::vector<std::string> backends;
  std::string report, references = "tests/conformance/references", stability;
  std::string size, precision = "auto";
  bool sweep = false;
  int sweep_max_spp = 16;
};

std::vector<std::string> required_backends() {
  std::vector<std::string> names;
  const char* env = std::getenv("PRISM_REQUIRE_BACKENDS");
  std::istringstream in(env ? env : "");
  for (std::string name; std::getline(in, name, ',');)
    if (!name.empty()) names.push_back(name);
  return names;
}

int run_conform(const ConformArgs& args) {
  conform::Options options;
  for (const std::string& scene : args.scenes) options.scenes.emplace_back(scene);
  if (options.scenes.empty()) options.scenes.emplace_back("scenes/conformance");
  options.backends = args.backends;
  options.required = required_backends();
  options.sweep = args.sweep;
  options.sweep_max_spp = args.sweep_max_spp;
  options.references = args.references;
  options.precision = precision_flag(args.precision);
  if (!args.size.empty()) options.size = conform::parse_size(args.size);
  if (!args.report.empty()) fs::create_directories(args.report);
  std::optional<conform::StabilityResults> stability;
  if (!args.stability.empty()) stability = conform::read_stability_results(args.stability);
  Registry registry;
  conform::RunResult run = conform::run_conformance(registry, options, [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  });
  run.stability = stability;
  if (!args.report.empty()) {
    conform::write_report(run, args.report);
    std::printf("report: %s\n", (fs::path(args.report) / "index.html").string().c_str());
  }
  std::printf("%s\n", conform::fastest_line(conform::summarize(run)).c_str());
  std::printf("%s: %zu scene(s) in %.1f s\n", run.passed() ? "PASSED" : "FAILED", run.scenes.size(), run.wall_ms / 1000.0);
  return run.passed() ? 0 : 1;
}

}  // namespace

Command add_conform_command(CLI::App& app) {
  auto args = std::make_shared<ConformArgs>();
  CLI::App* sub = app.add_subcommand(
      "conform", "Compare every backend with the reference backend on conformance scenes (exit 1 on any failure)");
  sub->add_option("scenes", args->scenes, "Scene files or folders (default scenes/conformance)");
  sub->add_option("-b,--backend", args->backends, "Backends to test, comma-separated (default: every one found)")
      ->delimiter(',');
  sub->add_option("--report", args->report, "Write index.html, results.json and results.csv to this folder");
  sub->add_option("--size", args->size, "Render every scene at WIDTHxHEIGHT (e.g. 320x180) instead of its own size");
  sub->add_flag("--sweep", args->sweep, "Also measure error against time over spp 1, 2, 4, ...");
  sub->add_option("--sweep-max-spp", args->sweep_max_spp, "Largest spp of the sweep (default 16)")
      ->check(CLI::Range(1, 4096));
  sub->add_option("--references", args->references,
                  "Folder of the stored high-spp <scene>.exr images (default tests/conformance/references)");
  sub->add_option("--stability", args->stability,
                  "Show the stability suite's results from this folder (prism_stability --out) in the report");
  sub->add_option("--precision", args->precision,
                  std::string(kPrecisionHelp) + "; the backends tested, not the reference they are judged against");
  return [args] { return run_conform(*args); };
}

}  // namespace prism::cli
