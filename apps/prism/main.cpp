// prism: list the plugins, render a scene, trace a batch of rays, view a scene
// live, check every backend against the reference (conform), measure frame
// rates (bench), check a primitive plugin (plugin check).
// Exit status: 0 success, 2 bad input (scene, flag, CSV line, unknown
// backend, plugin that fails to load), 1 failure at run time, 128 + the
// signal's number when SIGINT (130) or SIGTERM (143) stopped the run.
#include <cstdio>
#include <cstring>
#include <map>

#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/registry.hpp"

int main(int argc, char** argv) {
  // The hidden child of an isolated backend probe (prism/registry.hpp).
  if (argc == 3 && std::strcmp(argv[1], prism::kProbeCommand) == 0) return prism::run_probe_child(argv[2]);
  // Backends the run does not need are probed in children of this very
  // executable, so that one that crashes or exits cannot end the run.
  prism::set_probe_executable("/proc/self/exe");
  CLI::App app{"Prism: Whitted ray tracing of analytic primitives, with interchangeable backends"};
  app.require_subcommand(1);
  std::map<CLI::App*, prism::cli::Command> commands;
  auto add = [&](prism::cli::Command (*adder)(CLI::App&)) {
    size_t before = app.get_subcommands({}).size();
    auto command = adder(app);
    commands[app.get_subcommands({})[before]] = command;
  };
  add(prism::cli::add_list_command);
  add(prism::cli::add_render_command);
  add(prism::cli::add_trace_command);
  add(prism::cli::add_view_command);
  add(prism::cli::add_conform_command);
  add(prism::cli::add_bench_command);
  add(prism::cli::add_plugin_command);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  prism::cli::stop_on_interrupt();
  try {
    for (auto* sub : app.get_subcommands())
      if (auto it = commands.find(sub); it != commands.end()) return it->second();
    return 2;
  } catch (const prism::Cancelled& e) {
    std::fprintf(stderr, "prism: %s; the output files were left as they were\n", e.what());
    return 128 + e.signal();
  } catch (const prism::InputError& e) {
    std::fprintf(stderr, "prism: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism: error: %s\n", e.what());
    return 1;
  }
}
