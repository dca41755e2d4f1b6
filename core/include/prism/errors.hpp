// The two kinds of failure the command line tells apart.
//
// Plugins throw these too. Their key functions (the destructors) live in
// libprism_core and the classes are exported, so the vtable and type_info of
// a thrown error are the core's, never a copy inside the plugin: a backend's
// error stays readable after its plugin is unloaded on the way out.
#pragma once

#include <stdexcept>
#include <string>

#define PRISM_CORE_API __attribute__((visibility("default")))

namespace prism {

// Bad input: a scene, a flag, a CSV line, an unknown backend or plugin. Exit status 2.
class PRISM_CORE_API InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~InputError() override;
};

// A failure while running: device lost, out of memory, unwritable output. Exit status 1.
class PRISM_CORE_API RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~RuntimeError() override;
};

}  // namespace prism
