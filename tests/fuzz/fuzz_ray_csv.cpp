// libFuzzer target: the bytes as the ray file of `prism trace`. InputError
// is the expected answer to bad input; any other exception, a crash, a
// sanitizer report, a hang or a ray that breaks the reader's promises
// (finite origin and tmin, unit direction) is a bug.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "prism/errors.hpp"
#include "prism/ray_csv.hpp"

namespace {

[[noreturn]] void broken(size_t index, const char* what) {
  std::fprintf(stderr, "fuzz_ray_csv: ray %zu: %s\n", index, what);
  std::abort();
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_rays(const std::vector<prism::TraceQuery>& rays) {
  for (size_t i = 0; i < rays.size(); ++i) {
    if (!finite(rays[i].origin) || !std::isfinite(rays[i].tmin)) broken(i, "origin or tmin not finite");
    if (!finite(rays[i].dir) || !(std::abs(glm::length(rays[i].dir) - 1) <= 1e-12)) broken(i, "direction not unit");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    check_rays(prism::parse_ray_csv(text, "fuzz.csv"));
  } catch (const prism::InputError&) {
  }
  return 0;
}
