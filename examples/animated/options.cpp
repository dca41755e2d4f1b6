#include "options.hpp"

#include <charconv>
#include <span>
#include <string_view>

#include <prism/errors.hpp>

namespace animated {

namespace {

// Bounds of the scene format (and of `prism render`'s flags): a bad value
// is reported against its flag here rather than as set_image's field.
struct IntFlag {
  std::string_view name;
  int Options::*field;
  int low, high;
};
constexpr IntFlag kIntFlags[] = {
    {"--width", &Options::width, 1, 16384},
    {"--height", &Options::height, 1, 16384},
    {"--spp", &Options::spp, 1, 4096},
    {"--max-depth", &Options::max_depth, 1, 64},
};

int parse_int(std::string_view flag, std::string_view text, int low, int high) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty())
    throw prism::InputError(std::string(flag) + ": expected a whole number, got '" + std::string(text) + "'");
  if (value < low || value > high)
    throw prism::InputError(std::string(flag) + ": must be " + std::to_string(low) + ".." + std::to_string(high) +
                            ", got " + std::to_string(value));
  return value;
}

// The argument after `flag`; advances `i` past it.
std::string_view value_of(std::span<const char* const> args, size_t& i) {
  if (i + 1 >= args.size()) throw prism::InputError(std::string(args[i]) + ": needs a value");
  return args[++i];
}

std::string_view non_empty(std::string_view flag, std::string_view value) {
  if (value.empty()) throw prism::InputError(std::string(flag) + ": needs a non-empty value");
  return value;
}

}  // namespace

Options parse_options(int argc, const char* const* argv) {
  Options options;
  const std::span<const char* const> args(argv, size_t(argc));
  for (size_t i = 1; i < args.size(); ++i) {
    const std::string_view arg = args[i];
    bool matched = false;
    for (const IntFlag& flag : kIntFlags)
      if (arg == flag.name) {
        options.*flag.field = parse_int(flag.name, value_of(args, i), flag.low, flag.high);
        matched = true;
      }
    if (matched) continue;
    if (arg == "--backend" || arg == "-b") options.backend = non_empty(arg, value_of(args, i));
    else if (arg == "--frames") options.frames = parse_int(arg, value_of(args, i), 1, 1'000'000);
    else if (arg == "--out") options.out = non_empty(arg, value_of(args, i));
    else if (arg == "--textures") options.textures = non_empty(arg, value_of(args, i));
    else if (arg == "--window") options.window = true;
    else if (arg == "--help" || arg == "-h") options.help = true;
    else throw prism::InputError("unknown argument '" + std::string(arg) + "' (--help lists the options)");
  }
  if (options.help) return options;
  std::error_code ec;
  if (!std::filesystem::is_directory(options.textures, ec))
    throw prism::InputError("--textures: " + options.textures.string() + " is not a folder");
  return options;
}

std::string usage() {
  return "usage: prism_animated [--backend NAME] [--frames N] [--width W] [--height H] [--spp S]\n"
         "                      [--max-depth D] [--out DIR] [--window] [--textures DIR]\n"
         "The showcase scene, built in code and animated, rendered frame after frame.\n"
         "  --backend NAME  reference, embree, opengl, vulkan, or auto: the fastest usable (default)\n"
         "  --frames N      frames to render (default 120; with --window, until the window is closed)\n"
         "  --width W --height H --spp S --max-depth D   image settings (default 640 360 1 5)\n"
         "  --out DIR       write each frame to DIR/frame_0000.png, ... (DIR is created)\n"
         "  --window        show the frames in a window, frame rate in its status line (Esc quits)\n"
         "  --textures DIR  the showcase's textures (default " PRISM_ANIMATED_TEXTURES ")\n"
         "Exit status: 0 done, 2 bad arguments, 1 a failure while running.\n";
}

}  // namespace animated
