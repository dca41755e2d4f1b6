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

// A number from the environment: `fallback` when `variable` is unset or
// empty; otherwise the whole value must be a finite number in [min, max],
// else InputError naming the variable, its value and the range (exit status
// 2). Every numeric PRISM_* variable is read through this.
double env_number(const char* variable, double fallback, double min, double max);

}  // namespace prism
