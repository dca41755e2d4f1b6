#include "prism/ray_csv.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "unit_vector.hpp"

namespace prism {

namespace {

// The field as a message shows it: control bytes as \xNN, since a NUL
// would end the message (what() is a C string) and others garble a terminal.
std::string printable(const std::string& field) {
  std::string out;
  for (unsigned char c : field) {
    if (c >= 0x20 && c != 0x7f) {
      out += char(c);
      continue;
    }
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
    out += escaped;
  }
  return out;
}

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
      throw InputError(where + ": '" + printable(field) + "' is not a number");
    if (!std::isfinite(v)) throw InputError(where + ": '" + printable(field) + "' is not a finite number");
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
  for (size_t number = 1; std::getline(in, line); ++number) {  // size_t: no overflow at 2^31 lines
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;  // blank lines carry no ray
    if (number == 1 && line.rfind("ox", 0) == 0) continue;              // the optional header
    const std::string where = source_name + ":" + std::to_string(number);
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
