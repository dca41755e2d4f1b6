// prism bench SCENE [-b BACKENDS] [--frames N] [--warmup N] [--width W --height H --spp S --max-depth D]
//                   [--orbit DEGREES] [--no-check] [--json F] [--profile] [--precision auto|float|double]
// Frame time, FPS and rays per second per backend, the one-off costs apart,
// and the memory held while rendering (apps/prism/bench/bench_run.hpp).
// Exit 1 when a backend's last frame differs from a fresh render of its camera.
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bench/bench_run.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"

namespace prism::cli {

namespace {

struct BenchArgs {
  std::string scene, json, precision = "auto";
  std::vector<std::string> backends;
  std::optional<int> width, height, spp, max_depth;
  int frames = 20, warmup = 2;
  double orbit = 0.25;
  bool no_check = false;
  bool profile = false;
};

double mib(int64_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

std::vector<std::string> backends_to_run(Registry& registry, const BenchArgs& args) {
  if (!args.backends.empty()) {
    for (const std::string& name : args.backends) registry.backend(name);  // InputError when unknown
    return args.backends;
  }
  // Every backend found, less those that do not load or crash in a probe of their own.
  std::vector<std::string> names;
  for (const auto& [name, probe] : registry.probe_backends(registry.backend_names_found())) {
    if (probe.error.empty())
      names.push_back(name);
    else
      std::fprintf(stderr, "prism bench: skipping backend '%s': %s\n", name.c_str(), probe.error.c_str());
  }
  return names;
}

// Where a frame's time goes: each phase's share of the render threads' time.
void print_profile(const bench::Result& r) {
  if (r.png_write_ms == 0 && r.exr_write_ms == 0) return;  // not profiled
  if (r.profile_ms.empty()) {
    std::printf("  profile: this backend does not time its phases\n");
  } else {
    const auto on_device = [](const std::string& phase) { return phase.starts_with(ms_key::kDevicePhasePrefix); };
    double total = 0;
    for (const auto& [phase, ms] : r.profile_ms)
      if (!on_device(phase)) total += ms;
    std::printf("  profile, ms per frame summed over threads (%.1f in all):", total);
    for (const auto& [phase, ms] : r.profile_ms)
      if (!on_device(phase)) std::printf(" %s %.1f (%.0f%%)", phase.c_str(), ms, 100 * ms / total);
    for (const auto& [phase, ms] : r.profile_ms)
      if (on_device(phase)) std::printf("; %s %.1f (within the above)", phase.c_str(), ms);
    std::printf("\n");
  }
  std::printf("  image write (last frame): png %.1f ms, exr %.1f ms\n", r.png_write_ms, r.exr_write_ms);
}

void print_result(const bench::Result& r) {
  if (!r.skipped.empty()) {
    std::printf("%s: skipped (%s)\n", r.backend.c_str(), r.skipped.c_str());
    return;
  }
  std::printf("%s (%s): %zu frames, median %.1f ms (p10 %.1f, p90 %.1f, min %.1f, max %.1f), %.1f FPS\n",
              r.backend.c_str(), r.device.c_str(), r.frame_ms.size(), r.median_ms(), r.percentile_ms(10),
              r.percentile_ms(90), r.percentile_ms(0), r.percentile_ms(100), r.fps());
  std::printf("  processor time: %.1f ms per frame, all threads\n", r.cpu_ms_per_frame);
  if (!r.precision.empty()) std::printf("  precision: %s\n", r.precision.c_str());
  std::printf("  rays: %.2f M/s total", r.rays_per_second() / 1e6);
  const double seconds = r.rays > 0 ? double(r.rays) / r.rays_per_second() : 0;
  for (const auto& [kind, count] : r.rays_by_kind)
    std::printf(", %s %.2f M/s", kind.c_str(), seconds > 0 ? double(count) / seconds / 1e6 : 0.0);
  std::printf(" (%.0f rays per frame)\n", double(r.rays) / double(std::max<size_t>(1, r.frame_ms.size())));
  std::printf("  one-off: start %.0f ms, build %.1f ms, kernel compile %.0f ms, first frame %.1f ms\n", r.start_ms,
              r.build_ms, r.compile_ms, r.first_frame_ms);
  const bench::Memory& m = r.memory;
  std::printf("  memory: %.1f MiB peak while rendering over %.1f MiB loaded: +%.1f MiB", mib(m.peak_bytes),
              mib(m.loaded_bytes), mib(m.growth()));
  if (m.bound() >= 0)
    std::printf(" (bound 4 x (scene %.2f MiB + frame %.2f MiB) = %.1f MiB: %s)", mib(m.scene_bytes),
                mib(m.frame_bytes), mib(m.bound()), m.growth() <= m.bound() ? "within" : "OVER");
  std::printf("\n");
  print_profile(r);
  if (r.checked) {
    if (r.check_max_difference == 0)
      std::printf("  check: the last frame equals a fresh render of its camera, bit for bit\n");
    else
      std::printf("  check: FAILED, the last frame differs from a fresh render of its camera by up to %g\n",
                  r.check_max_difference);
  }
}

nlohmann::ordered_json to_json(const bench::Result& r) {
  nlohmann::ordered_json j;
  j["backend"] = r.backend;
  if (!r.skipped.empty()) {
    j["skipped"] = r.skipped;
    return j;
  }
  j["device"] = r.device;
  j["precision"] = r.precision;
  j["frames"] = r.frame_ms.size();
  j["frame_ms"] = {{"median", r.median_ms()}, {"p10", r.percentile_ms(10)}, {"p90", r.percentile_ms(90)},
                   {"min", r.percentile_ms(0)}, {"max", r.percentile_ms(100)}, {"all", r.frame_ms}};
  j["fps"] = r.fps();
  j["cpu_ms_per_frame"] = r.cpu_ms_per_frame;
  j["rays"] = r.rays;
  j["rays_by_kind"] = r.rays_by_kind;
  j["rays_per_second"] = r.rays_per_second();
  j["one_off_ms"] = {{"start", r.start_ms}, {"build", r.build_ms}, {"compile", r.compile_ms},
                     {"first_frame", r.first_frame_ms}};
  const bench::Memory& m = r.memory;
  j["memory_bytes"] = {{"loaded", m.loaded_bytes}, {"peak", m.peak_bytes}, {"growth", m.growth()},
                       {"scene", m.scene_bytes}, {"frame", m.frame_bytes}, {"bound", m.bound()}};
  if (r.checked) j["check_max_difference"] = r.check_max_difference;
  if (!r.profile_ms.empty()) j["profile_ms"] = r.profile_ms;
  if (r.png_write_ms > 0) j["image_write_ms"] = {{"png", r.png_write_ms}, {"exr", r.exr_write_ms}};
  return j;
}

int run_bench(const BenchArgs& args) {
  show_status_notices();
  if (!args.json.empty()) check_output_path(args.json, {".json"});
  if (args.frames < 1) throw InputError("--frames must be >= 1, got " + std::to_string(args.frames));
  if (args.warmup < 1) throw InputError("--warmup must be >= 1, got " + std::to_string(args.warmup));
  bench::check_orbit_degrees(args.orbit);
  PhaseTimer timer;
  Registry registry;
  Scene scene = load_scene(args.scene, registry);
  const double load_ms = timer.lap();
  bench::Options options;
  options.settings.image = image_with_overrides(scene, args);
  options.frames = args.frames;
  options.warmup = args.warmup;
  options.orbit_degrees = args.orbit;
  options.check = !args.no_check;
  options.profile = args.profile;
  options.settings.profile = args.profile;
  options.precision = precision_flag(args.precision);
  const std::vector<std::string> names = backends_to_run(registry, args);

  const ImageSettings& image = options.settings.image;
  std::printf("%s at %dx%d, %d spp, depth %d: %d frames after %d warm-up, camera orbiting %g deg per frame; "
              "scene load %.0f ms\n",
              args.scene.c_str(), image.width, image.height, image.spp, image.max_depth, args.frames, args.warmup,
              args.orbit, load_ms);
  std::fflush(stdout);
  nlohmann::ordered_json report;
  report["scene"] = args.scene;
  report["image"] = {{"width", image.width}, {"height", image.height}, {"spp", image.spp}, {"max_depth", image.max_depth}};
  report["frames"] = args.frames;
  report["warmup"] = args.warmup;
  report["orbit_degrees"] = args.orbit;
  report["load_ms"] = load_ms;
  report["backends"] = nlohmann::ordered_json::array();
  bool all_checks_pass = true;
  for (const std::string& name : names) {
    const bench::Result result = bench::run_backend(registry, scene, name, options);
    print_result(result);
    std::fflush(stdout);
    report["backends"].push_back(to_json(result));
    all_checks_pass = all_checks_pass && (!result.checked || result.check_max_difference == 0);
  }
  if (!args.json.empty()) write_text_file_atomically(args.json, report.dump(2) + "\n");
  return all_checks_pass ? 0 : 1;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* sub = app.add_subcommand(
      "bench", "Frame time, FPS, rays per second and memory per backend, as an interactive viewer renders");
  sub->add_option("scene", args->scene, "Scene file (JSON)")->required();
  sub->add_option("-b,--backend", args->backends, "Backends to measure (default: every one found)")->delimiter(',');
  sub->add_option("--frames", args->frames, "Measured frames per backend (default 20)");
  sub->add_option("--warmup", args->warmup, "Frames before them, the first compiling any kernel (default 2)");
  sub->add_option("--width", args->width, "Image width in pixels (1..16384)");
  sub->add_option("--height", args->height, "Image height in pixels (1..16384)");
  sub->add_option("--spp", args->spp, "Samples per pixel (1..4096)");
  sub->add_option("--max-depth", args->max_depth, "Surface interactions per camera sample (1..64)");
  sub->add_option("--orbit", args->orbit, "Camera yaw per frame about the viewer's orbit target, degrees (0.25)");
  sub->add_flag("--no-check", args->no_check, "Skip comparing the last frame with a fresh render of its camera");
  sub->add_option("--json", args->json, "Write the results to this JSON file");
  sub->add_option("--precision", args->precision, kPrecisionHelp);
  sub->add_flag("--profile", args->profile,
                "Print where a frame's time goes: camera rays, secondary rays, shadow rays, shading, image write");
  return [args] { return run_bench(*args); };
}

}  // namespace prism::cli
