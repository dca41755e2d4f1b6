// The valid scene the command-line tests (and the fuzzers' seed corpus)
// break one piece of. No GoogleTest here: tests/fuzz builds it too.
#pragma once

#include <string>

namespace prism::cli_test {

// A valid scene as text, member by member, for tests to break one piece of:
// a sphere of radius 1 at the origin (object 0), the plane y = -2 (object 1)
// and a point light with a visible sphere above the camera (light 0).
// An empty member is left out; `extra` is inserted verbatim as more
// top-level members (without a trailing comma).
struct SceneText {
  std::string prism = "1";
  std::string camera = R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y": 60})";
  std::string image = R"({"width": 8, "height": 6})";
  std::string extra;
  std::string lights = R"([{"type": "point", "position": [0, 5, -5], "radius": 0.5}])";
  std::string objects =
      R"([{"type": "sphere", "radius": 1}, {"type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0]}])";
  std::string text() const;
};

}  // namespace prism::cli_test
