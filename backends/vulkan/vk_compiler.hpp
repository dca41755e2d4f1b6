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

// Compiles a GLSL 4.50 compute shader for Vulkan 1.2 (SPIR-V 1.5). Returns
// the SPIR-V words, or sets `error` and returns nothing.
std::vector<uint32_t> compile_compute_shader(const std::string& source, CompileError& error);

}  // namespace prism::vk
