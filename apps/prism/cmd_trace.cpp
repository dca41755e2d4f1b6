// prism trace SCENE -b BACKEND --rays IN.csv -o OUT.csv [--digits N] [--stats F.json]
// One line per ray in: ox,oy,oz,dx,dy,dz[,tmin]; one line per ray out:
// t,object,nx,ny,nz of the closest hit with t > tmin (a miss: inf,-1,0,0,0).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/scene_loader.hpp"

namespace prism::cli {

namespace {

struct TraceArgs {
  std::string scene, backend = "auto", rays, output, stats;
  int digits = 9;
};

std::vector<double> parse_fields(const std::string& line, const std::string& where) {
  std::vector<double> values;
  std::stringstream fields(line);
  std::string field;
  while (std::getline(fields, field, ',')) {
    const char* begin = field.c_str();
    char* end = nullptr;
    double v = std::strtod(begin, &end);
    while (end && (*end == ' ' || *end == '\t' || *end == '\r')) ++end;
    if (end == begin || *end != '\0') throw InputError(where + ": '" + field + "' is not a number");
    if (!std::isfinite(v)) throw InputError(where + ": '" + field + "' is not a finite number");
    values.push_back(v);
  }
  if (!line.empty() && line.back() == ',') throw InputError(where + ": empty field at the end");
  if (values.size() != 6 && values.size() != 7)
    throw InputError(where + ": expected ox,oy,oz,dx,dy,dz[,tmin], got " + std::to_string(values.size()) + " fields");
  return values;
}

std::vector<TraceQuery> read_rays(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open ray file");
  std::vector<TraceQuery> rays;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;  // blank lines carry no ray
    if (number == 1 && line.rfind("ox", 0) == 0) continue;              // the optional header
    const std::string where = file + ":" + std::to_string(number);
    auto v = parse_fields(line, where);
    glm::dvec3 dir{v[3], v[4], v[5]};
    double length = glm::length(dir);
    if (!(length > 0) || !std::isfinite(length)) throw InputError(where + ": the direction is zero");
    rays.push_back({{v[0], v[1], v[2]}, dir / length, v.size() == 7 ? v[6] : 0.0});
  }
  if (in.bad()) throw InputError(file + ": cannot read ray file");
  return rays;
}

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
  PhaseTimer timer;
  std::map<std::string, double> ms;
  Registry registry;
  Scene scene = load_scene(args.scene, registry);
  std::vector<TraceQuery> rays = read_rays(args.rays);
  ms["load"] = timer.lap();
  BackendChoice choice = open_backend(registry, args.backend);
  choice.backend->prepare(scene);
  ms["build"] = timer.lap();
  auto results = choice.backend->trace(rays);
  ms["render"] = timer.lap();
  write_text_file_atomically(args.output, format_results(results, args.digits));
  if (!args.stats.empty()) write_stats(args.stats, choice, scene, timer, ms);
  return 0;
}

}  // namespace

Command add_trace_command(CLI::App& app) {
  auto args = std::make_shared<TraceArgs>();
  CLI::App* sub = app.add_subcommand("trace", "Closest hits of a batch of rays (CSV in, CSV out)");
  sub->add_option("scene", args->scene, "Scene file (JSON)")->required();
  sub->add_option("-b,--backend", args->backend, "Backend name, or auto");
  sub->add_option("--rays", args->rays, "Rays: ox,oy,oz,dx,dy,dz[,tmin] per line")->required();
  sub->add_option("-o,--output", args->output, "Output CSV: t,object,nx,ny,nz per ray")->required();
  sub->add_option("--digits", args->digits, "Significant digits (1..17)")->check(CLI::Range(1, 17));
  sub->add_option("--stats", args->stats, "Write run statistics to this JSON file");
  return [args] { return run_trace(*args); };
}

}  // namespace prism::cli
