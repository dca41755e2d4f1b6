// Storage and staging buffers, and the one command buffer Prism records
// into and waits on. Scene data lives in device-local buffers filled through
// a staging buffer; results come back the same way.
#pragma once

#include <chrono>
#include <functional>
#include <span>
#include <string>

#include "vk_context.hpp"

namespace prism::vk {

enum class Memory {
  Device,   // device-local where the device has it: storage buffers
  Staging,  // host-visible and coherent, mapped: uploads and readback
};

class Buffer {
 public:
  Buffer() = default;
  // Throws RuntimeError("... out of device memory ...") when `size` exceeds
  // the memory heap or the allocation fails. A zero size becomes 16 bytes
  // (Vulkan has no empty buffers; the kernels read none of it).
  Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory, const std::string& what);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }  // Staging buffers only

 private:
  void release();
  const Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

// A view of the first `texels` RGBA32F texels of a buffer (at least one),
// for a uniform texel buffer descriptor (the kernels' samplerBuffer). Not
// the whole buffer: one kept from a larger scene may exceed the device's
// maxTexelBufferElements.
class TexelView {
 public:
  TexelView() = default;
  TexelView(const Context& context, const Buffer& buffer, size_t texels, const std::string& what);
  ~TexelView();
  TexelView(TexelView&& other) noexcept;
  TexelView& operator=(TexelView&& other) noexcept;

  VkBufferView handle() const { return view_; }
  explicit operator bool() const { return view_ != VK_NULL_HANDLE; }

 private:
  void release();
  const Context* context_ = nullptr;
  VkBufferView view_ = VK_NULL_HANDLE;
};

// One primary command buffer and a fence: record, submit, wait.
class Commands {
 public:
  explicit Commands(const Context& context);
  ~Commands();
  Commands(const Commands&) = delete;
  Commands& operator=(const Commands&) = delete;

  // Records `record` into the command buffer, submits it and waits for it.
  // Throws RuntimeError when the device is lost, runs out of memory, or has
  // not finished after $PRISM_VULKAN_TIMEOUT seconds (default 300): a hung
  // device ends the run with a message instead of hanging it.
  void run(const std::string& what, const std::function<void(VkCommandBuffer)>& record);
  // The two halves of run(), so that the host can work while the device
  // does: submit() first waits for anything still pending.
  void submit(const std::string& what, const std::function<void(VkCommandBuffer)>& record);
  void wait(const std::string& what);

 private:
  bool pending_ = false;
  const Context& context_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

// A barrier making `src` accesses at `src_stage` visible to `dst` accesses at `dst_stage`.
void barrier(const Api& api, VkCommandBuffer commands, VkPipelineStageFlags src_stage, VkAccessFlags src,
             VkPipelineStageFlags dst_stage, VkAccessFlags dst);

// A device-local storage buffer holding `bytes`, filled through a staging buffer.
Buffer upload_storage(const Context& context, Commands& commands, const void* bytes, size_t size,
                      const std::string& what);

// Bytes to copy into part of a device-local storage buffer.
struct BufferWrite {
  const Buffer* target;
  VkDeviceSize offset;
  const void* data;
  size_t size;
};

// Copies every write through one staging buffer in one submission, after
// the kernels' earlier reads and before their later ones (a live update
// sends only the ranges that changed). Empty writes are skipped.
void write_storage(const Context& context, Commands& commands, std::span<const BufferWrite> writes,
                   const std::string& what);

}  // namespace prism::vk
