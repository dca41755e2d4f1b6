// The compute pipeline of a generated kernel, through an on-disk cache keyed
// by a hash of the kernel source and the device: a hit skips glslang and
// hands the driver its own pipeline-cache data back. A cache file that is
// truncated or corrupt (checksum), or stale (written by another driver
// version: its pipeline-cache UUID or driver version differ), is rebuilt
// and rewritten.
#pragma once

#include <filesystem>
#include <string>

#include "gpu_layout.hpp"
#include "vk_context.hpp"

namespace prism::vk {

// Every kernel's interface: storage buffers 0..7 in set 0, the texels as a
// uniform texel buffer at binding 8 (gpu::KernelOptions::texel_sampler),
// the materials as a uniform buffer at binding 9
// (gpu::KernelOptions::material_block), and the tile origin (an ivec4) as a
// push constant.
constexpr uint32_t kTexelViewBinding = gpu::kBindingCount;
constexpr uint32_t kMaterialBlockBinding = gpu::kBindingCount + 1;
constexpr uint32_t kLayoutBindingCount = gpu::kBindingCount + 2;

class PipelineLayout {
 public:
  explicit PipelineLayout(const Context& context);
  ~PipelineLayout();
  PipelineLayout(const PipelineLayout&) = delete;
  PipelineLayout& operator=(const PipelineLayout&) = delete;
  VkDescriptorSetLayout sets() const { return sets_; }
  VkPipelineLayout handle() const { return layout_; }

 private:
  const Context& context_;
  VkDescriptorSetLayout sets_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
};

struct PipelineStats {
  int glslang_compile_calls = 0;
  double glslang_ms = 0.0;  // GLSL to SPIR-V (0 on a cache hit)
  double driver_ms = 0.0;   // the driver's pipeline creation
  std::string cache;  // hit, miss, corrupt, stale, disabled
  std::filesystem::path cache_file;
  double ms = 0.0;
};

// The pipeline for `source`. Throws RuntimeError with glslang's log (and
// where the generated source was saved) when it does not compile.
VkPipeline build_pipeline(const Context& context, const PipelineLayout& layout, const std::string& source,
                          PipelineStats& stats);

}  // namespace prism::vk
