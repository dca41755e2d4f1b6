// The two kinds of failure the command line tells apart.
#pragma once

#include <stdexcept>
#include <string>

namespace prism {

// Bad input: a scene, a flag, a CSV line, an unknown backend or plugin. Exit status 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A failure while running: device lost, out of memory, unwritable output. Exit status 1.
class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace prism
