#include "prism/registry.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string_view>

#include "prism/errors.hpp"

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
  if (!d.intersect || !d.surface || !d.pack || !d.bounds || !d.intersect_packet || !d.occluded_packet)
    return "missing functions (intersect, surface, pack, bounds, intersect_packet, occluded_packet)";
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
      throw InputError("unknown object type '" + type + "' (primitive plugins found: " + join(primitive_types_found()) +
                       "; searched " + join_paths(search_path_) + ")");
    throw InputError("the primitive plugin for '" + type + "' failed to load: " + join(failures));
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
      throw InputError("unknown backend '" + name + "' (backends found: " + join(backend_names_found()) +
                       "; searched " + join_paths(search_path_) + ")");
    throw InputError("the backend '" + name + "' failed to load: " + join(failures));
  }
  backends_[name] = plugin;
  return plugin;
}

std::vector<PluginReport> Registry::scan_all() {
  std::vector<PluginReport> reports;
  for (const std::string kind : {"backend", "primitive"}) {
    for (const auto& name : names_found(kind)) {
      for (const auto& file : candidates(kind, name)) {
        PluginReport report{kind, name, file, "", "", false, ""};
        if (kind == "backend") {
          auto plugin = load_backend_plugin(file, report.error);
          if (plugin) {
            report.version = plugin->desc().version ? plugin->desc().version : "";
            PrismBackendProbe probe = plugin->probe();
            report.usable = probe.usable != 0;
            report.detail = probe.reason;
          }
        } else {
          auto plugin = load_primitive_plugin(file, report.error);
          if (plugin) report.version = plugin->desc().plugin_version ? plugin->desc().plugin_version : "";
        }
        reports.push_back(report);
      }
    }
  }
  return reports;
}

std::string pick_auto_backend(Registry& registry) {
  std::string best;
  int best_rank = -1;
  for (const auto& name : registry.backend_names_found()) {
    try {
      auto plugin = registry.backend(name);
      if (plugin->probe().usable && plugin->desc().speed_rank > best_rank) {
        best = name;
        best_rank = plugin->desc().speed_rank;
      }
    } catch (const InputError&) {
      // a plugin that fails to load is simply not a candidate for auto
    }
  }
  if (best.empty()) throw InputError("-b auto: no usable backend found (run `prism list` to see why)");
  return best;
}

OpenedBackend open_backend(Registry& registry, const std::string& requested) {
  const std::string name = requested == "auto" ? pick_auto_backend(registry) : requested;
  auto plugin = registry.backend(name);
  PrismBackendProbe probe = plugin->probe();
  if (!probe.usable) throw RuntimeError("backend '" + name + "' cannot run here: " + probe.reason);
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
