#include "prism/errors.hpp"

#include "quoting.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace prism {

// Out of line on purpose: the key functions that anchor the vtables and
// type_info in libprism_core (see errors.hpp).
InputError::~InputError() = default;
RuntimeError::~RuntimeError() = default;

double env_number(const char* variable, double fallback, double min, double max) {
  const char* text = std::getenv(variable);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(value) || value < min || value > max) {
    char range[96];
    std::snprintf(range, sizeof range, "a number in [%g, %g]", min, max);
    throw InputError(std::string(variable) + ": must be " + range + ", got " + quote(text));
  }
  return value;
}

}  // namespace prism
