// The `prism` subcommands. Each registers its flags on the CLI11 app and
// returns the function that runs it.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace prism::cli {

using Command = std::function<int()>;

Command add_list_command(CLI::App& app);
Command add_render_command(CLI::App& app);
Command add_trace_command(CLI::App& app);
Command add_view_command(CLI::App& app);
Command add_conform_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_plugin_command(CLI::App& app);
Command add_version_command(CLI::App& app);

// `prism version` and `prism --version`.
int run_version();

}  // namespace prism::cli
