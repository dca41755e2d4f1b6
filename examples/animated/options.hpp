// The command line of prism_animated.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace animated {

struct Options {
  std::string backend = "auto";
  std::optional<int> frames;  // unset: 120, or with --window until the window is closed
  int width = 640, height = 360, spp = 1, max_depth = 5;
  std::filesystem::path out;  // empty: no files written
  bool window = false;
  bool help = false;
  std::filesystem::path textures = PRISM_ANIMATED_TEXTURES;  // baked in by CMakeLists.txt
};

// Throws prism::InputError, naming the flag, for anything it cannot use.
Options parse_options(int argc, const char* const* argv);

std::string usage();

}  // namespace animated
