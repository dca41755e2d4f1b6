// prism render SCENE -b BACKEND -o OUT.(png|exr) [overrides] [--aov id,path] [--stats F.json]
#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/scene_loader.hpp"

namespace prism::cli {

namespace {

struct RenderArgs {
  std::string scene, backend = "auto", output, stats;
  std::optional<int> width, height, spp, max_depth;
  std::vector<std::string> aov;
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

int run_render(const RenderArgs& args) {
  check_output_path(args.output, {".png", ".exr"});
  if (!args.aov.empty() && std::filesystem::path(args.output).extension() != ".exr")
    throw InputError("--aov needs an .exr output (PNG has no extra channels)");
  if (!args.stats.empty()) check_output_path(args.stats, {".json"});
  PhaseTimer timer;
  std::map<std::string, double> ms;
  Registry registry;
  Scene scene = load_scene(args.scene, registry);
  RenderSettings settings = settings_for(scene, args);
  ms["load"] = timer.lap();
  BackendChoice choice = open_backend(registry, args.backend);
  choice.backend->prepare(scene);
  ms["build"] = timer.lap();
  settings.progress = progress_bar();
  Image image = choice.backend->render(settings);
  finish_progress_bar();
  ms["render"] = timer.lap();
  write_image(image, args.output);
  if (!args.stats.empty()) write_stats(args.stats, choice, scene, timer, ms);
  return 0;
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* sub = app.add_subcommand("render", "Render a scene to an image (.png sRGB 8-bit, .exr linear float)");
  sub->add_option("scene", args->scene, "Scene file (JSON)")->required();
  sub->add_option("-b,--backend", args->backend, "Backend name, or auto for the fastest usable one");
  sub->add_option("-o,--output", args->output, "Output image, .png or .exr")->required();
  sub->add_option("--width", args->width, "Image width in pixels (1..16384)");
  sub->add_option("--height", args->height, "Image height in pixels (1..16384)");
  sub->add_option("--spp", args->spp, "Samples per pixel (1..4096)");
  sub->add_option("--max-depth", args->max_depth, "Surface interactions per camera sample (1..64)");
  sub->add_option("--aov", args->aov, "Extra EXR channels: id, path")->delimiter(',');
  sub->add_option("--stats", args->stats, "Write run statistics to this JSON file");
  return [args] { return run_render(*args); };
}

}  // namespace prism::cli
