// GLSL to SPIR-V with the glslang library, at run time: the generated
// kernel differs per scene, so it cannot be compiled ahead of time.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace prism::vk {

struct CompileError {
  std::string log;  // glslang's info log: "ERROR: kernel:<line>: ...", lines of the generated source
};

// Whether the SPIR-V goes through shrink_for_driver().
enum class Shrink { no, yes };

// Compiles a GLSL 4.50 compute shader for Vulkan 1.2 (SPIR-V 1.5). Returns
// the SPIR-V words, or sets `error` and returns nothing.
std::vector<uint32_t> compile_compute_shader(const std::string& source, CompileError& error,
                                             Shrink shrink = Shrink::yes);

// glslang's SPIR-V with its calls inlined, dead functions, branches and
// code removed and single-store locals forwarded (SPIRV-Tools' optimizer,
// the passes listed in the .cpp): less for a driver's own compiler to do
// at every pipeline creation, which the program cache cannot spare it on
// drivers whose pipeline cache holds nothing (lavapipe). Returns `spirv`
// unchanged when the optimizer fails.
std::vector<uint32_t> shrink_for_driver(const std::vector<uint32_t>& spirv);

// Names the passes of shrink_for_driver(), for the program cache's key.
const char* shrink_passes_tag();

}  // namespace prism::vk
