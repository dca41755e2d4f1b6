#include "prism/errors.hpp"

namespace prism {

// Out of line on purpose: the key functions that anchor the vtables and
// type_info in libprism_core (see errors.hpp).
InputError::~InputError() = default;
RuntimeError::~RuntimeError() = default;

}  // namespace prism
