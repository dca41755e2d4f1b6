// prism trace SCENE [-b BACKEND] --rays IN.csv -o OUT.csv [--digits N] [--stats F.json] [--threads N]
//   [--precision auto|float|double] [-v]
// One line per ray in: ox,oy,oz,dx,dy,dz[,tmin]; one line per ray out:
// t,object,nx,ny,nz of the closest hit with t > tmin (a miss: inf,-1,0,0,0).
#include <cstdio>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/ray_csv.hpp"
#include "prism/scene_loader.hpp"
#include "prism/stats_keys.hpp"

namespace prism::cli {

namespace {

struct TraceArgs {
  std::string scene, backend = "auto", rays, output, stats, precision = "auto";
  int digits = 9;
  std::optional<int> threads;
  bool verbose = false;
};

std::string format_results(const std::vector<TraceResult>& results, int digits) {
  std::string out;
  char line[256];
  for (const auto& r : results) {
    if (r.id == -1) {
      out += "inf,-1,0,0,0\n";
      continue;
    }
    std::snprintf(line, sizeof line, "%.*g,%d,%.*g,%.*g,%.*g\n", digits, r.t, r.id, digits, r.normal.x, digits,
                  r.normal.y, digits, r.normal.z);
    out += line;
  }
  return out;
}

int run_trace(const TraceArgs& args) {
  check_output_path(args.output, {".csv"});
  if (!args.stats.empty()) check_output_path(args.stats, {".json"});
  const Precision precision = precision_flag(args.precision);
  const auto threads = limit_threads(args.threads);
  PhaseTimer timer;
  std::map<std::string, double> ms;
  // trace has no bar: each step, the tracing too, shows as a phase line on a terminal.
  constexpr bool kShowSteps = true;
  Registry registry;
  Scene scene = with_phase_line("loading " + scene_name_for_phase(args.scene), kShowSteps,
                                [&] { return load_scene(args.scene, registry); });
  std::vector<TraceQuery> rays = with_phase_line("reading " + args.rays, kShowSteps, [&] { return read_ray_csv(args.rays); });
  ms["load"] = timer.lap();
  BackendChoice choice = open_backend_showing_it(registry, args.backend, kShowSteps, precision);
  prepare_showing_it(choice, scene, kShowSteps);
  ms[ms_key::kBuild] = timer.lap();
  const std::string tracing = choice.name + ": tracing " + std::to_string(rays.size()) + (rays.size() == 1 ? " ray" : " rays");
  auto results = with_phase_line(tracing, kShowSteps,
                                 [&] { return choice.backend->trace(rays); });
  ms[ms_key::kRender] = timer.lap();
  // Both complete on disk before either replaces its older file.
  StagedFile output = stage_text_file(args.output, format_results(results, args.digits));
  std::optional<StagedFile> stats;
  if (!args.stats.empty()) stats.emplace(stage_stats(args.stats, choice, scene, timer, ms));
  output.commit();
  if (stats) stats->commit();
  if (args.verbose) std::fprintf(stderr, "phases: %s\n", phase_times_line(phase_times(choice, timer, ms)).c_str());
  return 0;
}

}  // namespace

Command add_trace_command(CLI::App& app) {
  auto args = std::make_shared<TraceArgs>();
  CLI::App* sub = app.add_subcommand("trace", "Closest hits of a batch of rays (CSV in, CSV out)");
  sub->add_option("scene", args->scene, "Scene file (JSON)")->required();
  sub->add_option("-b,--backend", args->backend,
                  "Backend name, or auto: the fastest usable here (default auto; `prism list` says which)");
  sub->add_option("--rays", args->rays, "Rays: ox,oy,oz,dx,dy,dz[,tmin] per line")->required();
  sub->add_option("-o,--output", args->output, "Output CSV: t,object,nx,ny,nz per ray")->required();
  sub->add_option("--digits", args->digits, "Significant digits, 1 to 17 (default 9)")->check(CLI::Range(1, 17));
  sub->add_option("--stats", args->stats, "Write run statistics to this JSON file");
  sub->add_option("--threads", args->threads, "Threads of the CPU backends, at least 1 (default: one per core)");
  sub->add_option("--precision", args->precision, kPrecisionHelp);
  sub->add_flag("-v,--verbose", args->verbose, "Print the phase times --stats writes");
  return [args] { return run_trace(*args); };
}

}  // namespace prism::cli
