// prism version (and prism --version): Prism's version, the plugin ABI
// versions a plugin must be built against, and each backend found with its
// plugin version and what its probe reports (the library and device it found,
// or why it cannot run here).
#include <cstdio>

#include "commands.hpp"
#include "prism/backend.hpp"
#include "prism/primitive_abi.h"
#include "prism/registry.hpp"

#ifndef PRISM_VERSION
#error "PRISM_VERSION (the CMake project version) must be defined"
#endif

namespace prism::cli {

int run_version() {
  std::printf("prism %s\n", PRISM_VERSION);
  std::printf("plugin ABI: primitive %u, backend %u\n", unsigned(PRISM_PRIMITIVE_ABI_VERSION),
              unsigned(PRISM_BACKEND_ABI_VERSION));
  Registry registry;
  const auto probes = registry.probe_backends(registry.backend_names_found());
  std::printf("backends:%s\n", probes.empty() ? " none found" : "");
  for (const auto& [name, probe] : probes) {
    if (!probe.error.empty()) {
      std::printf("  %-10s  %s\n", name.c_str(), probe.error.c_str());
      continue;
    }
    const std::string found = probe.usable ? probe.detail : "not usable here: " + probe.detail;
    std::printf("  %-10s  %-8s %s\n", name.c_str(), probe.version.c_str(), found.c_str());
  }
  return 0;
}

Command add_version_command(CLI::App& app) {
  app.add_subcommand("version", "Print Prism's version, the plugin ABI versions and each backend's version");
  return run_version;
}

}  // namespace prism::cli
