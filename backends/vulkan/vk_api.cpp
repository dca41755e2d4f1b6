#include "vk_api.hpp"

#include <dlfcn.h>

#include <cstdlib>

#include "prism/errors.hpp"

namespace prism::vk {

namespace {

// The loader stays open for the life of the process: drivers it loaded keep
// threads and atexit handlers that must not outlive their code.
void* open_loader() {
  const char* name = std::getenv("PRISM_VULKAN_LOADER");
  if (!name || !*name) name = "libvulkan.so.1";
  void* handle = dlopen(name, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw RuntimeError(std::string("no Vulkan loader (") + (why ? why : name) +
                       "); on Debian install libvulkan1 and a driver such as mesa-vulkan-drivers");
  }
  return handle;
}

template <class Fn>
void resolve(Fn& slot, void (*address)(), const char* name, bool required) {
  slot = reinterpret_cast<Fn>(address);
  if (!slot && required) throw RuntimeError(std::string("the Vulkan loader lacks ") + name);
}

}  // namespace

void Api::load_global() {
  void* loader = open_loader();
  vkGetInstanceProcAddr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(loader, "vkGetInstanceProcAddr"));
  if (!vkGetInstanceProcAddr) throw RuntimeError("the Vulkan loader has no vkGetInstanceProcAddr");
#define PRISM_VK_LOAD(name) resolve(name, vkGetInstanceProcAddr(nullptr, #name), #name, true);
  PRISM_VK_GLOBAL_FUNCTIONS(PRISM_VK_LOAD)
#undef PRISM_VK_LOAD
}

void Api::load_instance(VkInstance instance) {
#define PRISM_VK_LOAD(name) resolve(name, vkGetInstanceProcAddr(instance, #name), #name, true);
  PRISM_VK_INSTANCE_FUNCTIONS(PRISM_VK_LOAD)
#undef PRISM_VK_LOAD
  // Present only with VK_EXT_debug_utils enabled (validation runs).
#define PRISM_VK_LOAD(name) resolve(name, vkGetInstanceProcAddr(instance, #name), #name, false);
  PRISM_VK_DEBUG_FUNCTIONS(PRISM_VK_LOAD)
#undef PRISM_VK_LOAD
}

void Api::load_device(VkDevice device) {
#define PRISM_VK_LOAD(name) resolve(name, vkGetDeviceProcAddr(device, #name), #name, true);
  PRISM_VK_DEVICE_FUNCTIONS(PRISM_VK_LOAD)
#undef PRISM_VK_LOAD
}

const char* result_name(VkResult result) {
  switch (result) {
#define PRISM_VK_NAME(r) \
  case r: return #r;
    PRISM_VK_NAME(VK_SUCCESS)
    PRISM_VK_NAME(VK_NOT_READY)
    PRISM_VK_NAME(VK_TIMEOUT)
    PRISM_VK_NAME(VK_INCOMPLETE)
    PRISM_VK_NAME(VK_ERROR_OUT_OF_HOST_MEMORY)
    PRISM_VK_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    PRISM_VK_NAME(VK_ERROR_INITIALIZATION_FAILED)
    PRISM_VK_NAME(VK_ERROR_DEVICE_LOST)
    PRISM_VK_NAME(VK_ERROR_MEMORY_MAP_FAILED)
    PRISM_VK_NAME(VK_ERROR_LAYER_NOT_PRESENT)
    PRISM_VK_NAME(VK_ERROR_EXTENSION_NOT_PRESENT)
    PRISM_VK_NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    PRISM_VK_NAME(VK_ERROR_INCOMPATIBLE_DRIVER)
    PRISM_VK_NAME(VK_ERROR_TOO_MANY_OBJECTS)
    PRISM_VK_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED)
    PRISM_VK_NAME(VK_ERROR_FRAGMENTED_POOL)
    PRISM_VK_NAME(VK_ERROR_OUT_OF_POOL_MEMORY)
    PRISM_VK_NAME(VK_ERROR_INVALID_SHADER_NV)
#undef PRISM_VK_NAME
    default: return "an unknown VkResult";
  }
}

void check(VkResult result, const std::string& what) {
  if (result == VK_SUCCESS) return;
  std::string meaning;
  switch (result) {
    case VK_ERROR_DEVICE_LOST:
      meaning = "the device was lost (the driver crashed, reset the GPU or hit its watchdog)";
      break;
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: meaning = "out of device memory"; break;
    case VK_ERROR_OUT_OF_HOST_MEMORY: meaning = "out of host memory"; break;
    case VK_ERROR_INCOMPATIBLE_DRIVER: meaning = "no compatible Vulkan driver (ICD) is installed"; break;
    default: break;
  }
  const std::string name = result_name(result);
  throw RuntimeError("Vulkan failed during " + what + ": " + (meaning.empty() ? name : meaning + " (" + name + ")"));
}

}  // namespace prism::vk
