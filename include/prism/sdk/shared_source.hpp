// Reading a shared-dialect source's directives: the one parser of
// `// prism:require <module>` lines, used by the kernel generator, by
// plugin_testing.hpp and (through `prism-glsl-modules`, built from this
// header) by scripts/check_plugin_glsl.sh.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace prism::sdk {

struct RequiredModules {
  std::vector<std::string> modules;  // in order of appearance, each once
  std::string problem;               // empty, or the first malformed directive
};

// A directive is a line of its own, exactly `// prism:require <module>`
// (module: letters, digits, `_`; trailing spaces allowed). A line that
// begins with `// prism:require` and is not that is a problem, not a
// comment, so a typo cannot silently drop a module.
inline RequiredModules required_modules(std::string_view source) {
  constexpr std::string_view tag = "// prism:require";
  RequiredModules result;
  size_t start = 0;
  while (start < source.size()) {
    size_t end = source.find('\n', start);
    if (end == std::string_view::npos) end = source.size();
    std::string_view line = source.substr(start, end - start);
    start = end + 1;
    if (line.substr(0, tag.size()) != tag) continue;
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r' || line.back() == '\t')) line.remove_suffix(1);
    std::string_view name = line.substr(tag.size());
    bool valid = name.size() > 1 && name[0] == ' ';
    if (valid) name.remove_prefix(1);
    for (char c : name)
      valid = valid && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_');
    if (!valid) {
      if (result.problem.empty()) result.problem = "malformed directive `" + std::string(line) + "`";
      continue;
    }
    bool seen = false;
    for (const std::string& m : result.modules) seen = seen || m == name;
    if (!seen) result.modules.emplace_back(name);
  }
  return result;
}

}  // namespace prism::sdk
