// prism_stability: the numerical stability suite. For every backend and every
// stiff-case family (families.hpp) it writes the scene and the rays, runs
//   <build>/bin/prism trace SCENE -b BACKEND --rays R.csv -o OUT.csv --digits 17 --stats S.json
// and compares each answer with the quad-precision oracle (exact.hpp):
// misclassification outside the ambiguity band, relative t error, normal
// angle, reported point off the surface, and ns per ray (the trace phase:
// `--stats` ms.render over the rays). Every backend that accepts
// `--precision float` (tried once per backend) runs the families a second
// time with it: its float rows. Exit status 1 when a cap (measure.hpp) fails
// or a required backend cannot run, else 0.
//
//   prism_stability [--quick | --full] [--primitive T[,T...]] [--family SUBSTRING]
//                   [-b BACKEND[,BACKEND...]] [--precision auto,float] [--out DIR] [--prism PATH] [--keep] [--list]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "families.hpp"
#include "measure.hpp"
#include "process.hpp"
#include "report.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace prism::stability;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) {
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

struct Options {
  Mode mode = Mode::quick;
  std::vector<std::string> primitives, backends;
  std::vector<std::string> precisions = {"auto", "float"};  // `prism trace --precision` of each pass
  std::string family_filter;
  fs::path out_dir, prism;
  bool keep = false, list = false;
};

void usage(std::FILE* out) {
  std::fprintf(out,
               "usage: prism_stability [--quick | --full] [--primitive T[,T...]] [--family SUBSTRING]\n"
               "                       [-b BACKEND[,BACKEND...]] [--precision auto,float] [--out DIR]\n"
               "                       [--prism PATH] [--keep] [--list]\n"
               "  --quick       one parameter value per family, 48 rays (the default)\n"
               "  --full        the whole parameter sweep, 256 rays per value\n"
               "  --primitive   only these primitive types\n"
               "  --family      only families whose name contains SUBSTRING\n"
               "  -b            these backends (default: every backend `prism list` says is usable);\n"
               "                PRISM_REQUIRE_BACKENDS names backends that must run\n"
               "  --precision   the passes: auto (each backend's own precision) and float (every\n"
               "                backend that accepts `prism trace --precision float`); default both\n"
               "  --out DIR     write DIR/stability.csv, stability.json, stability.svg\n"
               "  --prism PATH  the prism binary (default: <build>/bin/prism)\n"
               "  --keep        keep the scratch folder with every scene, ray file and answer\n"
               "  --list        list the families and their parameters, run nothing\n");
}

Options parse_options(int argc, char** argv) {
  Options o;
  o.prism = fs::path(PRISM_BINARY_DIR) / "bin" / "prism";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--quick")
      o.mode = Mode::quick;
    else if (a == "--full")
      o.mode = Mode::full;
    else if (a == "--primitive")
      for (auto& p : split(value())) o.primitives.push_back(p);
    else if (a == "--family")
      o.family_filter = value();
    else if (a == "-b" || a == "--backend")
      for (auto& b : split(value())) o.backends.push_back(b);
    else if (a == "--precision") {
      o.precisions = split(value());
      for (const auto& p : o.precisions)
        if (p != "auto" && p != "float") throw std::invalid_argument("--precision: '" + p + "' is not auto or float");
    } else if (a == "--out")
      o.out_dir = value();
    else if (a == "--prism")
      o.prism = value();
    else if (a == "--keep")
      o.keep = true;
    else if (a == "--list")
      o.list = true;
    else if (a == "-h" || a == "--help") {
      usage(stdout);
      std::exit(0);
    } else
      throw std::invalid_argument("unknown argument '" + a + "'");
  }
  return o;
}

// `prism list`: backend name -> "" when usable, else why not.
std::map<std::string, std::string> list_backends(const fs::path& prism, const fs::path& scratch) {
  const ProcessResult r = run_process({prism.string(), "list"}, scratch);
  if (!r.exited || r.status != 0) throw std::runtime_error("`prism list` failed: " + r.describe());
  std::map<std::string, std::string> found;
  std::istringstream in(r.out);
  bool in_backends = false;
  for (std::string line; std::getline(in, line);) {
    if (line == "backends:") {
      in_backends = true;
      continue;
    }
    if (!line.empty() && line[0] != ' ') {
      in_backends = false;
      continue;
    }
    if (!in_backends) continue;
    std::istringstream fields(line);
    std::string name;
    fields >> name;
    if (name.empty()) continue;
    if (line.find(" usable: ") != std::string::npos) {
      found[name] = "";
    } else {
      std::string reason = line.substr(line.find(name) + name.size());
      reason.erase(0, reason.find_first_not_of(" "));
      found[name] = reason.empty() ? "not usable here" : reason;
    }
  }
  return found;
}

// One pass of one backend: `flag` is its `--precision` ("auto": none given),
// `precision` what its --stats then says it computed in.
struct BackendRun {
  std::string name, flag, precision;
  std::string key() const { return flag == "auto" ? name : name + " --precision " + flag; }
  std::vector<std::string> precision_args() const {
    return flag == "auto" ? std::vector<std::string>{} : std::vector<std::string>{"--precision", flag};
  }
};

// Whether `backend` accepts `prism trace --precision <flag>`: one ray on a
// case's scene (a refusal is exit status 2, before anything is prepared).
bool accepts_precision(const fs::path& prism, const std::string& backend, const std::string& flag, const Case& c,
                       const fs::path& scratch) {
  const fs::path dir = scratch / ("probe_" + backend + "_" + flag);
  fs::create_directories(dir);
  write_text(dir / "scene.json", scene_json(c.objects).dump(2) + "\n");
  write_text(dir / "rays.csv", rays_csv({c.rays.front()}));
  const ProcessResult r = run_process({prism.string(), "trace", (dir / "scene.json").string(), "-b", backend, "--rays",
                                       (dir / "rays.csv").string(), "-o", (dir / "out.csv").string(), "--precision",
                                       flag},
                                      dir);
  return r.exited && r.status == 0;
}

// The float rows of double-only families over the float caps: what float
// cannot do, reported and not failed.
void print_beyond_float(const std::vector<Summary>& rows) {
  bool first = true;
  for (const Summary& s : rows) {
    if (s.beyond_float.empty()) continue;
    if (first) std::printf("\nDouble-only families in float (reported, not failed):\n");
    first = false;
    std::printf("  %s [%s] on %s (%s):", s.family.c_str(), s.param.c_str(), s.backend.c_str(), s.precision.c_str());
    for (const auto& f : s.beyond_float) std::printf(" %s.", f.c_str());
    std::printf("\n");
  }
}

}  // namespace

int run(int argc, char** argv) {
  const auto start = Clock::now();
  Options opt;
  try {
    opt = parse_options(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism_stability: %s\n", e.what());
    usage(stderr);
    return 2;
  }

  // The families.
  std::vector<Family> families;
  try {
    if (opt.primitives.empty()) {
      families = make_families(opt.mode);
    } else {
      for (const auto& p : opt.primitives) {
        auto more = make_families(opt.mode, p);
        families.insert(families.end(), more.begin(), more.end());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism_stability: %s\n", e.what());
    return 2;
  }
  if (!opt.family_filter.empty())
    std::erase_if(families, [&](const Family& f) { return f.name.find(opt.family_filter) == std::string::npos; });
  if (opt.list) {
    for (const Family& f : families) {
      std::printf("%-26s %s\n", f.name.c_str(), f.description.c_str());
      for (const Case& c : f.cases) std::printf("    %-20s %zu rays\n", c.param.c_str(), c.rays.size());
    }
    return 0;
  }
  if (families.empty()) {
    std::fprintf(stderr, "prism_stability: no family matches\n");
    return 2;
  }

  const fs::path scratch = fs::temp_directory_path() / ("prism_stability_" + std::to_string(getpid()));
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  int status = 0;

  // The backends: the ones asked for, or every usable one; a backend that
  // cannot run is skipped, or fails when PRISM_REQUIRE_BACKENDS names it.
  const std::vector<std::string> required = prism::test::required_backends();
  auto is_required = [&](const std::string& n) {
    return std::find(required.begin(), required.end(), n) != required.end();
  };
  std::map<std::string, std::string> found;
  try {
    found = list_backends(opt.prism, scratch);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism_stability: %s\n", e.what());
    fs::remove_all(scratch);
    return 1;
  }
  std::vector<std::string> wanted = opt.backends;
  if (wanted.empty()) {
    for (const auto& [name, why] : found)
      if (why.empty()) wanted.push_back(name);
    for (const auto& name : required)
      if (std::find(wanted.begin(), wanted.end(), name) == wanted.end()) wanted.push_back(name);
  }
  std::vector<BackendRun> backends;
  std::vector<Skipped> skipped;
  for (const auto& name : wanted) {
    auto it = found.find(name);
    const std::string why = it == found.end() ? "not found by `prism list`" : it->second;
    if (why.empty()) {
      for (const std::string& flag : opt.precisions) {
        if (flag != "auto" && !accepts_precision(opt.prism, name, flag, families.front().cases.front(), scratch)) {
          std::printf("backend %s: no --precision %s pass (it computes in its own precision only)\n", name.c_str(),
                      flag.c_str());
          continue;
        }
        backends.push_back({name, flag, ""});
      }
      continue;
    }
    skipped.push_back({name, why, is_required(name)});
    if (is_required(name)) {
      std::printf("backend %s FAILED: %s (it is in PRISM_REQUIRE_BACKENDS)\n", name.c_str(), why.c_str());
      status = 1;
    } else {
      std::printf("backend %s SKIPPED: %s\n", name.c_str(), why.c_str());
    }
  }

  // Every case: the oracle once, then each backend.
  size_t cases = 0, rays = 0;
  for (const Family& f : families) {
    cases += f.cases.size();
    for (const Case& c : f.cases) rays += c.rays.size();
  }
  std::fprintf(stderr, "prism_stability: %s mode, %zu families, %zu cases, %zu rays, backends:",
               opt.mode == Mode::quick ? "quick" : "full", families.size(), cases, rays);
  for (const auto& b : backends) std::fprintf(stderr, " [%s]", b.key().c_str());
  std::fprintf(stderr, "\n");

  double oracle_s = 0, trace_s = 0;
  std::vector<Summary> rows, sweep;
  std::vector<std::string> errors;
  for (size_t fi = 0; fi < families.size() && !backends.empty(); ++fi) {
    const Family& family = families[fi];
    const auto family_start = Clock::now();
    std::map<std::string, Tally> family_tally;
    std::map<std::string, std::string> family_error;
    for (size_t ci = 0; ci < family.cases.size(); ++ci) {
      const Case& c = family.cases[ci];
      const fs::path dir = scratch / family.name / std::to_string(ci);
      fs::create_directories(dir);
      const fs::path scene = dir / "scene.json", rays_file = dir / "rays.csv";
      write_text(scene, scene_json(c.objects).dump(2) + "\n");
      write_text(rays_file, rays_csv(c.rays));
      const auto oracle_start = Clock::now();
      CaseOracle oracle;
      try {
        oracle = solve_case(c);
      } catch (const std::exception& e) {
        errors.push_back(family.name + " " + c.param + ": " + e.what());
        status = 1;
        continue;
      }
      oracle_s += seconds_since(oracle_start);

      for (BackendRun& b : backends) {
        if (family_error.count(b.key())) continue;
        const std::string file_stem = b.name + "." + b.flag;
        const fs::path out = dir / (file_stem + ".csv"), stats = dir / (file_stem + ".stats.json");
        const auto trace_start = Clock::now();
        std::vector<std::string> command = {opt.prism.string(), "trace",         scene.string(), "-b",
                                            b.name,             "--rays",        rays_file.string(), "-o",
                                            out.string(),       "--digits",      "17",           "--stats",
                                            stats.string()};
        for (const std::string& arg : b.precision_args()) command.push_back(arg);
        const ProcessResult r = run_process(command, dir);
        trace_s += seconds_since(trace_start);
        Tally tally;
        try {
          if (!r.exited || r.status != 0) throw std::runtime_error("prism trace failed (" + r.describe() + ")");
          const auto stats_json = nlohmann::json::parse(read_text(stats));
          const std::string precision = stats_json.at("info").value("precision", "");
          if (b.precision.empty()) b.precision = precision;
          tally.render_ms = stats_json.at("ms").at("render").get<double>();
          compare(family.name, c, oracle, parse_answers(read_text(out)), b.name, tally);
        } catch (const std::exception& e) {
          family_error[b.key()] = c.param + ": " + e.what() + "\n    $ " + r.command;
          continue;
        }
        sweep.push_back(
            summarize(family.name, c.param, family.primitive, b.name, b.precision, tally, family.double_only));
        Tally& ft = family_tally[b.key()];
        ft.rays += tally.rays;
        ft.hits += tally.hits;
        ft.ambiguous += tally.ambiguous;
        ft.misclassified += tally.misclassified;
        ft.false_miss += tally.false_miss;
        ft.false_hit += tally.false_hit;
        ft.wrong_object += tally.wrong_object;
        ft.ambiguous_disagree += tally.ambiguous_disagree;
        ft.render_ms += tally.render_ms;
        for (auto [to, from] : {std::pair{&ft.t_rel, &tally.t_rel},
                                {&ft.normal_angle, &tally.normal_angle},
                                {&ft.point_distance, &tally.point_distance},
                                {&ft.t_floor, &tally.t_floor},
                                {&ft.normal_floor, &tally.normal_floor}})
          to->insert(to->end(), from->begin(), from->end());
        for (auto [to, from] : {std::pair{&ft.worst_misclassified, &tally.worst_misclassified},
                                {&ft.worst_t, &tally.worst_t},
                                {&ft.worst_normal, &tally.worst_normal},
                                {&ft.worst_point, &tally.worst_point}}) {
          to->insert(to->end(), from->begin(), from->end());
          std::stable_sort(to->begin(), to->end(),
                           [](const Example& x, const Example& y) { return x.severity > y.severity; });
          if (to->size() > 3) to->resize(3);
        }
      }
    }
    std::string line;
    for (const BackendRun& b : backends) {
      if (auto e = family_error.find(b.key()); e != family_error.end()) {
        errors.push_back(family.name + " on " + b.key() + ": " + e->second);
        status = 1;
        continue;
      }
      if (!family_tally.count(b.key())) continue;
      Summary s = summarize(family.name, opt.mode == Mode::quick ? family.cases[0].param : "all", family.primitive,
                            b.name, b.precision, family_tally[b.key()], family.double_only);
      if (!s.failures.empty()) status = 1;
      line += " " + b.name + (b.flag == "auto" ? "" : "/" + b.flag) + " " + verdict_word(s);
      rows.push_back(std::move(s));
    }
    std::fprintf(stderr, "  [%zu/%zu] %-26s %.1f s:%s\n", fi + 1, families.size(), family.name.c_str(),
                 seconds_since(family_start), line.c_str());
  }
  const double total_s = seconds_since(start);

  // Report.
  if (!rows.empty()) {
    std::printf("\nStability suite (%s): one row per family x backend\n",
                opt.mode == Mode::quick ? "quick" : "full, pooled over each sweep");
    print_table(stdout, rows);
  }
  if (opt.mode == Mode::full && !sweep.empty()) {
    std::printf("\nPer parameter value:\n");
    print_table(stdout, sweep);
  }
  // The caps hold per family (pooled over its sweep) and, in full mode, per
  // parameter value too (stricter: a value can fail where the pool passes).
  // The failures are shown per value, where the worst rays come from.
  const std::vector<Summary>& detail = opt.mode == Mode::full ? sweep : rows;
  int failing = 0;
  for (const Summary& s : detail) {
    if (s.failures.empty()) continue;
    ++failing;
    status = 1;
    std::printf("\nFAIL %s [%s] on %s (%s):\n", s.family.c_str(), s.param.c_str(), s.backend.c_str(),
                s.precision.c_str());
    for (const auto& f : s.failures) std::printf("  %s\n", f.c_str());
    for (const Example& e : s.worst) {
      const bool relevant =
          (e.what.find("false") == 0 || e.what.find("wrong") == 0) ||
          std::any_of(s.failures.begin(), s.failures.end(), [&](const std::string& f) {
            return (f.find("t error") != std::string::npos && e.what.find("t error") != std::string::npos) ||
                   (f.find("normal") != std::string::npos && e.what.find("normal") == 0) ||
                   (f.find("point") != std::string::npos && e.what.find("point") == 0);
          });
      if (!relevant) continue;
      std::printf("    %s [%s]: ray o=(%.17g, %.17g, %.17g) d=(%.17g, %.17g, %.17g) tmin=%.17g\n", e.what.c_str(),
                  e.param.c_str(), e.ray.origin[0], e.ray.origin[1], e.ray.origin[2], e.ray.dir[0], e.ray.dir[1],
                  e.ray.dir[2], e.ray.tmin);
      std::printf("      oracle:  %s\n      %-8s %s\n", e.oracle.c_str(), (e.backend + ":").c_str(),
                  e.backend_answer.c_str());
    }
  }
  print_beyond_float(detail);
  for (const auto& e : errors) std::printf("\nERROR %s\n", e.c_str());

  if (!opt.out_dir.empty()) {
    try {
      fs::create_directories(opt.out_dir);
      write_csv(opt.out_dir / "stability.csv", rows);
      nlohmann::ordered_json meta;
      meta["mode"] = opt.mode == Mode::quick ? "quick" : "full";
      meta["prism"] = opt.prism.string();
      meta["seconds"] = {{"total", total_s}, {"oracle", oracle_s}, {"trace", trace_s}};
      meta["families"] = families.size();
      meta["cases"] = cases;
      meta["rays_per_backend"] = rays;
      meta["backends"] = nlohmann::ordered_json::array();
      for (const auto& b : backends)
        meta["backends"].push_back({{"name", b.name},
                                    {"precision_flag", b.flag},
                                    {"precision", b.precision},
                                    {"caps", [&] {
                                       const Caps c = caps_for(b.precision);
                                       nlohmann::ordered_json j;
                                       j["misclassified_fraction"] = c.misclassified_fraction;
                                       j["t_rel_p99"] = c.t_rel_p99;
                                       j["normal_p99"] =
                                           c.normal_p99 >= 0 ? nlohmann::ordered_json(c.normal_p99) : nullptr;
                                       j["point_p99"] =
                                           c.point_p99 >= 0 ? nlohmann::ordered_json(c.point_p99) : nullptr;
                                       return j;
                                     }()}});
      meta["skipped"] = nlohmann::ordered_json::array();
      for (const auto& s : skipped)
        meta["skipped"].push_back({{"backend", s.backend}, {"reason", s.reason}, {"required", s.required}});
      meta["errors"] = errors;
      write_json(opt.out_dir / "stability.json", meta, rows, opt.mode == Mode::full ? sweep : std::vector<Summary>{});
      if (opt.mode == Mode::full) write_csv(opt.out_dir / "stability_sweep.csv", sweep);
      write_svg(opt.out_dir / "stability.svg", rows,
                std::string("Prism stability suite (") + (opt.mode == Mode::quick ? "quick" : "full") +
                    "): p99 relative t error against time per ray");
      std::printf("\nwrote %s/stability.{csv,json,svg}\n", opt.out_dir.c_str());
    } catch (const std::exception& e) {
      std::printf("ERROR writing the report: %s\n", e.what());
      status = 1;
    }
  }

  std::printf("\n%zu %s, %d failing; %zu errors; %.1f s (oracle %.1f s, prism trace %.1f s)\n", detail.size(),
              opt.mode == Mode::full ? "family x value x backend rows" : "family x backend rows", failing,
              errors.size(), total_s, oracle_s, trace_s);
  if (opt.keep)
    std::printf("scratch folder (scenes, rays, answers): %s\n", scratch.c_str());
  else
    fs::remove_all(scratch);
  if (backends.empty() && status == 0) std::printf("no backend ran\n");
  return status;
}

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism_stability: %s\n", e.what());
    return 1;
  }
}
