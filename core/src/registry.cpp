#include "prism/registry.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <set>
#include <string_view>

#include "prism/backend_fingerprint.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "quoting.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace prism {

namespace {

constexpr const char* kPrimitivePrefix = "libprism_primitive_";
constexpr const char* kBackendPrefix = "libprism_backend_";

std::string prefix_of(const std::string& kind) { return kind == "primitive" ? kPrimitivePrefix : kBackendPrefix; }

fs::path executable_folder() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::current_path() : exe.parent_path();
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out.empty() ? "none" : out;
}

// Calls a plugin's entry function. It is C by contract, but a C++ plugin may
// still throw through it: that is caught here, at the boundary, and becomes
// the plugin's load error like any other fault.
template <typename Desc>
const Desc* call_entry(const Desc* (*entry)(), std::string& error) {
  try {
    const Desc* desc = entry();
    if (!desc) error = "entry function returned no descriptor";
    return desc;
  } catch (const std::exception& e) {
    error = std::string("entry function threw: ") + e.what();
  } catch (...) {
    error = "entry function threw an exception that is not a std::exception";
  }
  return nullptr;
}

// Limits on a descriptor's sizes: far above any real plugin, low enough
// that a garbage value is caught before the core allocates or reads by it.
constexpr uint32_t kMaxDescSize = 1u << 16;
constexpr uint32_t kMaxFields = 256;
constexpr uint32_t kMaxFieldCount = 64;  // entries of one array field
constexpr uint32_t kMaxRecordSize = 1u << 16;
constexpr size_t kMaxNameLength = 64;

// A name the core prints, uses in file names and GLSL section titles.
bool plausible_name(const char* name) {
  if (!name || !*name) return false;
  size_t n = 0;
  for (; name[n] && n <= kMaxNameLength; ++n)
    if (!std::isalnum(static_cast<unsigned char>(name[n])) && name[n] != '_' && name[n] != '-') return false;
  return n <= kMaxNameLength;
}

std::string field_problem(const PrismField& f, uint32_t index) {
  const std::string where = "field " + std::to_string(index);
  if (!f.name || !*f.name) return where + " has no name";
  if (f.kind > PRISM_FIELD_ARRAY_OR_NULL) return where + " ('" + f.name + "') has unknown kind " + std::to_string(f.kind);
  if (f.count == 0 || f.count > kMaxFieldCount || (f.kind == PRISM_FIELD_NUMBER && f.count != 1))
    return where + " ('" + f.name + "') has count " + std::to_string(f.count);
  if (!(f.flags & PRISM_FIELD_REQUIRED) && !f.defaults) return where + " ('" + f.name + "') is optional without defaults";
  if (!(f.min <= f.max)) return where + " ('" + f.name + "') has min > max";
  return "";
}

// Why a primitive descriptor of the right ABI version cannot be used ("" if it can).
std::string primitive_desc_problem(const PrismPrimitiveDesc& d) {
  if (d.desc_size < sizeof(PrismPrimitiveDesc) || d.desc_size > kMaxDescSize)
    return "desc_size " + std::to_string(d.desc_size) + " (expected " + std::to_string(sizeof(PrismPrimitiveDesc)) + ")";
  if (!plausible_name(d.type_name)) return "type_name is missing or not a name";
  if (!d.plugin_version) return "plugin_version is missing";
  if (!d.intersect || !d.surface || !d.pack || !d.bounds || !d.intersect_packet || !d.occluded_packet ||
      !d.intersect_float || !d.occluded)
    return "missing functions (intersect, surface, pack, bounds, intersect_packet, occluded_packet, intersect_float, "
           "occluded)";
  if (d.record_size % 16 != 0 || d.record_size > kMaxRecordSize)
    return "record_size " + std::to_string(d.record_size) + " (a multiple of 16, at most " +
           std::to_string(kMaxRecordSize) + ")";
  if (d.field_count > kMaxFields || (d.field_count > 0 && !d.fields))
    return "field table of " + std::to_string(d.field_count) + " fields" + (d.fields ? "" : " is missing");
  for (uint32_t i = 0; i < d.field_count; ++i)
    if (std::string problem = field_problem(d.fields[i], i); !problem.empty()) return problem;
  if (d.glsl_source && !plausible_name(d.glsl_prefix)) return "glsl_source without a glsl_prefix";
  return "";
}

// A backend plugin whose layout fingerprint is not the core's: compiled
// against other headers, or by another compiler or standard library.
std::string foreign_build_message(const fs::path& plugin) {
  return plugin.filename().string() +
         " was built against a different Prism, compiler or standard library than this Prism"
         " (its layout fingerprint differs); rebuild it against this Prism's SDK";
}

std::string join_paths(const std::vector<fs::path>& paths) {
  std::vector<std::string> items;
  for (const auto& p : paths) items.push_back(p.string());
  return join(items);
}

}  // namespace

std::shared_ptr<SharedLibrary> SharedLibrary::open(const fs::path& path, std::string& error) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* reason = dlerror();
    error = reason ? reason : "dlopen failed";
    return nullptr;
  }
  return std::shared_ptr<SharedLibrary>(new SharedLibrary(path, handle));
}

SharedLibrary::~SharedLibrary() {
  if (handle_) dlclose(handle_);
}

void* SharedLibrary::symbol(const char* name) const { return dlsym(handle_, name); }

std::shared_ptr<const PrimitivePlugin> load_primitive_plugin(const fs::path& path, std::string& error) {
  auto library = SharedLibrary::open(path, error);
  if (!library) return nullptr;
  auto entry = reinterpret_cast<PrismPrimitiveEntryFn>(library->symbol(PRISM_PRIMITIVE_ENTRY_SYMBOL));
  if (!entry) {
    error = std::string("no entry symbol ") + PRISM_PRIMITIVE_ENTRY_SYMBOL;
    return nullptr;
  }
  const PrismPrimitiveDesc* desc = call_entry(entry, error);
  if (!desc) return nullptr;
  if (desc->abi_version != PRISM_PRIMITIVE_ABI_VERSION) {
    error = "ABI version " + std::to_string(desc->abi_version) + ", this build of Prism needs " +
            std::to_string(PRISM_PRIMITIVE_ABI_VERSION) + " (rebuild the plugin against this Prism's SDK)";
    return nullptr;
  }
  if (std::string problem = primitive_desc_problem(*desc); !problem.empty()) {
    error = "descriptor is unusable: " + problem;
    return nullptr;
  }
  return std::make_shared<PrimitivePlugin>(std::move(library), desc);
}

std::shared_ptr<const BackendPlugin> load_backend_plugin(const fs::path& path, std::string& error) {
  auto library = SharedLibrary::open(path, error);
  if (!library) return nullptr;
  auto entry = reinterpret_cast<PrismBackendEntryFn>(library->symbol(PRISM_BACKEND_ENTRY_SYMBOL));
  if (!entry) {
    error = std::string("no entry symbol ") + PRISM_BACKEND_ENTRY_SYMBOL;
    return nullptr;
  }
  const PrismBackendDesc* desc = call_entry(entry, error);
  if (!desc) return nullptr;
  if (desc->abi_version != PRISM_BACKEND_ABI_VERSION) {
    error = "ABI version " + std::to_string(desc->abi_version) + ", this build of Prism needs " +
            std::to_string(PRISM_BACKEND_ABI_VERSION);
    return nullptr;
  }
  // Before anything else of the descriptor is read: past its first 16 bytes,
  // a plugin of another layout may mean something else by every member.
  if (desc->layout_fingerprint != backend_layout_fingerprint()) {
    error = foreign_build_message(path);
    return nullptr;
  }
  if (desc->desc_size < sizeof(PrismBackendDesc) || desc->desc_size > kMaxDescSize || !plausible_name(desc->name) ||
      !desc->probe || !desc->create) {
    error = "descriptor is unusable: a bad desc_size, name, probe or create";
    return nullptr;
  }
  return std::make_shared<BackendPlugin>(std::move(library), desc);
}

PrismBackendProbe BackendPlugin::probe() const {
  PrismBackendProbe result{};
  try {
    desc_->probe(&result);
  } catch (const std::exception& e) {
    result.usable = 0;
    std::snprintf(result.reason, sizeof result.reason, "probe failed: %s", e.what());
  } catch (...) {
    result.usable = 0;
    std::snprintf(result.reason, sizeof result.reason, "probe failed with an exception that is not a std::exception");
  }
  result.reason[sizeof result.reason - 1] = '\0';  // a plugin may have filled all of it
  return result;
}

std::unique_ptr<Backend> BackendPlugin::create() const {
  try {
    return std::unique_ptr<Backend>(desc_->create());
  } catch (const std::exception&) {
    throw;  // the caller reports it (InputError and RuntimeError keep their meaning)
  } catch (...) {
    throw RuntimeError("it threw an exception that is not a std::exception");
  }
}

fs::path Registry::core_library_folder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&Registry::core_library_folder), &info) == 0 || info.dli_fname == nullptr)
    return {};
  std::error_code ec;
  fs::path file = fs::canonical(info.dli_fname, ec);
  return ec ? fs::path() : file.parent_path();
}

std::vector<fs::path> Registry::default_search_path() {
  std::vector<fs::path> folders;
  if (const char* env = std::getenv("PRISM_PLUGIN_PATH")) {
    std::string list = env;
    size_t start = 0;
    while (start <= list.size()) {
      size_t end = list.find(':', start);
      if (end == std::string::npos) end = list.size();
      if (end > start) folders.emplace_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  // Beside the core library first: a program linking the installed
  // libprism_core.so (the library API) lives anywhere.
  std::vector<fs::path> defaults;
  if (fs::path core = core_library_folder(); !core.empty()) defaults.push_back(core / "prism");
  defaults.push_back(executable_folder() / ".." / "lib" / "prism");
  for (const fs::path& folder : defaults) {
    if (std::ranges::find(folders, folder.lexically_normal()) == folders.end())
      folders.push_back(folder.lexically_normal());
  }
  return folders;
}

Registry::Registry(std::vector<fs::path> search_path) : search_path_(std::move(search_path)) {}

std::vector<fs::path> Registry::candidates(const std::string& kind, const std::string& name) const {
  std::vector<fs::path> found;
  // A name is one part of a file name: a '/' would leave the plugin folder,
  // and a NUL would cut the path short (the type "sphere.so\0" opened the
  // sphere plugin). Such a name matches no plugin.
  if (name.find_first_of(std::string_view("/\0", 2)) != std::string::npos) return found;
  for (const auto& folder : search_path_) {
    fs::path file = folder / (prefix_of(kind) + name + ".so");
    std::error_code ec;
    if (fs::exists(file, ec)) found.push_back(file);
  }
  return found;
}

std::vector<std::string> Registry::names_found(const std::string& kind) const {
  std::set<std::string> names;
  const std::string prefix = prefix_of(kind);
  for (const auto& folder : search_path_) {
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      std::string file = it->path().filename().string();
      if (file.rfind(prefix, 0) == 0 && it->path().extension() == ".so")
        names.insert(file.substr(prefix.size(), file.size() - prefix.size() - 3));
    }
  }
  return {names.begin(), names.end()};
}

std::vector<std::string> Registry::primitive_types_found() const { return names_found("primitive"); }
std::vector<std::string> Registry::backend_names_found() const { return names_found("backend"); }

template <typename Plugin, typename Loader>
static std::shared_ptr<const Plugin> load_first(const std::vector<fs::path>& files, Loader loader,
                                                const std::string& what, const std::string& name,
                                                std::vector<std::string>& failures) {
  for (const auto& file : files) {
    std::string error;
    auto plugin = loader(file, error);
    if (plugin && plugin->name() == name) return plugin;
    if (plugin) error = "it declares " + what + " '" + plugin->name() + "', not '" + name + "'";
    // dlerror() already starts with the file name; say it once.
    if (error.rfind(file.string() + ": ", 0) == 0) error.erase(0, file.string().size() + 2);
    failures.push_back(file.string() + ": " + error);
  }
  return nullptr;
}

std::shared_ptr<const PrimitivePlugin> Registry::primitive(const std::string& type) {
  std::lock_guard lock(mutex_);
  if (auto it = primitives_.find(type); it != primitives_.end()) return it->second;
  std::vector<std::string> failures;
  auto plugin = load_first<PrimitivePlugin>(candidates("primitive", type), load_primitive_plugin, "type", type, failures);
  if (!plugin) {
    if (failures.empty())
      throw InputError("unknown object type " + quote(type) + " (primitive plugins found: " + join(primitive_types_found()) +
                       "; searched " + join_paths(search_path_) + ")");
    throw InputError("the primitive plugin for " + quote(type) + " failed to load: " + join(failures));
  }
  primitives_[type] = plugin;
  return plugin;
}

std::shared_ptr<const BackendPlugin> Registry::backend(const std::string& name) {
  std::lock_guard lock(mutex_);
  if (auto it = backends_.find(name); it != backends_.end()) return it->second;
  std::vector<std::string> failures;
  auto plugin = load_first<BackendPlugin>(candidates("backend", name), load_backend_plugin, "backend", name, failures);
  if (!plugin) {
    if (failures.empty())
      throw InputError("unknown backend " + quote(name) + " (backends found: " + join(backend_names_found()) +
                       "; searched " + join_paths(search_path_) + ")");
    throw InputError("the backend '" + name + "' failed to load: " + join(failures));
  }
  backends_[name] = plugin;
  return plugin;
}

std::vector<PluginReport> Registry::scan_all() {
  std::vector<PluginReport> reports;
  std::vector<fs::path> backend_files;
  for (const std::string kind : {"backend", "primitive"}) {
    for (const auto& name : names_found(kind)) {
      for (const auto& file : candidates(kind, name)) {
        PluginReport report{kind, name, file, "", "", false, ""};
        if (kind == "backend") {
          backend_files.push_back(file);  // probed below, all at once
        } else {
          auto plugin = load_primitive_plugin(file, report.error);
          if (plugin) report.version = plugin->desc().plugin_version ? plugin->desc().plugin_version : "";
        }
        reports.push_back(report);
      }
    }
  }
  const std::vector<BackendProbeReport> probes = probe_backend_files(backend_files);
  for (size_t i = 0, b = 0; i < reports.size(); ++i) {
    if (reports[i].kind != "backend") continue;
    const BackendProbeReport& probe = probes[b++];
    reports[i].error = probe.error;
    reports[i].version = probe.version;
    reports[i].usable = probe.usable;
    reports[i].detail = probe.detail;
    reports[i].speed_rank = probe.speed_rank;
  }
  return reports;
}

std::map<std::string, BackendProbeReport> Registry::probe_backends(const std::vector<std::string>& names) {
  std::vector<fs::path> files;
  std::vector<std::string> owners;
  for (const std::string& name : names) {
    for (const fs::path& file : candidates("backend", name)) {
      files.push_back(file);
      owners.push_back(name);
    }
  }
  const std::vector<BackendProbeReport> probes = probe_backend_files(files);
  std::map<std::string, BackendProbeReport> found;
  std::map<std::string, std::vector<std::string>> failures;
  for (size_t i = 0; i < probes.size(); ++i) {
    const std::string& name = owners[i];
    if (found.count(name)) continue;  // an earlier file of the search path won
    if (probes[i].error.empty() && probes[i].name == name) {
      found[name] = probes[i];
      continue;
    }
    const std::string why = probes[i].error.empty() ? "it declares backend '" + probes[i].name + "'" : probes[i].error;
    failures[name].push_back(files[i].string() + ": " + why);
  }
  for (const std::string& name : names) {
    if (found.count(name)) continue;
    BackendProbeReport& report = found[name];
    report.error = failures.count(name) ? "failed to load: " + join(failures[name]) : "unknown backend '" + name + "'";
  }
  return found;
}

namespace {
constexpr int kNoProbeExecutable = -2;
// -b auto through child probes: the index of the fastest usable file, -1
// when none is, kNoProbeExecutable when this program probes in process.
int pick_fastest_usable(const std::vector<fs::path>& files, const std::vector<std::string>& owners);
}  // namespace

std::string pick_auto_backend(Registry& registry) {
  std::vector<fs::path> files;
  std::vector<std::string> owners;
  for (const std::string& name : registry.backend_names_found()) {
    for (const fs::path& file : registry.files_of("backend", name)) {
      files.push_back(file);
      owners.push_back(name);
    }
  }
  const int chosen = pick_fastest_usable(files, owners);
  if (chosen >= 0) return owners[size_t(chosen)];
  if (chosen == kNoProbeExecutable) {  // a program without a probe executable: every probe in this process
    std::string best;
    int best_rank = -1;
    for (const auto& [name, probe] : registry.probe_backends(registry.backend_names_found())) {
      if (probe.error.empty() && probe.usable && probe.speed_rank > best_rank) {
        best = name;
        best_rank = probe.speed_rank;
      }
    }
    if (!best.empty()) return best;
  }
  throw InputError("-b auto: no usable backend found (run `prism list` to see why)");
}

OpenedBackend open_backend(Registry& registry, const std::string& requested) {
  const std::string name = requested == "auto" ? pick_auto_backend(registry) : requested;
  auto plugin = registry.backend(name);
  if (requested != "auto") {  // auto's choice was probed already
    PrismBackendProbe probe = plugin->probe();
    if (!probe.usable) throw RuntimeError("backend '" + name + "' cannot run here: " + probe.reason);
  }
  return {name, start_backend(*plugin, name)};
}

std::unique_ptr<Backend> start_backend(const BackendPlugin& plugin, const std::string& name) {
  std::unique_ptr<Backend> backend;
  try {
    backend = plugin.create();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw RuntimeError("backend '" + name + "' failed to start: " + e.what());
  }
  if (!backend) throw RuntimeError("backend '" + name + "' failed to start");
  return backend;
}

}  // namespace prism

// ------------------------------------------------ probes in a child process
//
// The child is a fresh `<exe> __probe-backend FILE` (posix_spawn), not a
// fork of this process: a fork of a multi-threaded program (TBB workers, a
// GPU driver's threads) may inherit locks held by threads that do not exist
// in the child, and a plugin that calls exit() in a fork would run this
// process's atexit handlers and flush its stdio buffers a second time.

namespace prism {

namespace {

std::mutex probe_executable_mutex;
fs::path probe_executable;  // guarded by probe_executable_mutex

constexpr int kReportFd = 3;  // where the child writes its report

BackendProbeReport probe_in_process(const fs::path& file,
                                    const std::function<void(const BackendPlugin&)>& loaded = nullptr) {
  BackendProbeReport report;
  report.file = file;
  auto plugin = load_backend_plugin(file, report.error);
  if (!plugin) return report;
  if (loaded) loaded(*plugin);
  report.name = plugin->name();
  report.version = plugin->desc().version ? plugin->desc().version : "";
  report.speed_rank = plugin->desc().speed_rank;
  const PrismBackendProbe probe = plugin->probe();
  report.usable = probe.usable != 0;
  report.detail = probe.reason;
  return report;
}

// The report travels as NUL-terminated fields: "ok" name version rank usable
// detail, or "error" message.
std::string encode(const BackendProbeReport& r) {
  std::string out;
  auto add = [&out](const std::string& field) {
    out += field;
    out += '\0';
  };
  if (!r.error.empty()) {
    add("error");
    add(r.error);
  } else {
    add("ok");
    add(r.name);
    add(r.version);
    add(std::to_string(r.speed_rank));
    add(r.usable ? "1" : "0");
    add(r.detail);
  }
  return out;
}

// The record a child sends as soon as its plugin has loaded: "loaded" name rank.
std::string encode_loaded(const BackendPlugin& plugin) {
  std::string out = "loaded";
  out += '\0';
  out += plugin.name();
  out += '\0';
  out += std::to_string(plugin.desc().speed_rank);
  out += '\0';
  return out;
}

// The loaded record at the start of a child's bytes: its size (0 when not
// all there yet), and the name and rank it carries.
size_t decode_loaded(const std::string& data, std::string& name, int& rank) {
  const std::string marker = std::string("loaded") + '\0';
  if (data.compare(0, marker.size(), marker) != 0) return 0;
  const size_t name_end = data.find('\0', marker.size());
  if (name_end == std::string::npos) return 0;
  const size_t rank_end = data.find('\0', name_end + 1);
  if (rank_end == std::string::npos) return 0;
  name = data.substr(marker.size(), name_end - marker.size());
  rank = std::atoi(data.substr(name_end + 1, rank_end - name_end - 1).c_str());
  return rank_end + 1;
}

// False when the child's bytes are not a whole report.
bool decode(const std::string& bytes, BackendProbeReport& r) {
  std::string loaded_name;
  int loaded_rank = 0;
  const std::string data = bytes.substr(decode_loaded(bytes, loaded_name, loaded_rank));
  std::vector<std::string> fields;
  for (size_t start = 0; start < data.size();) {
    const size_t end = data.find('\0', start);
    if (end == std::string::npos) return false;  // cut short
    fields.push_back(data.substr(start, end - start));
    start = end + 1;
  }
  if (fields.size() == 2 && fields[0] == "error") {
    r.error = fields[1];
    return true;
  }
  if (fields.size() != 6 || fields[0] != "ok") return false;
  r.name = fields[1];
  r.version = fields[2];
  r.speed_rank = std::atoi(fields[3].c_str());
  r.usable = fields[4] == "1";
  r.detail = fields[5];
  return true;
}

std::string signal_name(int signal) {
  const char* abbrev = sigabbrev_np(signal);
  return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(signal);
}

struct ChildProbe {
  pid_t pid = -1;
  int fd = -1;  // read end of the report pipe; -1 once at EOF
  std::string data;
  int status = 0;
  bool reaped = false;
};

ChildProbe spawn_probe(const fs::path& executable, const fs::path& file) {
  ChildProbe child;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw RuntimeError(std::string("cannot create a pipe: ") + std::strerror(errno));
  if (fds[1] == kReportFd) {  // dup2 onto itself would keep O_CLOEXEC
    const int moved = fcntl(fds[1], F_DUPFD_CLOEXEC, kReportFd + 1);
    ::close(fds[1]);
    fds[1] = moved;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], kReportFd);
  // What a plugin prints goes to stderr: stdout may be the run's output.
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  const std::string exe = executable.string(), path = file.string();
  char* argv[] = {const_cast<char*>(exe.c_str()), const_cast<char*>(kProbeCommand), const_cast<char*>(path.c_str()),
                  nullptr};
  const int failed = posix_spawn(&child.pid, exe.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (failed != 0) {
    ::close(fds[0]);
    throw RuntimeError("cannot start " + exe + " to probe " + path + ": " + std::strerror(failed));
  }
  child.fd = fds[0];
  return child;
}

void read_some(ChildProbe& child) {
  char buffer[4096];
  const ssize_t n = ::read(child.fd, buffer, sizeof buffer);
  if (n > 0 && child.data.size() < 65536) child.data.append(buffer, size_t(n));
  if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) {
    ::close(child.fd);
    child.fd = -1;
  }
}

void reap(ChildProbe& child) {
  if (child.reaped) return;
  if (child.fd >= 0) ::close(child.fd);
  child.fd = -1;
  while (::waitpid(child.pid, &child.status, 0) < 0 && errno == EINTR) {
  }
  child.reaped = true;
}

void kill_all(std::vector<ChildProbe>& children) {
  for (ChildProbe& child : children)
    if (!child.reaped) ::kill(child.pid, SIGKILL);
  for (ChildProbe& child : children) reap(child);
}

// One child per file; none left running when one cannot be started.
std::vector<ChildProbe> spawn_probes(const fs::path& executable, const std::vector<fs::path>& files) {
  std::vector<ChildProbe> children;
  try {
    for (const fs::path& file : files) children.push_back(spawn_probe(executable, file));
  } catch (...) {
    kill_all(children);
    throw;
  }
  return children;
}

fs::path current_probe_executable() {
  std::lock_guard lock(probe_executable_mutex);
  return probe_executable;
}

// Reaps a child that has closed its end of the pipe, if it has exited.
void try_reap(ChildProbe& child) {
  if (child.reaped || child.fd >= 0) return;
  if (::waitpid(child.pid, &child.status, WNOHANG) == child.pid) child.reaped = true;
}

// Reaps the children that have ended and reads what the others sent,
// waiting up to 100 ms for something to arrive.
void pump(std::vector<ChildProbe>& children) {
  std::vector<pollfd> fds;
  std::vector<size_t> which;
  for (size_t i = 0; i < children.size(); ++i) {
    try_reap(children[i]);
    if (children[i].fd < 0) continue;
    fds.push_back({children[i].fd, POLLIN, 0});
    which.push_back(i);
  }
  if (fds.empty()) {
    ::usleep(1000);  // only exits left to wait for
    return;
  }
  if (::poll(fds.data(), fds.size(), 100) <= 0) return;
  for (size_t k = 0; k < fds.size(); ++k)
    if (fds[k].revents != 0) read_some(children[which[k]]);
}

// Reads every child's report until each has exited, the deadline passes
// (the rest are killed: hung) or a cancel request arrives (all killed, Cancelled).
void collect(std::vector<ChildProbe>& children, std::vector<bool>& hung) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kProbeTimeoutSeconds);
  for (;;) {
    pump(children);
    if (std::all_of(children.begin(), children.end(), [](const ChildProbe& c) { return c.reaped; })) return;
    if (cancel_requested()) {
      kill_all(children);
      throw_if_cancelled();
    }
    if (std::chrono::steady_clock::now() > deadline) {
      for (size_t i = 0; i < children.size(); ++i) hung[i] = !children[i].reaped;
      kill_all(children);
      return;
    }
  }
}

BackendProbeReport report_of(const fs::path& file, ChildProbe& child, bool hung) {
  reap(child);
  BackendProbeReport report;
  report.file = file;
  // A whole report stands even if the child died after sending it.
  if (!hung && decode(child.data, report)) return report;
  report = BackendProbeReport{};
  report.file = file;
  if (hung)
    report.error = "probe did not finish within " + std::to_string(kProbeTimeoutSeconds) + " s";
  else if (WIFSIGNALED(child.status))
    report.error = "probe crashed (" + signal_name(WTERMSIG(child.status)) + ")";
  else
    report.error = "probe exited with status " + std::to_string(WEXITSTATUS(child.status)) + " before reporting";
  return report;
}

}  // namespace

PrismBackendProbe BackendProbeReport::as_probe() const {
  PrismBackendProbe probe{};
  probe.usable = error.empty() && usable ? 1 : 0;
  std::snprintf(probe.reason, sizeof probe.reason, "%s", error.empty() ? detail.c_str() : error.c_str());
  return probe;
}

void set_probe_executable(fs::path executable) {
  std::lock_guard lock(probe_executable_mutex);
  probe_executable = std::move(executable);
}

namespace {

bool write_whole(int fd, const std::string& bytes) {
  for (size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

}  // namespace

int run_probe_child(const char* file) {
  // First what loading told (name and rank: -b auto orders the candidates
  // by it before their probes end), then the whole report.
  const std::string report = encode(probe_in_process(file, [](const BackendPlugin& plugin) {
    write_whole(kReportFd, encode_loaded(plugin));
  }));
  if (!write_whole(kReportFd, report)) return 1;
  std::fflush(nullptr);
  std::_Exit(0);  // no static destructors, no dlclose: the plugin had its say
}

std::vector<BackendProbeReport> probe_backend_files(const std::vector<fs::path>& files) {
  const fs::path executable = current_probe_executable();
  std::vector<BackendProbeReport> reports;
  if (executable.empty()) {
    for (const fs::path& file : files) reports.push_back(probe_in_process(file));
    return reports;
  }
  std::vector<ChildProbe> children = spawn_probes(executable, files);
  std::vector<bool> hung(children.size(), false);
  collect(children, hung);
  for (size_t i = 0; i < files.size(); ++i) reports.push_back(report_of(files[i], children[i], hung[i]));
  return reports;
}

namespace {

// What -b auto knows of one child so far.
struct AutoCandidate {
  bool loaded = false;  // its loaded record came: name and rank known
  std::string name;
  int rank = 0;
  bool reported = false;  // its whole report came
  BackendProbeReport report;
};

AutoCandidate candidate_of(const ChildProbe& child) {
  AutoCandidate c;
  c.loaded = decode_loaded(child.data, c.name, c.rank) > 0;
  c.reported = decode(child.data, c.report);
  return c;
}

// The decision once every child has loaded its plugin or ended: the fastest
// candidate whose probe says usable, once the probes of every faster one
// (and of an earlier file of the same name, which would shadow it) are in.
// -1: none is usable; -3: a probe that matters is still running.
constexpr int kUndecided = -3;
int decide(const std::vector<ChildProbe>& children, const std::vector<std::string>& owners) {
  std::vector<AutoCandidate> cs;
  for (const ChildProbe& child : children) {
    cs.push_back(candidate_of(child));
    if (!cs.back().loaded && !child.reaped) return kUndecided;
  }
  std::vector<size_t> order;
  for (size_t i = 0; i < cs.size(); ++i)
    if (cs[i].loaded && cs[i].name == owners[i]) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cs[a].rank > cs[b].rank; });
  for (const size_t i : order) {
    bool shadowed = false;
    for (size_t j = 0; j < i; ++j) {
      if (owners[j] != owners[i] || !cs[j].loaded || cs[j].name != owners[j]) continue;
      if (!cs[j].reported && !children[j].reaped) return kUndecided;
      shadowed = shadowed || (cs[j].reported && cs[j].report.error.empty());
    }
    if (shadowed) continue;
    if (!cs[i].reported) {
      if (!children[i].reaped) return kUndecided;
      continue;  // crashed or exited in its probe
    }
    if (cs[i].report.error.empty() && cs[i].report.usable) return int(i);
  }
  return -1;
}

int pick_fastest_usable(const std::vector<fs::path>& files, const std::vector<std::string>& owners) {
  const fs::path executable = current_probe_executable();
  if (executable.empty()) return kNoProbeExecutable;
  std::vector<ChildProbe> children = spawn_probes(executable, files);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kProbeTimeoutSeconds);
  for (;;) {
    pump(children);
    const int decision = decide(children, owners);
    if (decision != kUndecided) {
      kill_all(children);  // the slower candidates' probes are not needed
      return decision;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      kill_all(children);  // a hung probe is passed over like a crashed one
      return std::max(decide(children, owners), -1);
    }
    if (cancel_requested()) {
      kill_all(children);
      throw_if_cancelled();
    }
  }
}

}  // namespace

}  // namespace prism
