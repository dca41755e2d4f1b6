// A Vulkan instance, the chosen physical device, a logical device with one
// compute queue, and the validation messenger when validation is on.
//
// The device: $PRISM_VULKAN_DEVICE picks one by index (in the order
// vkEnumeratePhysicalDevices gives) or by a case-insensitive substring of its
// name; otherwise the first suitable one, discrete GPUs before integrated,
// virtual and CPU devices. Suitable: Vulkan 1.2 and a compute queue.
// shaderFloat64 is enabled where the device has it; without it (or with
// PRISM_VULKAN_HIDE_FLOAT64=1, for tests) every kernel runs in a float world
// (gpu/precision.hpp), which holds no double.
//
// Validation: with PRISM_VULKAN_VALIDATION=1 (the test suite sets it) the
// Khronos validation layer is required, with synchronisation validation on,
// and every message it reports is kept and counted.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "vk_api.hpp"

namespace prism::vk {

// Whether PRISM_VULKAN_VALIDATION asks for the validation layer.
bool validation_requested();

class Context {
 public:
  explicit Context(bool validation = validation_requested());
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const Api& api() const { return api_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  // The queue's timestamp bits (0: it cannot time its commands).
  uint32_t timestamp_bits() const { return timestamp_bits_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceMemoryProperties& memory() const { return memory_; }
  bool validation() const { return messenger_ != VK_NULL_HANDLE; }
  // Whether kernels may use double (shaderFloat64 enabled).
  bool has_float64() const { return float64_; }

  // "llvmpipe (LLVM 15.0.6, 256 bits), CPU device, Vulkan 1.3.230"
  std::string description() const;
  // What a compiled pipeline depends on besides its source: the device's
  // name and vendor and device ids (the driver version and pipeline-cache
  // UUID are checked inside the cache file, so that an updated driver finds
  // a stale entry rather than a miss).
  std::string identity() const;

  // After a device loss or a timeout: the destructor then neither waits for
  // the device (it may never finish) nor destroys what it may still use.
  void abandon() const { abandoned_ = true; }
  bool abandoned() const { return abandoned_; }

  // Validation messages so far (warnings and errors), and their text.
  size_t validation_message_count() const;
  std::vector<std::string> validation_messages() const;

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                    VkDebugUtilsMessageTypeFlagsEXT types,
                                                    const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);
  void create_instance(bool validation);
  void choose_device();
  void create_device();

  Api api_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  uint32_t queue_family_ = 0;
  uint32_t timestamp_bits_ = 0;
  bool float64_ = false;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  mutable bool abandoned_ = false;
  mutable std::mutex messages_mutex_;
  std::vector<std::string> messages_;
};

}  // namespace prism::vk
