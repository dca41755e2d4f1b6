#include "vk_buffer.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

#include "prism/errors.hpp"

namespace prism::vk {

namespace {

std::string mib(VkDeviceSize bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB"; }

// The memory type for `bits` with every `required` flag, preferring one with
// the `preferred` flags too. Throws when the buffer cannot fit its heap.
uint32_t memory_type(const Context& context, const VkMemoryRequirements& needs, VkMemoryPropertyFlags required,
                     VkMemoryPropertyFlags preferred, const std::string& what) {
  const VkPhysicalDeviceMemoryProperties& m = context.memory();
  int chosen = -1;
  for (uint32_t i = 0; i < m.memoryTypeCount; ++i) {
    const VkMemoryPropertyFlags flags = m.memoryTypes[i].propertyFlags;
    if (!(needs.memoryTypeBits & (1u << i)) || (flags & required) != required) continue;
    if (chosen < 0 || ((flags & preferred) == preferred && (m.memoryTypes[chosen].propertyFlags & preferred) != preferred))
      chosen = int(i);
  }
  if (chosen < 0) throw RuntimeError("Vulkan failed during " + what + ": the device has no suitable memory type");
  const VkDeviceSize heap = m.memoryHeaps[m.memoryTypes[chosen].heapIndex].size;
  if (needs.size > heap)
    throw RuntimeError("Vulkan failed during " + what + ": out of device memory (needs " + mib(needs.size) +
                       ", the memory heap holds " + mib(heap) + ")");
  return uint32_t(chosen);
}

// At most a day: the fence wait takes nanoseconds in 64 bits, and a longer
// wait is a hang by any measure.
double timeout_seconds() { return env_number("PRISM_VULKAN_TIMEOUT", 300.0, 0.001, 86400.0); }

}  // namespace

Buffer::Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
               const std::string& what)
    : context_(&context), size_(size == 0 ? 16 : size) {
  const Api& api = context.api();
  const VkDeviceSize range_limit = context.properties().limits.maxStorageBufferRange;
  if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && size_ > range_limit)
    throw RuntimeError("Vulkan failed during " + what + ": the scene needs a " + std::to_string(size_) +
                       "-byte storage buffer; this device allows " + std::to_string(range_limit));
  auto info = make<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  info.size = size_;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(api.vkCreateBuffer(context.device(), &info, nullptr, &buffer_), what);
  VkMemoryRequirements needs{};
  api.vkGetBufferMemoryRequirements(context.device(), buffer_, &needs);
  auto allocation = make<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  allocation.allocationSize = needs.size;
  try {
    allocation.memoryTypeIndex =
        memory == Memory::Device
            ? memory_type(context, needs, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, what)
            : memory_type(context, needs, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                          VK_MEMORY_PROPERTY_HOST_CACHED_BIT, what);
    check(api.vkAllocateMemory(context.device(), &allocation, nullptr, &memory_), what);
    check(api.vkBindBufferMemory(context.device(), buffer_, memory_, 0), what);
    if (memory == Memory::Staging) check(api.vkMapMemory(context.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), what);
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

void Buffer::release() {
  if (!context_ || context_->abandoned()) return;
  const Api& api = context_->api();
  if (buffer_) api.vkDestroyBuffer(context_->device(), buffer_, nullptr);
  if (memory_) api.vkFreeMemory(context_->device(), memory_, nullptr);  // unmaps too
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

TexelView::TexelView(const Context& context, const Buffer& buffer, size_t texels, const std::string& what)
    : context_(&context) {
  auto info = make<VkBufferViewCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO);
  info.buffer = buffer.handle();
  info.format = VK_FORMAT_R32G32B32A32_SFLOAT;  // uniform texel buffers of it are mandatory in Vulkan 1.0
  info.offset = 0;
  info.range = std::max<VkDeviceSize>(texels, 1) * 16;  // a buffer holds at least 16 bytes
  check(context.api().vkCreateBufferView(context.device(), &info, nullptr, &view_), what);
}

TexelView::~TexelView() { release(); }

TexelView::TexelView(TexelView&& other) noexcept { *this = std::move(other); }

TexelView& TexelView::operator=(TexelView&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
  }
  return *this;
}

void TexelView::release() {
  if (!context_ || context_->abandoned() || !view_) return;
  context_->api().vkDestroyBufferView(context_->device(), view_, nullptr);
  view_ = VK_NULL_HANDLE;
}

Commands::Commands(const Context& context) : context_(context) {
  const Api& api = context.api();
  auto pool = make<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool.queueFamilyIndex = context.queue_family();
  check(api.vkCreateCommandPool(context.device(), &pool, nullptr, &pool_), "command pool creation");
  auto allocation = make<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  allocation.commandPool = pool_;
  allocation.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocation.commandBufferCount = 1;
  auto fence = make<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  try {
    check(api.vkAllocateCommandBuffers(context.device(), &allocation, &commands_), "command buffer allocation");
    check(api.vkCreateFence(context.device(), &fence, nullptr, &fence_), "fence creation");
  } catch (...) {
    api.vkDestroyCommandPool(context.device(), pool_, nullptr);
    throw;
  }
}

Commands::~Commands() {
  if (context_.abandoned()) return;
  const Api& api = context_.api();
  if (pending_) api.vkWaitForFences(context_.device(), 1, &fence_, VK_TRUE, UINT64_MAX);
  if (fence_) api.vkDestroyFence(context_.device(), fence_, nullptr);
  api.vkDestroyCommandPool(context_.device(), pool_, nullptr);  // frees the command buffer
}

void Commands::run(const std::string& what, const std::function<void(VkCommandBuffer)>& record) {
  submit(what, record);
  wait(what);
}

void Commands::submit(const std::string& what, const std::function<void(VkCommandBuffer)>& record) {
  timeout_seconds();  // a bad value is refused before anything is submitted
  if (pending_) wait(what);
  const Api& api = context_.api();
  auto begin = make<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(api.vkBeginCommandBuffer(commands_, &begin), what);  // implicitly resets it
  record(commands_);
  check(api.vkEndCommandBuffer(commands_), what);
  check(api.vkResetFences(context_.device(), 1, &fence_), what);
  auto submit = make<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  const VkResult submitted = api.vkQueueSubmit(context_.queue(), 1, &submit, fence_);
  if (submitted == VK_ERROR_DEVICE_LOST) context_.abandon();
  check(submitted, what);
  pending_ = true;
}

void Commands::wait(const std::string& what) {
  if (!pending_) return;
  pending_ = false;
  const double seconds = timeout_seconds();
  const Api& api = context_.api();
  const VkResult waited = api.vkWaitForFences(context_.device(), 1, &fence_, VK_TRUE, uint64_t(seconds * 1e9));
  if (waited != VK_SUCCESS) context_.abandon();
  if (waited == VK_TIMEOUT)
    throw RuntimeError("Vulkan failed during " + what + ": the device did not finish within " +
                       std::to_string(int(seconds)) + " s (PRISM_VULKAN_TIMEOUT sets the limit)");
  check(waited, what);
}

void barrier(const Api& api, VkCommandBuffer commands, VkPipelineStageFlags src_stage, VkAccessFlags src,
             VkPipelineStageFlags dst_stage, VkAccessFlags dst) {
  auto memory = make<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  memory.srcAccessMask = src;
  memory.dstAccessMask = dst;
  api.vkCmdPipelineBarrier(commands, src_stage, dst_stage, 0, 1, &memory, 0, nullptr, 0, nullptr);
}

Buffer upload_storage(const Context& context, Commands& commands, const void* bytes, size_t size,
                      const std::string& what) {
  // Also a uniform texel buffer (the texels are read through a TexelView)
  // and a uniform buffer (the materials' block).
  Buffer device(context, size,
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                    VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                Memory::Device, what);
  if (size == 0) return device;
  Buffer staging(context, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Memory::Staging, what);
  std::memcpy(staging.mapped(), bytes, size);
  commands.run(what, [&](VkCommandBuffer cb) {
    const VkBufferCopy region{0, 0, size};
    context.api().vkCmdCopyBuffer(cb, staging.handle(), device.handle(), 1, &region);
    barrier(context.api(), cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
  });
  return device;
}

void write_storage(const Context& context, Commands& commands, std::span<const BufferWrite> writes,
                   const std::string& what) {
  VkDeviceSize total = 0;
  for (const BufferWrite& w : writes) total += w.size;
  if (total == 0) return;
  Buffer staging(context, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Memory::Staging, what);
  std::vector<VkBufferCopy> regions;
  VkDeviceSize at = 0;
  for (const BufferWrite& w : writes) {
    if (w.size == 0) continue;
    std::memcpy(static_cast<char*>(staging.mapped()) + at, w.data, w.size);
    regions.push_back({at, w.offset, w.size});
    at += w.size;
  }
  const Api& api = context.api();
  commands.run(what, [&](VkCommandBuffer cb) {
    // Earlier dispatches read these buffers: the copies wait for them.
    barrier(api, cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    size_t r = 0;
    for (const BufferWrite& w : writes)
      if (w.size != 0) api.vkCmdCopyBuffer(cb, staging.handle(), w.target->handle(), 1, &regions[r++]);
    barrier(api, cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_SHADER_READ_BIT);
  });
}

}  // namespace prism::vk
