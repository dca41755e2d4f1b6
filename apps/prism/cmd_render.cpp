// prism render SCENE -b BACKEND -o OUT.(png|exr) [overrides] [--aov id,path] [--stats F.json]
//   [--frames N [--orbit DEG] | --cameras FILE] [--mpi [--tile N]]
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

namespace prism::cli {

namespace {

struct RenderArgs {
  std::string scene, backend = "auto", output, stats, cameras;
  std::optional<int> width, height, spp, max_depth;
  std::vector<std::string> aov;
  int frames = 0;
  double orbit = 360.0;
  bool mpi = false;
  int tile = 64;
};

RenderSettings settings_for(const Scene& scene, const RenderArgs& args) {
  RenderSettings settings;
  settings.image = image_with_overrides(scene, args);
  for (const auto& aov : args.aov) {
    if (aov == "id") settings.aov_id = true;
    else if (aov == "path") settings.aov_path = true;
    else throw InputError("--aov: unknown channel '" + aov + "' (expected id or path)");
  }
  return settings;
}

void check_outputs(const RenderArgs& args) {
  check_output_path(args.output, {".png", ".exr"});
  if (!args.aov.empty() && std::filesystem::path(args.output).extension() != ".exr")
    throw InputError("--aov needs an .exr output (PNG has no extra channels)");
  if (!args.stats.empty()) check_output_path(args.stats, {".json"});
}

// One image, or each frame of a camera path, from one prepared backend.
int run_render(const RenderArgs& args) {
  check_outputs(args);
  PhaseTimer timer;
  std::map<std::string, double> ms;
  Registry registry;
  Scene scene = load_scene(args.scene, registry);
  write_warnings(scene, std::cerr);
  RenderSettings settings = settings_for(scene, args);
  const FramePlan plan = plan_frames(scene, args.output, args.frames, args.orbit, args.cameras);
  ms["load"] = timer.lap();
  BackendChoice choice = open_backend(registry, args.backend);
  choice.backend->prepare(scene);
  ms["build"] = timer.lap();
  std::optional<StagedFile> last;
  for (size_t f = 0; f < plan.cameras.size(); ++f) {
    if (last) last->commit();
    settings.camera = plan.cameras[f];
    settings.progress = progress_bar();
    Image image = choice.backend->render(settings);
    finish_progress_bar();
    ms["render"] += timer.lap();
    last.emplace(stage_image(image, plan.outputs[f]));
  }
  // The last image and the statistics are both complete on disk before
  // either replaces its older file: failing to write one keeps both.
  std::optional<StagedFile> stats;
  if (!args.stats.empty()) stats.emplace(stage_stats(args.stats, choice, scene, timer, ms));
  if (last) last->commit();
  if (stats) stats->commit();
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

int run_mpi_render(const RenderArgs& args) {
  if (args.tile < 8 || args.tile > 4096) throw InputError("--tile: must be in [8, 4096], got " + std::to_string(args.tile));
  PrismMpiRenderFn render = load_mpi_module();
  MpiRequest request;
  request.backend = args.backend;
  request.tile = args.tile;
  request.stats = args.stats;
  request.prepare_job = [&args] {
    check_outputs(args);
    Registry registry;
    const Scene scene = load_scene(args.scene, registry);
    const FramePlan plan = plan_frames(scene, args.output, args.frames, args.orbit, args.cameras);
    return MpiJob{args.scene, settings_for(scene, args), plan.cameras, plan.outputs};
  };
  return render(request);
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* sub = app.add_subcommand("render", "Render a scene to an image (.png sRGB 8-bit, .exr linear float)");
  sub->add_option("scene", args->scene, "Scene file (JSON; - reads standard input)")->required();
  sub->add_option("-b,--backend", args->backend, "Backend name, or auto for the fastest usable one");
  sub->add_option("-o,--output", args->output, "Output image, .png or .exr")->required();
  sub->add_option("--width", args->width, "Image width in pixels (1..16384)");
  sub->add_option("--height", args->height, "Image height in pixels (1..16384)");
  sub->add_option("--spp", args->spp, "Samples per pixel (1..4096)");
  sub->add_option("--max-depth", args->max_depth, "Surface interactions per camera sample (1..64)");
  sub->add_option("--aov", args->aov, "Extra EXR channels: id, path")->delimiter(',');
  sub->add_option("--stats", args->stats, "Write run statistics to this JSON file");
  sub->add_option("--frames", args->frames, "Render N frames orbiting the scene, to OUT with _NNNN (or its ### run) numbered")
      ->check(CLI::Range(1, 100000));
  sub->add_option("--orbit", args->orbit, "Degrees the --frames camera path turns in all (default 360)");
  sub->add_option("--cameras", args->cameras, "Render the cameras listed in this JSON file ({\"cameras\": [...]}) as frames");
  sub->add_flag("--mpi", args->mpi, "Deal tiles out over MPI ranks (mpirun -np N prism render ... --mpi)");
  sub->add_option("--tile", args->tile, "Tile side in pixels for --mpi (default 64)");
  return [args] { return args->mpi ? run_mpi_render(*args) : run_render(*args); };
}

}  // namespace prism::cli
