// Bad scenes, one per class of error the scene format names, each with the
// parts its message must hold: the table of tests/cli/cli_errors_test.cpp,
// and seeds for the scene-loader fuzzer (tests/fuzz). No GoogleTest here.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "scene_text.hpp"

namespace prism::cli_test {

struct BadScene {
  std::string name;
  std::string scene;                // the whole file
  std::vector<std::string> expect;  // parts of the message ("a|b": either)
};

// Test names in GoogleTest's output.
inline std::ostream& operator<<(std::ostream& os, const BadScene& c) { return os << c.name; }

const std::vector<BadScene>& bad_scenes();

// The valid scene with `objects` holding just `object`.
std::string with_object(const std::string& object);

}  // namespace prism::cli_test
