// Reading validated values out of a JSON tree, with every error naming the
// JSON path of the offending value. Each object reader records the keys it
// consumed; finish() rejects the rest, so a typo never passes silently.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "quoting.hpp"

namespace prism::json {

using Json = nlohmann::json;

// Parses JSON text, rejecting duplicate keys and non-finite numbers; errors
// name the line and column (syntax) or the JSON path (duplicates).
Json parse_strict(const std::string& text, const std::string& source_name);

// Largest magnitude the format allows for a length or coordinate.
constexpr double kMaxLength = 1e7;

[[noreturn]] void fail(const std::string& path, const std::string& message);
std::string describe(const Json& value);  // "a string", "an array", "1.5", ...
std::string format_number(double value);

std::string child_path(const std::string& path, const std::string& key);
std::string index_path(const std::string& path, size_t index);

// Range of a number: [min, max] with optionally exclusive ends.
struct Range {
  double min = -INFINITY;
  double max = INFINITY;
  bool min_exclusive = false;
  bool max_exclusive = false;
};
constexpr Range kAny{};
constexpr Range kNonNegative{0.0, INFINITY, false, false};
constexpr Range kPositive{0.0, INFINITY, true, false};
constexpr Range kUnit{0.0, 1.0, false, false};
constexpr Range kLength{-kMaxLength, kMaxLength, false, false};
constexpr Range kPositiveLength{0.0, kMaxLength, true, false};

double read_number(const Json& value, const std::string& path, Range range = kAny);
long long read_integer(const Json& value, const std::string& path, long long min, long long max);
std::string read_string(const Json& value, const std::string& path);
std::vector<double> read_numbers(const Json& value, const std::string& path, size_t count, Range range = kAny);
glm::dvec3 read_vec3(const Json& value, const std::string& path, Range range = kAny);
void require_nonzero(const glm::dvec3& v, const std::string& path);

// The candidate a misspelt `given` most likely stands for: the nearest
// within two edits (a swap of neighbours is one) and fewer than half the
// letters of the longer name; names over 64 bytes are never guessed.
std::optional<std::string> likely_meant(const std::string& given, const std::vector<std::string>& candidates);
// The message for a name that is not defined: "unknown material 'rde'" and
// then "(did you mean 'red'?)", "(materials: 'm', 'red')" or "(no materials
// are defined)". `kind` is singular ("material"), `kinds` plural.
std::string unknown_name(const std::string& kind, const std::string& kinds, const std::string& name,
                         const std::vector<std::string>& defined);

class ObjectReader {
 public:
  ObjectReader(const Json& value, std::string path);
  const std::string& path() const { return path_; }
  std::string path_of(const std::string& key) const { return child_path(path_, key); }

  bool has(const std::string& key) const;
  const Json& at(const std::string& key);           // required: error when missing
  const Json* find(const std::string& key);         // optional: nullptr when missing
  void require_absent(const std::string& key, const std::string& why);
  // Reports a missing required key (or the misspelling standing in its place).
  [[noreturn]] void fail_missing(const std::string& key) const;

  double number(const std::string& key, double fallback, Range range = kAny);
  double required_number(const std::string& key, Range range = kAny);
  int integer(const std::string& key, int fallback, int min, int max);
  glm::dvec3 vec3(const std::string& key, glm::dvec3 fallback, Range range = kAny);
  glm::dvec3 required_vec3(const std::string& key, Range range = kAny);
  glm::dvec2 vec2(const std::string& key, glm::dvec2 fallback, Range range = kAny);
  std::optional<std::string> string(const std::string& key);

  // Fails on any key that no call above asked for: names the key it is a
  // typo of, or else lists those asked for.
  void finish() const;

 private:
  const Json& value_;
  std::string path_;
  std::vector<std::string> known_;  // keys asked for, in the order asked
  void know(const std::string& key);
};

}  // namespace prism::json
