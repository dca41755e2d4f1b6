// prism render SCENE [-b BACKEND] -o OUT.(png|exr|jpg|tif|hdr|-) [overrides] [--aov id,path,depth,normal,albedo] [--stats F.json]
//   [--frames N [--orbit DEG] | --cameras FILE] [--camera-position X,Y,Z --look-at X,Y,Z] [--fov DEG]
//   [--threads N] [--precision auto|float|double] [-q | -v] [--mpi [--tile N]]
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "frames.hpp"
#include "mpi/mpi_render.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/scene_loader.hpp"
#include "render_camera.hpp"

namespace prism::cli {

namespace {

constexpr const char* kStdout = "-";  // -o -: PNG to standard output

struct RenderArgs {
  std::string scene, backend = "auto", output, stats, cameras, precision = "auto";
  std::optional<int> width, height, spp, max_depth, threads;
  std::vector<std::string> aov;
  int frames = 0;
  double orbit = 360.0;
  CameraFlags camera;
  bool quiet = false, verbose = false;
  bool mpi = false;
  int tile = 64;
};

RenderSettings settings_for(const Scene& scene, const RenderArgs& args) {
  RenderSettings settings;
  settings.image = image_with_overrides(scene, args);
  for (const auto& aov : args.aov) {
    if (aov == "id") settings.aov_id = true;
    else if (aov == "path") settings.aov_path = true;
    else if (aov == "depth") settings.aov_depth = true;
    else if (aov == "normal") settings.aov_normal = true;
    else if (aov == "albedo") settings.aov_albedo = true;
    else throw InputError("--aov: unknown channel '" + aov + "' (expected id, path, depth, normal or albedo)");
  }
  return settings;
}

bool to_stdout(const RenderArgs& args) { return args.output == kStdout; }

void check_stdout_output(const RenderArgs& args) {
  if (args.frames > 0 || !args.cameras.empty())
    throw InputError("-o -: standard output takes one image, not a sequence (--frames, --cameras)");
  if (!args.aov.empty()) throw InputError("--aov needs an .exr output (-o - writes PNG)");
  if (args.mpi) throw InputError("-o -: not with --mpi (give a file name)");
  if (::isatty(STDOUT_FILENO))
    throw InputError("-o -: standard output is a terminal (redirect it to a file or a program)");
}

// Everything about the command line that can be wrong, found before anything is loaded.
void check_arguments(const RenderArgs& args) {
  if (args.quiet && args.verbose) throw InputError("-q and -v: give one or the other");
  check_thread_count(args.threads);
  if (precision_flag(args.precision) != Precision::automatic && args.mpi)
    throw InputError("--precision and --mpi: the ranks choose their backend's precision (give one or the other)");
  check_camera_flags(args.camera);
  if (!args.camera.position.empty() && !args.cameras.empty())
    throw InputError("--camera-position and --cameras: give one or the other");
  if (to_stdout(args)) return check_stdout_output(args);
  check_output_path(args.output, image_output_extensions());
  if (!args.aov.empty() && std::filesystem::path(args.output).extension() != ".exr")
    throw InputError("--aov needs an .exr output (PNG has no extra channels)");
}

void check_outputs(const RenderArgs& args) {
  check_arguments(args);
  if (!args.stats.empty()) check_output_path(args.stats, {".json"});
}

// What the run wrote, for the summary line: "out.png", "24 frames out_0000.png to out_0023.png".
std::string outputs_written(const RenderArgs& args, const FramePlan& plan) {
  if (to_stdout(args)) return "PNG to standard output";
  if (plan.outputs.size() == 1) return plan.outputs.front().string();
  return std::to_string(plan.outputs.size()) + " frames " + plan.outputs.front().string() + " to " +
         plan.outputs.back().string();
}

// "wrote out.png: embree, 640x360, 4 spp, 1.7 s, 7.0 Mrays/s": the render
// time and ray rate over all frames (the rate where the backend counts rays).
void print_summary(const RenderArgs& args, const FramePlan& plan, const std::string& backend,
                   const RenderSettings& settings, double render_ms, uint64_t rays) {
  std::string line = "wrote " + outputs_written(args, plan) + ": " + backend + ", " +
                     std::to_string(settings.image.width) + "x" + std::to_string(settings.image.height) + ", " +
                     std::to_string(settings.image.spp) + " spp, " + format_duration(render_ms);
  if (rays > 0 && render_ms > 0) line += ", " + format_ray_rate(double(rays) / (render_ms / 1000.0));
  std::fprintf(stderr, "%s\n", line.c_str());
}

// One image, or each frame of a camera path, from one prepared backend.
int run_render(const RenderArgs& args) {
  check_outputs(args);
  if (!args.quiet) show_status_notices();
  const auto threads = limit_threads(args.threads);
  PhaseTimer timer;
  std::map<std::string, double> ms;
  const bool show_steps = !args.quiet;
  Registry registry;
  Scene scene = with_phase_line("loading " + scene_name_for_phase(args.scene), show_steps,
                                [&] { return load_scene(args.scene, registry); });
  write_warnings(scene, std::cerr);
  scene.camera = camera_from_flags(args.camera, scene.camera);
  RenderSettings settings = settings_for(scene, args);
  const FramePlan plan = plan_frames(scene, args.output, args.frames, args.orbit, args.cameras);
  ms["load"] = timer.lap();
  BackendChoice choice = open_backend_showing_it(registry, args.backend, show_steps, precision_flag(args.precision));
  prepare_showing_it(choice, scene, show_steps);
  ms["build"] = timer.lap();
  std::optional<StagedFile> last;
  std::optional<Image> for_stdout;
  ProgressLabel label{0, int(plan.cameras.size()), 0.0};
  for (size_t f = 0; f < plan.cameras.size(); ++f) {
    if (last) last->commit();
    settings.camera = plan.cameras[f];
    label.frame = int(f);
    if (!args.quiet) show_progress_bar(settings, label);
    Image image = choice.backend->render(settings);
    finish_progress_bar();
    ms["render"] += timer.lap();
    // The rate so far, for the next frame's bar.
    label.rays_per_second = double(choice.backend->stats().rays) / (ms["render"] / 1000.0);
    if (to_stdout(args)) for_stdout.emplace(std::move(image));
    else last.emplace(stage_image(image, plan.outputs[f]));
  }
  // The last image and the statistics are both complete on disk before
  // either replaces its older file: failing to write one keeps both.
  std::optional<StagedFile> stats;
  if (!args.stats.empty()) stats.emplace(stage_stats(args.stats, choice, scene, timer, ms));
  if (last) last->commit();
  if (for_stdout) write_png_to(*for_stdout, STDOUT_FILENO, "standard output");
  if (stats) stats->commit();
  if (args.verbose) {
    std::fprintf(stderr, "threads: %zu\n", thread_limit());
    std::fprintf(stderr, "phases: %s\n", phase_times_line(phase_times(choice, timer, ms)).c_str());
  }
  if (!args.quiet) print_summary(args, plan, choice.name, settings, ms["render"], choice.backend->stats().rays);
  return 0;
}

// libprism_mpi.so, beside libprism_core.so (lib/ of the build or install tree).
PrismMpiRenderFn load_mpi_module() {
  const std::filesystem::path file = Registry::core_library_folder() / "libprism_mpi.so";
  std::string error;
  static std::shared_ptr<SharedLibrary> module;  // kept loaded until exit
  module = SharedLibrary::open(file, error);
  if (!module)
    throw InputError("--mpi: this build of Prism has no MPI support (" + error +
                     "); install libopenmpi-dev and openmpi-bin and configure again");
  auto entry = reinterpret_cast<PrismMpiRenderFn>(module->symbol(PRISM_MPI_RENDER_SYMBOL));
  if (!entry) throw RuntimeError(file.string() + " has no " + PRISM_MPI_RENDER_SYMBOL);
  return entry;
}

// --threads N holds on every rank: each is a process of its own that runs
// this command line. A bad count is left to rank 0's checks, which stop
// every rank with one message.
std::shared_ptr<void> limit_rank_threads(const std::optional<int>& threads) {
  if (!threads || *threads < 1) return nullptr;
  return limit_threads(threads);
}

int run_mpi_render(const RenderArgs& args) {
  if (args.tile < 8 || args.tile > 4096) throw InputError("--tile: must be in [8, 4096], got " + std::to_string(args.tile));
  PrismMpiRenderFn render = load_mpi_module();
  const auto threads = limit_rank_threads(args.threads);
  // What rank 0 planned, for its summary line.
  std::optional<FramePlan> plan;
  RenderSettings settings;
  MpiRequest request;
  request.backend = args.backend;
  request.tile = args.tile;
  request.stats = args.stats;
  request.prepare_job = [&] {
    check_outputs(args);
    Registry registry;
    Scene scene = with_phase_line("loading " + scene_name_for_phase(args.scene), !args.quiet,
                                  [&] { return load_scene(args.scene, registry); });
    write_warnings(scene, std::cerr);
    scene.camera = camera_from_flags(args.camera, scene.camera);
    plan = plan_frames(scene, args.output, args.frames, args.orbit, args.cameras);
    settings = settings_for(scene, args);
    return MpiJob{args.scene, settings, plan->cameras, plan->outputs};
  };
  request.written = [&](const std::string& backend, double render_ms, uint64_t rays) {
    if (!args.quiet) print_summary(args, *plan, backend, settings, render_ms, rays);
  };
  return render(request);
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* sub = app.add_subcommand(
      "render", "Render a scene to an image (.png/.jpg/.tif sRGB 8-bit, .exr/.hdr linear float, - PNG to stdout)");
  sub->add_option("scene", args->scene, "Scene file (JSON; - reads standard input)")->required();
  sub->add_option("-b,--backend", args->backend,
                  "Backend name, or auto: the fastest usable here (default auto; `prism list` says which)");
  sub->add_option("-o,--output", args->output,
                  "Output image: .png, .exr, .jpg/.jpeg, .tif/.tiff, .hdr, or - for PNG on standard output")
      ->required();
  sub->add_option("--width", args->width, "Image width in pixels, 1 to 16384 (default: the scene's)");
  sub->add_option("--height", args->height, "Image height in pixels, 1 to 16384 (default: the scene's)");
  sub->add_option("--spp", args->spp, "Samples per pixel, 1 to 4096 (default: the scene's)");
  sub->add_option("--max-depth", args->max_depth, "Surface interactions per camera sample, 1 to 64 (default: the scene's)");
  sub->add_option("--camera-position", args->camera.position,
                  "Render from this point instead of the scene's camera: X,Y,Z (with --look-at)");
  sub->add_option("--look-at", args->camera.look_at, "The point that camera looks at: X,Y,Z");
  sub->add_option("--fov", args->camera.fov, "Vertical field of view in degrees, in (0, 180) (default: the scene's)");
  sub->add_option("--aov", args->aov, "Extra EXR channels: id, path, depth (Z), normal (N.X N.Y N.Z), albedo (albedo.R albedo.G albedo.B)")->delimiter(',');
  sub->add_option("--stats", args->stats, "Write run statistics to this JSON file");
  sub->add_option("--frames", args->frames,
                  "Render N frames (1 to 100000) orbiting the scene, to OUT with _NNNN (or its ### run) numbered")
      ->check(CLI::Range(1, 100000));
  sub->add_option("--orbit", args->orbit, "Degrees the --frames camera path turns in all (default 360)");
  sub->add_option("--cameras", args->cameras, "Render the cameras listed in this JSON file ({\"cameras\": [...]}) as frames");
  sub->add_option("--threads", args->threads,
                  "Threads of the CPU backends, at least 1, on each rank with --mpi (default: one per core)");
  sub->add_option("--precision", args->precision, kPrecisionHelp);
  sub->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary line");
  sub->add_flag("-v,--verbose", args->verbose, "Also print the thread count and the phase times --stats writes");
  sub->add_flag("--mpi", args->mpi, "Deal tiles out over MPI ranks (mpirun -np N prism render ... --mpi)");
  sub->add_option("--tile", args->tile, "Tile side in pixels for --mpi (default 64)");
  return [args] { return args->mpi ? run_mpi_render(*args) : run_render(*args); };
}

}  // namespace prism::cli
