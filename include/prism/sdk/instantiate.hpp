// Instantiates the shared-dialect source named by PRISM_SHARED_SOURCE (an
// include path) in double and in float: in namespaces prism::sdk::f64 and
// prism::sdk::f32, with internal linkage, after the SDK library
// (prism/sdk/modules/library.shared.glsl). No include guard: include it once
// per source, as prism/sdk/dialect.hpp shows.
#include "prism/sdk/library.hpp"

#ifndef PRISM_SHARED_SOURCE
#error "define PRISM_SHARED_SOURCE (the shared source to instantiate) before including prism/sdk/instantiate.hpp"
#endif

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
namespace prism::sdk::f64 {
namespace {
#include "prism/sdk/dialect_begin.inc"
#include PRISM_SHARED_SOURCE
#include "prism/sdk/dialect_end.inc"
}  // namespace
}  // namespace prism::sdk::f64
namespace prism::sdk::f32 {
namespace {
#include "prism/sdk/dialect_begin.inc"
#include PRISM_SHARED_SOURCE
#include "prism/sdk/dialect_end.inc"
}  // namespace
}  // namespace prism::sdk::f32
#pragma GCC diagnostic pop
#undef PRISM_SHARED_SOURCE
