// Finding the primitives' case modules (primitive_cases.hpp): the files
// libprism_cases_<type>.so in the folders the registry searches for plugins.
#include "primitive_cases.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "prism/registry.hpp"

namespace prism::cases {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kPrefix = "libprism_cases_";
constexpr std::string_view kSuffix = ".so";

bool is_case_module(const fs::path& file) {
  const std::string name = file.filename().string();
  return name.size() > kPrefix.size() + kSuffix.size() && name.starts_with(kPrefix) && name.ends_with(kSuffix);
}

// The module's cases. Never unloaded: the cases hold its code.
const PrimitiveCases* load(const fs::path& file) {
  void* handle = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::runtime_error("cannot load case module " + file.string() + ": " + ::dlerror());
  using Entry = const PrimitiveCases* (*)();
  auto entry = reinterpret_cast<Entry>(::dlsym(handle, "prism_primitive_cases"));
  if (!entry) throw std::runtime_error(file.string() + " has no prism_primitive_cases()");
  return entry();
}

std::vector<const PrimitiveCases*> load_all() {
  std::map<std::string, const PrimitiveCases*> by_type;
  for (const fs::path& folder : Registry::default_search_path()) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder, ec))
      if (is_case_module(entry.path())) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      const std::string type = file.filename().string().substr(
          kPrefix.size(), file.filename().string().size() - kPrefix.size() - kSuffix.size());
      if (by_type.count(type)) continue;  // an earlier folder has it
      const PrimitiveCases* cases = load(file);
      if (cases->type != type)
        throw std::runtime_error(file.string() + " holds the cases of '" + cases->type + "', not '" + type + "'");
      by_type[type] = cases;
    }
  }
  std::vector<const PrimitiveCases*> all;
  for (const auto& [type, cases] : by_type) all.push_back(cases);
  return all;
}

}  // namespace

const std::vector<const PrimitiveCases*>& all_primitive_cases() {
  static const std::vector<const PrimitiveCases*> all = load_all();
  return all;
}

const PrimitiveCases* find_primitive_cases(const std::string& type) {
  for (const PrimitiveCases* cases : all_primitive_cases())
    if (cases->type == type) return cases;
  return nullptr;
}

}  // namespace prism::cases
