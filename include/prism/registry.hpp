// Finds and loads plugins at run time: primitive plugins
// (libprism_primitive_<type>.so) and backends (libprism_backend_<name>.so),
// from the folders in PRISM_PLUGIN_PATH (':'-separated) and then the
// install-relative default, <folder of the executable>/../lib/prism.
// Every failure is reported with its reason; a bad plugin never crashes the
// process and never hides the good ones.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "prism/backend.hpp"
#include "prism/primitive_abi.h"

namespace prism {

// A dlopen'ed shared object; closes it when the last user lets go.
class SharedLibrary {
 public:
  static std::shared_ptr<SharedLibrary> open(const std::filesystem::path& path, std::string& error);
  ~SharedLibrary();
  void* symbol(const char* name) const;
  const std::filesystem::path& path() const { return path_; }

 private:
  SharedLibrary(std::filesystem::path path, void* handle) : path_(std::move(path)), handle_(handle) {}
  std::filesystem::path path_;
  void* handle_;
};

class PrimitivePlugin {
 public:
  PrimitivePlugin(std::shared_ptr<SharedLibrary> library, const PrismPrimitiveDesc* desc)
      : library_(std::move(library)), desc_(desc) {}
  const PrismPrimitiveDesc& desc() const { return *desc_; }
  std::string name() const { return desc_->type_name; }
  const std::filesystem::path& path() const { return library_->path(); }

 private:
  std::shared_ptr<SharedLibrary> library_;
  const PrismPrimitiveDesc* desc_;
};

class BackendPlugin {
 public:
  BackendPlugin(std::shared_ptr<SharedLibrary> library, const PrismBackendDesc* desc)
      : library_(std::move(library)), desc_(desc) {}
  const PrismBackendDesc& desc() const { return *desc_; }
  std::string name() const { return desc_->name; }
  PrismBackendProbe probe() const;
  std::unique_ptr<Backend> create() const;

 private:
  std::shared_ptr<SharedLibrary> library_;
  const PrismBackendDesc* desc_;
};

// One backend plugin file loaded and probed, in a child process where the
// program allows it (set_probe_executable): a plugin that crashes or exits
// while it loads or probes ends the child, not the caller.
struct BackendProbeReport {
  std::filesystem::path file;
  std::string name;       // the descriptor's, when it loaded
  std::string version;
  int speed_rank = 0;
  std::string error;      // why it did not load or report ("probe crashed (SIGSEGV)"); empty when it did
  bool usable = false;    // the probe says it can run here
  std::string detail;     // the probe's description or reason
  // As a PrismBackendProbe: a load error or crash is "cannot run here" with its reason.
  PrismBackendProbe as_probe() const;
};

// Loads and probes each file, each in a child process of its own when a
// probe executable is set (all at once), else in this process.
std::vector<BackendProbeReport> probe_backend_files(const std::vector<std::filesystem::path>& files);

// The program whose `<exe> __probe-backend FILE` runs run_probe_child
// (prism sets its own). Without one, probes run in this process.
inline constexpr const char* kProbeCommand = "__probe-backend";
void set_probe_executable(std::filesystem::path executable);
// The child's side: loads and probes `file` and writes the result to file
// descriptor 3. Returns the exit status.
int run_probe_child(const char* file);
// How long a child probe may take before it is killed and reported as hung.
inline constexpr int kProbeTimeoutSeconds = 60;

// What was found in one plugin file, loaded or not.
struct PluginReport {
  std::string kind;  // "primitive" or "backend"
  std::string name;  // from the file name
  std::filesystem::path path;
  std::string version;  // when loaded
  std::string error;    // empty when it loaded
  bool usable = false;  // backends: the probe says it can run here
  std::string detail;   // backends: the probe's description or reason
  int speed_rank = 0;   // backends: the descriptor's, when loaded (`-b auto` picks the highest usable)
};

class Registry {
 public:
  // Search folders: PRISM_PLUGIN_PATH entries, then <core_library_folder()>/prism,
  // then <folder of the executable>/../lib/prism.
  static std::vector<std::filesystem::path> default_search_path();
  // The folder libprism_core.so was loaded from (empty when unknown).
  static std::filesystem::path core_library_folder();
  explicit Registry(std::vector<std::filesystem::path> search_path = default_search_path());

  const std::vector<std::filesystem::path>& search_path() const { return search_path_; }

  // Loads (once) the primitive plugin for `type`; throws InputError naming what
  // was found and why it failed. primitive() and backend() may be called from
  // several threads at once (two scenes loading with one registry).
  std::shared_ptr<const PrimitivePlugin> primitive(const std::string& type);
  std::shared_ptr<const BackendPlugin> backend(const std::string& name);

  // Every plugin file in the search path, each loaded to report on it.
  std::vector<PluginReport> scan_all();
  // Each backend of `names` probed as backend() would load it (the first
  // candidate file that declares that name), through probe_backend_files.
  // An unknown name has the report's error set.
  std::map<std::string, BackendProbeReport> probe_backends(const std::vector<std::string>& names);
  // Every file in the search path that may hold the plugin `name` of `kind`
  // ("primitive" or "backend"), in search order: the first that loads wins.
  std::vector<std::filesystem::path> files_of(const std::string& kind, const std::string& name) const {
    return candidates(kind, name);
  }
  std::vector<std::string> primitive_types_found() const;
  std::vector<std::string> backend_names_found() const;

 private:
  std::vector<std::filesystem::path> candidates(const std::string& kind, const std::string& name) const;
  std::vector<std::string> names_found(const std::string& kind) const;
  std::vector<std::filesystem::path> search_path_;
  std::map<std::string, std::shared_ptr<const PrimitivePlugin>> primitives_;
  std::map<std::string, std::shared_ptr<const BackendPlugin>> backends_;
  std::mutex mutex_;  // guards primitives_ and backends_
};

// A started backend and its name (`auto` resolved).
struct OpenedBackend {
  std::string name;
  std::unique_ptr<Backend> backend;
};

// The usable backend with the highest speed_rank, each probed through
// probe_backends (a plugin that crashes is passed over); InputError when none is.
std::string pick_auto_backend(Registry& registry);
// Loads, probes and starts the backend `name` ("auto": pick_auto_backend).
// Unknown or unloadable: InputError; cannot run or start here: RuntimeError.
OpenedBackend open_backend(Registry& registry, const std::string& name);
// Creates a backend already probed usable; RuntimeError when it fails to start.
std::unique_ptr<Backend> start_backend(const BackendPlugin& plugin, const std::string& name);

// Loads one plugin file; nullptr with `error` set when it is not a usable plugin.
std::shared_ptr<const PrimitivePlugin> load_primitive_plugin(const std::filesystem::path& path,
                                                              std::string& error);
std::shared_ptr<const BackendPlugin> load_backend_plugin(const std::filesystem::path& path,
                                                          std::string& error);

}  // namespace prism
