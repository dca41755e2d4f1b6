// The Vulkan entry points Prism calls, loaded at run time: the plugin opens
// the loader (libvulkan.so.1) itself rather than linking it, so a machine
// without one still loads the plugin and `prism list` can say what is
// missing. Global functions come from vkGetInstanceProcAddr(nullptr), the
// rest from the instance and the device (no loader trampoline per call).
#pragma once

#define VK_NO_PROTOTYPES 1
#include <vulkan/vulkan.h>

#include <string>

namespace prism::vk {

#define PRISM_VK_GLOBAL_FUNCTIONS(X)      \
  X(vkCreateInstance)                     \
  X(vkEnumerateInstanceVersion)           \
  X(vkEnumerateInstanceLayerProperties)   \
  X(vkEnumerateInstanceExtensionProperties)

#define PRISM_VK_INSTANCE_FUNCTIONS(X)           \
  X(vkDestroyInstance)                           \
  X(vkEnumeratePhysicalDevices)                  \
  X(vkGetPhysicalDeviceProperties)               \
  X(vkGetPhysicalDeviceFeatures)                 \
  X(vkGetPhysicalDeviceQueueFamilyProperties)    \
  X(vkGetPhysicalDeviceMemoryProperties)         \
  X(vkCreateDevice)                              \
  X(vkGetDeviceProcAddr)

#define PRISM_VK_DEBUG_FUNCTIONS(X)   \
  X(vkCreateDebugUtilsMessengerEXT)   \
  X(vkDestroyDebugUtilsMessengerEXT)

#define PRISM_VK_DEVICE_FUNCTIONS(X)  \
  X(vkDestroyDevice)                  \
  X(vkGetDeviceQueue)                 \
  X(vkDeviceWaitIdle)                 \
  X(vkCreateBuffer)                   \
  X(vkDestroyBuffer)                  \
  X(vkCreateBufferView)               \
  X(vkDestroyBufferView)              \
  X(vkGetBufferMemoryRequirements)    \
  X(vkAllocateMemory)                 \
  X(vkFreeMemory)                     \
  X(vkBindBufferMemory)               \
  X(vkMapMemory)                      \
  X(vkUnmapMemory)                    \
  X(vkCreateShaderModule)             \
  X(vkDestroyShaderModule)            \
  X(vkCreatePipelineCache)            \
  X(vkDestroyPipelineCache)           \
  X(vkGetPipelineCacheData)           \
  X(vkCreateDescriptorSetLayout)      \
  X(vkDestroyDescriptorSetLayout)     \
  X(vkCreatePipelineLayout)           \
  X(vkDestroyPipelineLayout)          \
  X(vkCreateComputePipelines)         \
  X(vkDestroyPipeline)                \
  X(vkCreateDescriptorPool)           \
  X(vkDestroyDescriptorPool)          \
  X(vkAllocateDescriptorSets)         \
  X(vkUpdateDescriptorSets)           \
  X(vkCreateCommandPool)              \
  X(vkDestroyCommandPool)             \
  X(vkAllocateCommandBuffers)         \
  X(vkBeginCommandBuffer)             \
  X(vkEndCommandBuffer)               \
  X(vkCmdBindPipeline)                \
  X(vkCmdBindDescriptorSets)          \
  X(vkCmdPushConstants)               \
  X(vkCmdDispatch)                    \
  X(vkCmdCopyBuffer)                  \
  X(vkCmdFillBuffer)                  \
  X(vkCreateQueryPool)                \
  X(vkDestroyQueryPool)               \
  X(vkCmdResetQueryPool)              \
  X(vkCmdWriteTimestamp)              \
  X(vkGetQueryPoolResults)            \
  X(vkCmdPipelineBarrier)             \
  X(vkQueueSubmit)                    \
  X(vkCreateFence)                    \
  X(vkDestroyFence)                   \
  X(vkWaitForFences)                  \
  X(vkResetFences)

#define PRISM_VK_DECLARE(name) PFN_##name name = nullptr;

struct Api {
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
  PRISM_VK_GLOBAL_FUNCTIONS(PRISM_VK_DECLARE)
  PRISM_VK_INSTANCE_FUNCTIONS(PRISM_VK_DECLARE)
  PRISM_VK_DEBUG_FUNCTIONS(PRISM_VK_DECLARE)
  PRISM_VK_DEVICE_FUNCTIONS(PRISM_VK_DECLARE)

  // Opens the loader ($PRISM_VULKAN_LOADER, else libvulkan.so.1) and fills
  // the global functions. Throws RuntimeError naming what is missing.
  void load_global();
  void load_instance(VkInstance instance);
  void load_device(VkDevice device);
};

#undef PRISM_VK_DECLARE

// A zeroed Vulkan structure with its sType set.
template <class T>
T make(VkStructureType type) {
  T value{};
  value.sType = type;
  return value;
}

// "VK_ERROR_DEVICE_LOST" and the like.
const char* result_name(VkResult result);

// Throws RuntimeError unless `result` is VK_SUCCESS: "Vulkan failed during
// <what>: <what the result means>", with device loss and out-of-memory told
// in words.
void check(VkResult result, const std::string& what);

}  // namespace prism::vk
