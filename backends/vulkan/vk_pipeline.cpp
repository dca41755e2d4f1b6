#include "vk_pipeline.hpp"

#include <chrono>
#include <cstddef>
#include <cstring>
#include <vector>

#include "gpu_dispatch.hpp"
#include "gpu_layout.hpp"
#include "kernel_source.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "program_cache.hpp"
#include "prism/status.hpp"
#include "vk_compiler.hpp"

namespace prism::vk {

namespace {

namespace fs = std::filesystem;

// Cache file: this header, the SPIR-V, then the driver's pipeline-cache data.
struct CacheHeader {
  char magic[8];  // "PRISMVKC"
  uint32_t version;
  uint32_t spirv_bytes;
  uint64_t pipeline_cache_bytes;
  uint64_t checksum;  // FNV-1a 64 of everything after the header
  char key[16];
  uint8_t pipeline_cache_uuid[VK_UUID_SIZE];  // of the driver that wrote the file
  uint32_t driver_version;
  uint32_t pad;
};
static_assert(sizeof(CacheHeader) == 72 && offsetof(CacheHeader, checksum) == 24 &&
              offsetof(CacheHeader, pipeline_cache_uuid) == 48);
constexpr uint32_t kCacheVersion = 1;
constexpr uint32_t kSpirvMagic = 0x07230203;

struct CacheEntry {
  std::vector<uint32_t> spirv;
  std::string pipeline_cache;
};

// Reads the entry; sets stats.cache to hit, or to why not.
bool load_entry(const Context& context, const fs::path& file, const std::string& key, CacheEntry& entry,
                PipelineStats& stats) {
  const std::optional<std::string> bytes = gpu::read_cache_file(file);
  if (!bytes) {
    stats.cache = "miss";
    return false;
  }
  stats.cache = "corrupt";
  CacheHeader header{};
  if (bytes->size() < sizeof header) return false;
  std::memcpy(&header, bytes->data(), sizeof header);
  const char* payload = bytes->data() + sizeof header;
  const size_t length = bytes->size() - sizeof header;
  if (std::memcmp(header.magic, "PRISMVKC", 8) != 0 || header.version != kCacheVersion ||
      std::memcmp(header.key, key.data(), sizeof header.key) != 0 || header.spirv_bytes % 4 != 0 ||
      header.spirv_bytes < 4 || uint64_t(header.spirv_bytes) + header.pipeline_cache_bytes != length ||
      header.checksum != gpu::fnv1a64(payload, length))
    return false;
  const VkPhysicalDeviceProperties& device = context.properties();
  if (std::memcmp(header.pipeline_cache_uuid, device.pipelineCacheUUID, VK_UUID_SIZE) != 0 ||
      header.driver_version != device.driverVersion) {
    stats.cache = "stale";
    return false;
  }
  entry.spirv.resize(header.spirv_bytes / 4);
  std::memcpy(entry.spirv.data(), payload, header.spirv_bytes);
  if (entry.spirv[0] != kSpirvMagic) return false;
  entry.pipeline_cache.assign(payload + header.spirv_bytes, header.pipeline_cache_bytes);
  stats.cache = "hit";
  return true;
}

void store_entry(const Context& context, const fs::path& file, const std::string& key, const CacheEntry& entry) {
  CacheHeader header{};
  std::memcpy(header.magic, "PRISMVKC", 8);
  header.version = kCacheVersion;
  header.spirv_bytes = uint32_t(entry.spirv.size() * 4);
  header.pipeline_cache_bytes = entry.pipeline_cache.size();
  std::memcpy(header.key, key.data(), sizeof header.key);
  std::memcpy(header.pipeline_cache_uuid, context.properties().pipelineCacheUUID, VK_UUID_SIZE);
  header.driver_version = context.properties().driverVersion;
  std::string payload(reinterpret_cast<const char*>(entry.spirv.data()), header.spirv_bytes);
  payload += entry.pipeline_cache;
  header.checksum = gpu::fnv1a64(payload.data(), payload.size());
  gpu::write_cache_file(file, std::string(reinterpret_cast<const char*>(&header), sizeof header) + payload);
}

std::vector<uint32_t> compile(const std::string& source, const std::string& key, PipelineStats& stats) {
  CompileError error;
  std::vector<uint32_t> spirv = compile_compute_shader(source, error);
  ++stats.glslang_compile_calls;
  if (spirv.empty()) {
    const std::string blame = gpu::blame_compile_error(source, error.log);
    throw RuntimeError("the generated GLSL kernel does not compile for Vulkan" +
                       (blame.empty() ? "" : ": error in " + blame) + " (source saved to " +
                       gpu::save_failed_source("vulkan", source, key) + ", line numbers refer to it):\n" + error.log);
  }
  return spirv;
}

// The driver's pipeline-cache data after building with it.
std::string pipeline_cache_data(const Context& context, VkPipelineCache cache) {
  size_t size = 0;
  if (context.api().vkGetPipelineCacheData(context.device(), cache, &size, nullptr) != VK_SUCCESS) return {};
  std::string data(size, '\0');
  if (context.api().vkGetPipelineCacheData(context.device(), cache, &size, data.data()) != VK_SUCCESS) return {};
  data.resize(size);
  return data;
}

VkPipeline create_pipeline(const Context& context, const PipelineLayout& layout, CacheEntry& entry) {
  const Api& api = context.api();
  const VkDevice device = context.device();
  auto cache_info = make<VkPipelineCacheCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO);
  cache_info.initialDataSize = entry.pipeline_cache.size();
  cache_info.pInitialData = entry.pipeline_cache.data();
  VkPipelineCache cache = VK_NULL_HANDLE;
  check(api.vkCreatePipelineCache(device, &cache_info, nullptr, &cache), "pipeline cache creation");
  auto module_info = make<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  module_info.codeSize = entry.spirv.size() * 4;
  module_info.pCode = entry.spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VkResult result = api.vkCreateShaderModule(device, &module_info, nullptr, &module);
  VkPipeline pipeline = VK_NULL_HANDLE;
  if (result == VK_SUCCESS) {
    auto info = make<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage = make<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout.handle();
    result = api.vkCreateComputePipelines(device, cache, 1, &info, nullptr, &pipeline);
    api.vkDestroyShaderModule(device, module, nullptr);
  }
  if (result == VK_SUCCESS) entry.pipeline_cache = pipeline_cache_data(context, cache);
  api.vkDestroyPipelineCache(device, cache, nullptr);
  check(result, "compute pipeline creation");
  return pipeline;
}

}  // namespace

PipelineLayout::PipelineLayout(const Context& context) : context_(context) {
  const Api& api = context.api();
  VkDescriptorSetLayoutBinding bindings[kLayoutBindingCount];
  for (uint32_t b = 0; b < gpu::kBindingCount; ++b)
    bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  bindings[kTexelViewBinding] = {kTexelViewBinding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1,
                                 VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  bindings[kMaterialBlockBinding] = {kMaterialBlockBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                     VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  auto sets = make<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  sets.bindingCount = kLayoutBindingCount;
  sets.pBindings = bindings;
  check(api.vkCreateDescriptorSetLayout(context.device(), &sets, nullptr, &sets_), "descriptor set layout creation");
  const VkPushConstantRange tile{VK_SHADER_STAGE_COMPUTE_BIT, 0, 4 * sizeof(int32_t)};
  auto info = make<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  info.setLayoutCount = 1;
  info.pSetLayouts = &sets_;
  info.pushConstantRangeCount = 1;
  info.pPushConstantRanges = &tile;
  const VkResult result = api.vkCreatePipelineLayout(context.device(), &info, nullptr, &layout_);
  if (result != VK_SUCCESS) api.vkDestroyDescriptorSetLayout(context.device(), sets_, nullptr);
  check(result, "pipeline layout creation");
}

PipelineLayout::~PipelineLayout() {
  if (context_.abandoned()) return;
  context_.api().vkDestroyPipelineLayout(context_.device(), layout_, nullptr);
  context_.api().vkDestroyDescriptorSetLayout(context_.device(), sets_, nullptr);
}

VkPipeline build_pipeline(const Context& context, const PipelineLayout& layout, const std::string& source,
                          PipelineStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  const std::string key = gpu::hash_hex(source + '\n' + context.identity() + '\n' + shrink_passes_tag());
  const fs::path dir = gpu::program_cache_dir("vulkan");
  CacheEntry entry;
  bool hit = false;
  if (dir.empty()) {
    stats.cache = "disabled";
  } else {
    stats.cache_file = dir / (key + ".vkc");
    hit = load_entry(context, stats.cache_file, key, entry, stats);
  }
  if (!hit) {
    notify_status(gpu::compile_notice("vulkan", stats.cache));
    const UninterruptibleWork compiling;
    const auto compile_start = std::chrono::steady_clock::now();
    entry.spirv = compile(source, key, stats);
    stats.glslang_ms += gpu::ms_since(compile_start);
  }
  const auto driver_start = std::chrono::steady_clock::now();
  VkPipeline pipeline = [&] {
    const UninterruptibleWork compiling;  // the driver compiles the SPIR-V here
    return create_pipeline(context, layout, entry);
  }();
  stats.driver_ms += gpu::ms_since(driver_start);
  if (!hit && !stats.cache_file.empty()) store_entry(context, stats.cache_file, key, entry);
  stats.ms += gpu::ms_since(start);
  return pipeline;
}

}  // namespace prism::vk
