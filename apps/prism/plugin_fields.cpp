#include "plugin_fields.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace prism::cli {

namespace {

// The bound PRISM_FIELD_LENGTH adds (primitive_abi.h), which the core also
// applies to `center`.
constexpr double kMaxLength = 1e7;

// The shortest text that reads back to `x`, exponent without '+' or leading
// zeros: 1, 0.5, 1e7, -1e-7.
std::string number_text(double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  std::string text(buffer, end);
  const size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent[0] == '-';
  if (exponent[0] == '+' || negative) exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

struct Bounds {
  double min, max;
  bool min_exclusive;
};

// The range the core checks each entry against: the field's own, narrowed
// to ±1e7 for a length.
Bounds bounds_of(const PrismField& f) {
  Bounds b{f.min, f.max, (f.flags & PRISM_FIELD_MIN_EXCLUSIVE) != 0};
  if (f.flags & PRISM_FIELD_LENGTH) {
    if (b.min <= -kMaxLength) b = {-kMaxLength, b.max, false};
    b.max = std::min(b.max, kMaxLength);
  }
  return b;
}

// " in (0, 1e7]", " ≥ 0", " ≤ 5", or "" when unbounded.
std::string range_text(const Bounds& b) {
  const bool has_min = std::isfinite(b.min), has_max = std::isfinite(b.max);
  if (has_min && has_max)
    return " in " + std::string(b.min_exclusive ? "(" : "[") + number_text(b.min) + ", " + number_text(b.max) + "]";
  if (has_min) return (b.min_exclusive ? " > " : " ≥ ") + number_text(b.min);
  if (has_max) return " ≤ " + number_text(b.max);
  return "";
}

// What the field takes: "number in (0, 1e7]", "3 numbers, each ...", ...
std::string value_text(const PrismField& f) {
  const std::string range = range_text(bounds_of(f));
  if (f.kind == PRISM_FIELD_NUMBER) return "number" + range;
  const std::string count = std::to_string(f.count);
  std::string text;
  if (f.kind == PRISM_FIELD_ARRAY_OR_NULL)
    text = count + " entries, each null (read as " + number_text(f.null_value) + ") or a number" + range;
  else
    text = count + " numbers" + (range.empty() ? "" : ", each" + range);
  if (f.flags & PRISM_FIELD_NONZERO) text += ", not all 0";
  return text;
}

bool is_required(const PrismField& f) { return (f.flags & PRISM_FIELD_REQUIRED) || !f.defaults; }

// The default as JSON ("1", "[0,0,0]", "[null,null,null]"), or "required".
std::string default_text(const PrismField& f) {
  if (is_required(f)) return "required";
  auto entry = [&](uint32_t i) {
    const bool reads_as_null = f.kind == PRISM_FIELD_ARRAY_OR_NULL && f.defaults[i] == f.null_value;
    return reads_as_null ? std::string("null") : number_text(f.defaults[i]);
  };
  if (f.kind == PRISM_FIELD_NUMBER) return entry(0);
  std::string text = "[";
  for (uint32_t i = 0; i < f.count; ++i) text += (i ? "," : "") + entry(i);
  return text + "]";
}

// A doc string in a table cell: '|' would end the cell.
std::string cell(const char* text) {
  std::string out;
  for (const char* c = text ? text : ""; *c; ++c) out += *c == '|' ? std::string("\\|") : std::string(1, *c);
  return out;
}

void append_row(std::string& out, const std::string& type, const std::string& key, const std::string& value,
                const std::string& default_value, const std::string& meaning) {
  out += "| " + type + " | " + key + " | " + value + " | " + default_value + " | " + meaning + " |\n";
}

}  // namespace

std::string fields_markdown(const std::vector<const PrismPrimitiveDesc*>& plugins) {
  std::string out =
      "<!-- Generated from the plugins' field tables by `prism plugin fields --markdown`: edit the plugins' doc "
      "strings, not this table. -->\n\n"
      "| object type | key | value | default | meaning |\n|---|---|---|---|---|\n";
  for (const PrismPrimitiveDesc* d : plugins) {
    std::string type = "`" + std::string(d->type_name) + "`";
    for (uint32_t i = 0; i < d->field_count; ++i) {
      const PrismField& f = d->fields[i];
      const std::string default_value = is_required(f) ? "required" : "`" + default_text(f) + "`";
      append_row(out, type, "`" + std::string(f.name) + "`", value_text(f), default_value, cell(f.doc));
      type.clear();
    }
    if (d->flags & PRISM_PRIMITIVE_TRANSFORMABLE)
      append_row(out, type, "`center`, `rotation`", "vec3, each in [-1e7, 1e7]; Rotation", "`[0,0,0]`; the identity",
                 "where the local frame lies and how it is turned: `world = center + R · local`");
  }
  return out;
}

std::string fields_text(const PrismPrimitiveDesc& plugin) {
  std::string out;
  char line[512];
  for (uint32_t i = 0; i < plugin.field_count; ++i) {
    const PrismField& f = plugin.fields[i];
    const std::string default_value = is_required(f) ? "required" : "default " + default_text(f);
    std::snprintf(line, sizeof line, "  %-14s %s; %s: %s\n", f.name, value_text(f).c_str(), default_value.c_str(),
                  f.doc ? f.doc : "");
    out += line;
  }
  if (plugin.flags & PRISM_PRIMITIVE_TRANSFORMABLE)
    out += "  center, rotation (the core's): where the local frame lies and how it is turned\n";
  return out;
}

}  // namespace prism::cli
