#include "prism/ray_csv.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "prism/cancel.hpp"
#include "prism/limits.hpp"
#include "quoting.hpp"
#include "unit_vector.hpp"

namespace prism {

namespace {

std::vector<double> parse_fields(const std::string& line, const std::string& where) {
  std::vector<double> values;
  std::stringstream fields(line);
  std::string field;
  while (std::getline(fields, field, ',')) {
    const char* begin = field.c_str();
    char* end = nullptr;
    double v = std::strtod(begin, &end);
    while (end && (*end == ' ' || *end == '\t' || *end == '\r')) ++end;
    // The whole field, not just up to a NUL byte inside it ("1\0x" is not 1).
    if (end == begin || end != begin + field.size())
      throw InputError(where + ": " + quote(field) + " is not a number");
    if (!std::isfinite(v)) throw InputError(where + ": " + quote(field) + " is not a finite number");
    values.push_back(v);
  }
  if (!line.empty() && line.back() == ',') throw InputError(where + ": empty field at the end");
  if (values.size() != 6 && values.size() != 7)
    throw InputError(where + ": expected ox,oy,oz,dx,dy,dz[,tmin], got " + std::to_string(values.size()) + " fields");
  return values;
}

TraceQuery ray_of(const std::vector<double>& v, const std::string& where) {
  return make_trace_query({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v.size() == 7 ? v[6] : 0.0, where);
}

// The longest line a ray can need: 7 numbers of 17 digits with signs,
// exponents and spaces, many times over.
constexpr size_t kMaxLineBytes = 1024;

// The next line into `line` (without its newline); false at the end. A line
// longer than kMaxLineBytes is an error, so that a file without newlines
// (/dev/zero) cannot grow one line without bound.
bool next_line(std::istream& in, std::vector<char>& buffer, std::string& line, const std::string& where) {
  in.getline(buffer.data(), std::streamsize(buffer.size()));
  const size_t got = size_t(in.gcount());
  if (in.fail() && !in.eof()) {
    if (got == buffer.size() - 1)
      throw InputError(where + ": longer than " + std::to_string(kMaxLineBytes) + " characters");
    return false;  // a read error: in.bad(), reported by the caller
  }
  if (got == 0 && in.eof()) return false;
  line.assign(buffer.data(), in.eof() ? got : got - 1);  // gcount counts the newline it took
  return true;
}

}  // namespace

TraceQuery make_trace_query(const glm::dvec3& origin, const glm::dvec3& direction, double tmin,
                            const std::string& where) {
  const glm::dvec3 dir = rescaled(direction);  // so that 1e-160 and 1e200 normalize too
  const double length = glm::length(dir);
  if (!(length > 0) || !std::isfinite(length)) throw InputError(where + ": the direction is zero");
  return {origin, dir / length, tmin};
}

std::vector<TraceQuery> parse_ray_csv(std::istream& in, const std::string& source_name) {
  std::vector<TraceQuery> rays;
  std::string line;
  std::vector<char> buffer(kMaxLineBytes + 2);  // the line, its '\r' and the terminator
  for (size_t number = 1; next_line(in, buffer, line, source_name + ":" + std::to_string(number)); ++number) {
    if (number % 4096 == 0) throw_if_cancelled();  // a large file reads for seconds
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;  // blank lines carry no ray
    if (number == 1 && line.rfind("ox", 0) == 0) continue;              // the optional header
    const std::string where = source_name + ":" + std::to_string(number);
    if (rays.size() == limits::kMaxTraceRays)
      throw InputError(where + ": more than " + std::to_string(limits::kMaxTraceRays) + " rays (the limit of one trace)");
    rays.push_back(ray_of(parse_fields(line, where), where));
  }
  if (in.bad()) throw InputError(source_name + ": cannot read ray file");
  return rays;
}

std::vector<TraceQuery> parse_ray_csv(const std::string& text, const std::string& source_name) {
  std::istringstream in(text);
  return parse_ray_csv(in, source_name);
}

std::vector<TraceQuery> read_ray_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot open ray file");
  return parse_ray_csv(in, file.string());
}

}  // namespace prism
