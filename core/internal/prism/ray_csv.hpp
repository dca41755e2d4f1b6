// The ray file of `prism trace`: one ray per line, ox,oy,oz,dx,dy,dz[,tmin]
// (tmin defaults to 0), an optional header line starting with "ox", blank
// lines skipped, CRLF accepted. Directions are normalized on the way in.
#pragma once

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "prism/backend.hpp"
#include "prism/errors.hpp"

namespace prism {

// One ray as `prism trace` reads it: the direction normalized (any finite,
// non-zero length); InputError naming `where` when it is zero. The caller
// has checked that every value is finite.
PRISM_CORE_API TraceQuery make_trace_query(const glm::dvec3& origin, const glm::dvec3& direction, double tmin,
                                           const std::string& where);
// Throws InputError naming `source_name` and the line ("rays.csv:3: ...").
PRISM_CORE_API std::vector<TraceQuery> parse_ray_csv(std::istream& in, const std::string& source_name);
PRISM_CORE_API std::vector<TraceQuery> parse_ray_csv(const std::string& text, const std::string& source_name);

// The same from a file; messages name the file as given.
PRISM_CORE_API std::vector<TraceQuery> read_ray_csv(const std::filesystem::path& file);

}  // namespace prism
