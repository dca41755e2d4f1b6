// prism: list the plugins, render a scene, trace a batch of rays, view a scene
// live, check every backend against the reference (conform), measure frame
// rates (bench), check a primitive plugin (plugin check), print the versions.
// Exit status: 0 success, 2 bad input (scene, flag, CSV line, unknown
// command or backend, plugin that fails to load), 1 failure at run time,
// 128 + the signal's number when SIGINT (130) or SIGTERM (143) stopped the run.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/registry.hpp"

namespace {

// CLI11's help prints each option's type and its validators' ranges
// (`INT:INT in [1 - 100000]`); the descriptions say what a value may be and
// what the default is, so only the kind of value is shown.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_opts(const CLI::Option* opt) const override {
    std::ostringstream out;
    if (!opt->get_option_text().empty()) return " " + opt->get_option_text();
    if (opt->get_type_size() != 0) {
      const std::string type = opt->get_type_name();
      if (!type.empty()) out << " " << type.substr(0, type.find(':'));
      if (opt->get_expected_max() == CLI::detail::expected_max_vector_size) out << " ...";
      if (opt->get_required()) out << " " << get_label("REQUIRED");
    }
    return out.str();
  }
};

std::string command_names(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

CLI::App* find_command(CLI::App& app, const std::string& name) {
  for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->get_name() == name) return sub;
  return nullptr;
}

int unknown_command(const CLI::App& app, const std::string& name) {
  std::fprintf(stderr, "prism: error: unknown command '%s' (commands: %s; `prism help` describes them)\n",
               name.c_str(), command_names(app).c_str());
  return 2;
}

// `prism help [COMMAND]`: the help of the program or of one command.
int print_help(CLI::App& app, int argc, char** argv) {
  if (argc < 3) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  CLI::App* sub = find_command(app, argv[2]);
  if (!sub) return unknown_command(app, argv[2]);
  std::fputs(sub->help(app.get_name()).c_str(), stdout);  // "Usage: prism render ...", as `prism render --help`
  return 0;
}

// What CLI11 would answer with "A subcommand is required": no command, a
// mistyped one or a mistyped option before it, `help` and `--version`.
// Nothing when CLI11 should parse.
std::optional<int> answer_before_parsing(CLI::App& app, int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "prism: error: a command is required (commands: %s; `prism help` describes them)\n",
                 command_names(app).c_str());
    return 2;
  }
  const std::string first = argv[1];
  if (first == "--version") return prism::cli::run_version();
  if (first == "help") return print_help(app, argc, argv);
  if (first == "-h" || first == "--help") return std::nullopt;
  if (first.empty() || first[0] != '-') {
    if (!find_command(app, first)) return unknown_command(app, first);
    return std::nullopt;
  }
  std::fprintf(stderr, "prism: error: unexpected argument: %s (`prism help` lists the commands and options)\n",
               first.c_str());
  return 2;
}

// `prism help render` when the command line names the command, else `prism help`.
std::string help_hint(CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (find_command(app, argv[i])) return std::string("prism help ") + argv[i];
  return "prism help";
}

// CLI11 lists the arguments it did not expect last first (`--b --a` for
// `--a --b`): they are said in the order given, with where to find the flags.
int report_unexpected(CLI::App& app, const CLI::ExtrasError& e, int argc, char** argv) {
  const std::string what = e.what();
  const std::string listed = what.substr(what.find(": ") + 2);
  std::vector<std::string> words;
  std::istringstream list(listed);
  for (std::string word; list >> word;) words.push_back(word);
  std::string in_order;
  size_t found = 0;
  for (int i = 1; i < argc; ++i) {
    const auto word = std::find(words.begin(), words.end(), argv[i]);
    if (word == words.end()) continue;
    in_order += (in_order.empty() ? "" : " ") + *word;
    words.erase(word);
    ++found;
  }
  if (!words.empty() || found == 0) in_order = listed;  // not split as it was given
  std::fprintf(stderr, "prism: error: unexpected argument%s: %s (`%s` lists the flags)\n", found == 1 ? "" : "s",
               in_order.c_str(), help_hint(app, argc, argv).c_str());
  return 2;
}

// Any other parse error (a missing value, a required option, a value that
// is not a number) in the form of Prism's other errors.
int report_parse_error(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  std::fprintf(stderr, "prism: error: %s (`%s` lists the flags)\n", e.what(), help_hint(app, argc, argv).c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  // The hidden child of an isolated backend probe (prism/registry.hpp).
  if (argc == 3 && std::strcmp(argv[1], prism::kProbeCommand) == 0) return prism::run_probe_child(argv[2]);
  // Backends the run does not need are probed in children of this very
  // executable, so that one that crashes or exits cannot end the run.
  prism::set_probe_executable("/proc/self/exe");
  CLI::App app{"Prism: Whitted ray tracing of analytic primitives, with interchangeable backends"};
  app.name("prism");  // the help's usage line, printed before parse() learns argv[0]
  app.formatter(std::make_shared<HelpFormatter>());  // before the commands, which copy it
  app.require_subcommand(1);
  bool version = false;  // answered before parsing; declared for the help
  app.add_flag("--version", version, "Print the versions (as `prism version` does) and exit");
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
  add(prism::cli::add_version_command);
  app.add_subcommand("help", "Print this help, or a command's (prism help render)");
  if (auto answer = answer_before_parsing(app, argc, argv)) return *answer;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    return report_unexpected(app, e, argc, argv);
  } catch (const CLI::ParseError& e) {
    return report_parse_error(app, e, argc, argv);
  }
  prism::cli::stop_on_interrupt();
  try {
    for (auto* sub : app.get_subcommands())
      if (auto it = commands.find(sub); it != commands.end()) return it->second();
    return 2;
  } catch (const prism::Cancelled& e) {
    prism::cli::end_progress_line();  // the message starts a line of its own, not after the bar
    std::fprintf(stderr, "prism: %s; the output files were left as they were\n", e.what());
    return 128 + e.signal();
  } catch (const prism::InputError& e) {
    prism::cli::end_progress_line();
    std::fprintf(stderr, "prism: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    prism::cli::end_progress_line();
    std::fprintf(stderr, "prism: error: %s\n", e.what());
    return 1;
  }
}
