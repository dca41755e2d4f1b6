#include "json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "prism/errors.hpp"
#include "prism/limits.hpp"

namespace prism::json {

namespace {

// Line and column (1-based) of a byte offset, for syntax errors.
std::pair<size_t, size_t> line_and_column(const std::string& text, size_t byte) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// A SAX handler that builds the document through nlohmann's own DOM
// builder while rejecting duplicate keys and non-finite numbers. (The
// parser-callback interface does the same job but rescans the parent array
// at every object's end, quadratic in a scene of 100,000 objects.) Paths
// are spelled out only for an error.
class StrictBuilder {
 public:
  using Dom = nlohmann::detail::json_sax_dom_parser<Json>;
  explicit StrictBuilder(Json& root) : dom_(root, true) {}

  bool null() { return value(dom_.null()); }
  bool boolean(bool v) { return value(dom_.boolean(v)); }
  bool number_integer(Json::number_integer_t v) { return value(dom_.number_integer(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return value(dom_.number_unsigned(v)); }
  bool number_float(Json::number_float_t v, const Json::string_t& text) {
    if (!std::isfinite(v)) fail(current_path(), "must be a finite number, got " + text);
    return value(dom_.number_float(v, text));
  }
  bool string(Json::string_t& v) { return value(dom_.string(v)); }
  bool binary(Json::binary_t& v) { return value(dom_.binary(v)); }
  bool start_object(std::size_t n) {
    check_depth();
    frames_.push_back({false, {}, {}, 0});
    return dom_.start_object(n);
  }
  bool key(Json::string_t& k) {
    Frame& f = frames_.back();
    f.key = k;
    if (!f.keys.insert(k).second) fail(current_path(), "duplicate key");
    return dom_.key(k);
  }
  bool end_object() { return end(dom_.end_object()); }
  bool start_array(std::size_t n) {
    check_depth();
    frames_.push_back({true, {}, {}, 0});
    return dom_.start_array(n);
  }
  bool end_array() { return end(dom_.end_array()); }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
    return dom_.parse_error(position, token, e);  // throws e
  }

 private:
  struct Frame {
    bool array;
    std::string key;  // objects: the key whose value is being read
    std::set<std::string> keys;
    size_t count;  // arrays: elements completed, i.e. the index being read
  };
  std::string current_path() const {
    std::string path;
    for (const Frame& f : frames_) path = f.array ? index_path(path, f.count) : child_path(path, f.key);
    return path;
  }
  // nlohmann's parser does not recurse, but copying or dumping a value does,
  // and each level costs a frame here: refuse nesting no valid scene needs.
  void check_depth() const {
    if (frames_.size() >= limits::kMaxJsonDepth)
      fail(current_path(), "arrays and objects nested more than " + std::to_string(limits::kMaxJsonDepth) +
                               " levels deep (the limit)");
  }
  bool value(bool ok) {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
    return ok;
  }
  bool end(bool ok) {
    frames_.pop_back();
    return value(ok);
  }
  Dom dom_;
  std::vector<Frame> frames_;
};

// "line L, column C: 1e999 " for the first number literal named in an
// overflow message ("number overflow parsing '1e999'").
std::string locate_overflow(const std::string& text, const std::string& message) {
  auto open = message.find('\'');
  auto close = message.rfind('\'');
  if (open == std::string::npos || close <= open) return "";
  const std::string literal = message.substr(open + 1, close - open - 1);
  auto is_number_char = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || std::strchr("+-.eE", c); };
  for (size_t at = text.find(literal); at != std::string::npos; at = text.find(literal, at + 1)) {
    const bool starts = at == 0 || !is_number_char(text[at - 1]);
    const bool ends = at + literal.size() >= text.size() || !is_number_char(text[at + literal.size()]);
    if (!starts || !ends) continue;
    auto [line, column] = line_and_column(text, at);
    return "line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + literal + " ";
  }
  return literal + " ";
}

bool in_range(double v, Range r) {
  if (r.min_exclusive ? !(v > r.min) : !(v >= r.min)) return false;
  if (r.max_exclusive ? !(v < r.max) : !(v <= r.max)) return false;
  return true;
}

// The bound `v` breaks, e.g. "> 0"; both ends when the range is a closed interval.
std::string range_text(Range r, double v) {
  if (std::isfinite(r.min) && std::isfinite(r.max) && !r.min_exclusive && !r.max_exclusive)
    return "in [" + format_number(r.min) + ", " + format_number(r.max) + "]";
  const bool below = r.min_exclusive ? !(v > r.min) : !(v >= r.min);
  std::string lo = r.min_exclusive ? "> " + format_number(r.min) : ">= " + format_number(r.min);
  std::string hi = r.max_exclusive ? "< " + format_number(r.max) : "<= " + format_number(r.max);
  return below ? lo : hi;
}

}  // namespace

Json parse_strict(const std::string& text, const std::string& source_name) {
  Json root;
  StrictBuilder builder(root);
  try {
    Json::sax_parse(text, &builder);
  } catch (const InputError& e) {
    throw InputError(source_name + ": " + e.what());
  } catch (const Json::out_of_range& e) {
    // nlohmann reports a number like 1e999 this way, without a position.
    throw InputError(source_name + ": " + locate_overflow(text, e.what()) + "must be a finite number");
  } catch (const Json::parse_error& e) {
    auto [line, column] = line_and_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    auto colon = what.find(": ", what.find("column"));
    std::string detail = colon == std::string::npos ? what : what.substr(colon + 2);
    throw InputError(source_name + ": not valid JSON at line " + std::to_string(line) + ", column " +
                     std::to_string(column) + ": " + detail);
  }
  return root;
}

void fail(const std::string& path, const std::string& message) {
  throw InputError((path.empty() ? std::string("(top level)") : path) + ": " + message);
}

std::string format_number(double value) {
  char buffer[64];
  // Whole numbers of moderate size read best as integers: 180, 10000000.
  if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e15) {
    std::snprintf(buffer, sizeof buffer, "%.0f", value);
    return buffer;
  }
  for (int digits = 1; digits <= 17; ++digits) {  // the shortest text that reads back the same
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string describe(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return value.get<bool>() ? "true" : "false";
    case Json::value_t::string: return "a string";
    case Json::value_t::array: return "an array of " + std::to_string(value.size());
    case Json::value_t::object: return "an object";
    case Json::value_t::number_float: {  // written with a point or exponent: show it as a non-integer
      std::string text = format_number(value.get<double>());
      return text.find_first_of(".e") == std::string::npos ? text + ".0" : text;
    }
    default: return value.dump();
  }
}

std::string child_path(const std::string& path, const std::string& key) {
  return path.empty() ? printable(key) : path + "." + printable(key);
}

std::string index_path(const std::string& path, size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

double read_number(const Json& value, const std::string& path, Range range) {
  if (!value.is_number()) fail(path, "must be a number, got " + describe(value));
  double v = value.get<double>();
  if (!std::isfinite(v)) fail(path, "must be a finite number");
  if (!in_range(v, range)) fail(path, "must be " + range_text(range, v) + ", got " + format_number(v));
  return v;
}

long long read_integer(const Json& value, const std::string& path, long long min, long long max) {
  if (!value.is_number_integer()) fail(path, "must be an integer, got " + describe(value));
  if (value.is_number_unsigned() && value.get<unsigned long long>() > static_cast<unsigned long long>(max))
    fail(path, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + value.dump());
  long long v = value.get<long long>();
  if (v < min || v > max)
    fail(path, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + std::to_string(v));
  return v;
}

std::string read_string(const Json& value, const std::string& path) {
  if (!value.is_string()) fail(path, "must be a string, got " + describe(value));
  return value.get<std::string>();
}

std::vector<double> read_numbers(const Json& value, const std::string& path, size_t count, Range range) {
  if (!value.is_array() || value.size() != count)
    fail(path, "must be an array of " + std::to_string(count) + " numbers, got " + describe(value));
  std::vector<double> out(count);
  for (size_t i = 0; i < count; ++i) out[i] = read_number(value[i], index_path(path, i), range);
  return out;
}

glm::dvec3 read_vec3(const Json& value, const std::string& path, Range range) {
  auto v = read_numbers(value, path, 3, range);
  return {v[0], v[1], v[2]};
}

void require_nonzero(const glm::dvec3& v, const std::string& path) {
  if (v.x == 0 && v.y == 0 && v.z == 0) fail(path, "must be non-zero, got [0, 0, 0]");
}

ObjectReader::ObjectReader(const Json& value, std::string path) : value_(value), path_(std::move(path)) {
  if (!value.is_object()) fail(path_, "must be an object, got " + describe(value));
}

void ObjectReader::know(const std::string& key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.push_back(key);
}

bool ObjectReader::has(const std::string& key) const { return value_.contains(key); }

namespace {

// Edits from a to b: insertions, deletions, substitutions and swaps of two
// neighbours ("raduis" is one swap from "radius"), to tell a misspelt key
// from a missing one. Three rows of the table: row i-2, i-1 and i.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> before(b.size() + 1), above(b.size() + 1), row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) above[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      row[j] = std::min({above[j] + 1, row[j - 1] + 1, above[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], before[j - 2] + 1);
    }
    std::swap(before, above);
    std::swap(above, row);
  }
  return above[b.size()];
}

// Names longer than this are not guessed at (the distance is quadratic in the length).
constexpr size_t kMaxGuessedLength = 64;

// At most this many names are listed after an unknown one.
constexpr size_t kMaxListedNames = 10;

}  // namespace

std::optional<std::string> likely_meant(const std::string& given, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  size_t best_distance = 3;  // two edits at most
  if (given.size() > kMaxGuessedLength) return best;
  for (const auto& candidate : candidates) {
    // Names of very different lengths are far apart: skip the quadratic distance (a key may be megabytes long).
    const size_t longer = std::max(given.size(), candidate.size());
    if (longer - std::min(given.size(), candidate.size()) >= best_distance || longer > kMaxGuessedLength) continue;
    const size_t d = edit_distance(given, candidate);
    // Fewer edits than half the longer name: "x" is no typo of "up".
    if (d < best_distance && 2 * d < longer) {
      best = candidate;
      best_distance = d;
    }
  }
  return best;
}

std::string unknown_name(const std::string& kind, const std::string& kinds, const std::string& name,
                         const std::vector<std::string>& defined) {
  const std::string head = "unknown " + kind + " " + quote(name);
  if (defined.empty()) return head + " (no " + kinds + " are defined)";
  if (auto meant = likely_meant(name, defined)) return head + " (did you mean " + quote(*meant) + "?)";
  std::string list;
  for (size_t i = 0; i < defined.size() && i < kMaxListedNames; ++i) list += (i ? ", " : "") + quote(defined[i]);
  if (defined.size() > kMaxListedNames) list += ", ... (" + std::to_string(defined.size()) + " in all)";
  return head + " (" + kinds + ": " + list + ")";
}

void ObjectReader::fail_missing(const std::string& key) const {
  // A required key missing beside an unknown key that looks like it is a typo: name the typo.
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (std::find(known_.begin(), known_.end(), it.key()) == known_.end() && likely_meant(it.key(), {key}))
      fail(path_of(it.key()), "unknown key (did you mean " + quote(key) + "?)");
  }
  fail(path_of(key), "required key is missing");
}

const Json& ObjectReader::at(const std::string& key) {
  know(key);
  if (!value_.contains(key)) fail_missing(key);
  return value_.at(key);
}

const Json* ObjectReader::find(const std::string& key) {
  know(key);
  auto it = value_.find(key);
  return it == value_.end() ? nullptr : &*it;
}

void ObjectReader::require_absent(const std::string& key, const std::string& why) {
  know(key);
  if (value_.contains(key)) fail(path_of(key), why);
}

double ObjectReader::number(const std::string& key, double fallback, Range range) {
  const Json* v = find(key);
  return v ? read_number(*v, path_of(key), range) : fallback;
}

double ObjectReader::required_number(const std::string& key, Range range) {
  return read_number(at(key), path_of(key), range);
}

int ObjectReader::integer(const std::string& key, int fallback, int min, int max) {
  const Json* v = find(key);
  return v ? static_cast<int>(read_integer(*v, path_of(key), min, max)) : fallback;
}

glm::dvec3 ObjectReader::vec3(const std::string& key, glm::dvec3 fallback, Range range) {
  const Json* v = find(key);
  return v ? read_vec3(*v, path_of(key), range) : fallback;
}

glm::dvec3 ObjectReader::required_vec3(const std::string& key, Range range) {
  return read_vec3(at(key), path_of(key), range);
}

glm::dvec2 ObjectReader::vec2(const std::string& key, glm::dvec2 fallback, Range range) {
  const Json* v = find(key);
  if (!v) return fallback;
  auto n = read_numbers(*v, path_of(key), 2, range);
  return {n[0], n[1]};
}

std::optional<std::string> ObjectReader::string(const std::string& key) {
  const Json* v = find(key);
  if (!v) return std::nullopt;
  return read_string(*v, path_of(key));
}

void ObjectReader::finish() const {
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (std::find(known_.begin(), known_.end(), it.key()) != known_.end()) continue;
    // A key already present is no typo of this one: suggest only those absent.
    std::vector<std::string> absent;
    for (const auto& k : known_)
      if (!value_.contains(k)) absent.push_back(k);
    if (auto meant = likely_meant(it.key(), absent))
      fail(path_of(it.key()), "unknown key (did you mean " + quote(*meant) + "?)");
    std::string list;
    for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
    fail(path_of(it.key()), "unknown key (expected one of: " + list + ")");
  }
}

}  // namespace prism::json
