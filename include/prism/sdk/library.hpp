// The SDK maths written once in the shared dialect
// (prism/sdk/modules/library.shared.glsl), instantiated for C++ in double
// (prism::sdk::f64) and float (prism::sdk::f32). The GPU kernel splices the
// same text after core/glsl/prelude.glsl.
#pragma once

#include "prism/sdk/dialect.hpp"

#define PRISM_SHARED_SOURCE "prism/sdk/modules/library.shared.glsl"
#include "prism/sdk/instantiate.hpp"
