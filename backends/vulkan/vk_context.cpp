#include "vk_context.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "prism/errors.hpp"

namespace prism::vk {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr const char* kNoDriver =
    "no Vulkan driver (ICD) with a device was found; on Debian install mesa-vulkan-drivers, or a GPU vendor's driver";

std::string version_text(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

const char* type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU device";
    default: return "device";
  }
}

// Lower is preferred.
int type_preference(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

bool has_layer(const Api& api, const char* name) {
  uint32_t count = 0;
  api.vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  api.vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

struct Candidate {
  VkPhysicalDevice handle;
  VkPhysicalDeviceProperties properties;
  uint32_t index;
  uint32_t queue_family;
  uint32_t timestamp_bits;  // the queue's timestampValidBits (0: no timestamps)
  bool float64;         // shaderFloat64, unless hidden_float64()
  std::string problem;  // empty when suitable
};

// PRISM_VULKAN_HIDE_FLOAT64=1 makes every device look as if it lacked
// shaderFloat64, so that the float-only path is tested on a device that has it.
bool hidden_float64() { return env_number("PRISM_VULKAN_HIDE_FLOAT64", 0.0, 0.0, 1.0) == 1.0; }

Candidate examine(const Api& api, VkPhysicalDevice device, uint32_t index) {
  Candidate c{device, {}, index, 0, 0, false, {}};
  api.vkGetPhysicalDeviceProperties(device, &c.properties);
  VkPhysicalDeviceFeatures features{};
  api.vkGetPhysicalDeviceFeatures(device, &features);
  uint32_t count = 0;
  api.vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  api.vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  auto compute = std::find_if(families.begin(), families.end(),
                              [](const VkQueueFamilyProperties& f) { return f.queueFlags & VK_QUEUE_COMPUTE_BIT; });
  if (c.properties.apiVersion < VK_API_VERSION_1_2)
    c.problem = "supports Vulkan " + version_text(c.properties.apiVersion) + ", Prism needs 1.2";
  else if (compute == families.end())
    c.problem = "has no compute queue";
  else {
    c.queue_family = uint32_t(compute - families.begin());
    c.timestamp_bits = compute->timestampValidBits;
  }
  c.float64 = features.shaderFloat64 && !hidden_float64();
  return c;
}

}  // namespace

bool validation_requested() { return env_number("PRISM_VULKAN_VALIDATION", 0.0, 0.0, 1.0) == 1.0; }

Context::Context(bool validation) {
  api_.load_global();
  create_instance(validation);
  choose_device();
  create_device();
}

Context::~Context() {
  if (abandoned_) return;  // a hung or lost device: leave it to the process exit
  if (device_) {
    api_.vkDeviceWaitIdle(device_);
    api_.vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) api_.vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
  if (instance_) api_.vkDestroyInstance(instance_, nullptr);
}

VkBool32 Context::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  auto* context = static_cast<Context*>(self);
  std::string text = std::string(severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning") +
                     ": " + (data && data->pMessage ? data->pMessage : "(no message)");
  std::fprintf(stderr, "prism: Vulkan validation %s\n", text.c_str());
  std::lock_guard lock(context->messages_mutex_);
  context->messages_.push_back(std::move(text));
  return VK_FALSE;
}

void Context::create_instance(bool validation) {
  uint32_t loader_version = VK_API_VERSION_1_0;
  api_.vkEnumerateInstanceVersion(&loader_version);
  if (loader_version < VK_API_VERSION_1_2)
    throw RuntimeError("the Vulkan loader supports Vulkan " + version_text(loader_version) + ", Prism needs 1.2");
  if (validation && !has_layer(api_, kValidationLayer))
    throw RuntimeError(std::string("PRISM_VULKAN_VALIDATION is set but the ") + kValidationLayer +
                       " layer is not installed (Debian: vulkan-validationlayers)");

  auto app = make<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "prism";
  app.pEngineName = "prism";
  app.apiVersion = VK_API_VERSION_1_2;
  auto info = make<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  info.pApplicationInfo = &app;

  // Validation: the layer, synchronisation validation, and a messenger that
  // is also chained into instance creation so that nothing goes unseen.
  const char* layers[] = {kValidationLayer};
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  auto features = make<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  auto messenger = make<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
  messenger.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = &Context::on_message;
  messenger.pUserData = this;
  if (validation) {
    features.pNext = &messenger;
    info.pNext = &features;
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
  }
  const VkResult created = api_.vkCreateInstance(&info, nullptr, &instance_);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER) throw RuntimeError(kNoDriver);
  check(created, "instance creation");
  api_.load_instance(instance_);
  if (validation) {
    // The loader unloads the layer with the last instance, while the layer
    // still holds process-wide state referenced from its own globals; kept
    // loaded, that state stays reachable instead of looking leaked to the
    // sanitizer build's leak check.
    dlopen("libVkLayer_khronos_validation.so", RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    if (!api_.vkCreateDebugUtilsMessengerEXT) throw RuntimeError("the validation layer offers no VK_EXT_debug_utils");
    check(api_.vkCreateDebugUtilsMessengerEXT(instance_, &messenger, nullptr, &messenger_), "messenger creation");
  }
}

void Context::choose_device() {
  uint32_t count = 0;
  check(api_.vkEnumeratePhysicalDevices(instance_, &count, nullptr), "device enumeration");
  std::vector<VkPhysicalDevice> devices(count);
  check(api_.vkEnumeratePhysicalDevices(instance_, &count, devices.data()), "device enumeration");
  if (devices.empty()) throw RuntimeError(kNoDriver);
  std::vector<Candidate> candidates;
  for (uint32_t i = 0; i < devices.size(); ++i) candidates.push_back(examine(api_, devices[i], i));

  const char* wanted = std::getenv("PRISM_VULKAN_DEVICE");
  std::string listing;
  for (const Candidate& c : candidates)
    listing += "\n  " + std::to_string(c.index) + ": " + c.properties.deviceName +
               (c.problem.empty() ? (c.float64 ? "" : " (no shaderFloat64: float kernels only)") : " (" + c.problem + ")");
  if (wanted && *wanted) {
    const std::string w = wanted;
    const bool by_index = std::all_of(w.begin(), w.end(), [](unsigned char ch) { return std::isdigit(ch); });
    std::erase_if(candidates, [&](const Candidate& c) {
      return by_index ? std::to_string(c.index) != w : lower(c.properties.deviceName).find(lower(w)) == std::string::npos;
    });
    if (candidates.empty())
      throw RuntimeError("PRISM_VULKAN_DEVICE=" + w + " matches no Vulkan device; there are:" + listing);
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return type_preference(a.properties.deviceType) < type_preference(b.properties.deviceType);
  });
  auto chosen = std::find_if(candidates.begin(), candidates.end(), [](const Candidate& c) { return c.problem.empty(); });
  if (chosen == candidates.end()) throw RuntimeError("no suitable Vulkan device:" + listing);
  physical_ = chosen->handle;
  properties_ = chosen->properties;
  queue_family_ = chosen->queue_family;
  timestamp_bits_ = chosen->timestamp_bits;
  float64_ = chosen->float64;
  api_.vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
}

void Context::create_device() {
  const float priority = 1.0f;
  auto queue = make<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  queue.queueFamilyIndex = queue_family_;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures features{};
  features.shaderFloat64 = float64_ ? VK_TRUE : VK_FALSE;
  auto info = make<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  info.pEnabledFeatures = &features;
  check(api_.vkCreateDevice(physical_, &info, nullptr, &device_), "device creation");
  api_.load_device(device_);
  api_.vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
}

std::string Context::description() const {
  return std::string(properties_.deviceName) + ", " + type_name(properties_.deviceType) + ", Vulkan " +
         version_text(properties_.apiVersion) + (float64_ ? "" : ", no shaderFloat64");
}

std::string Context::identity() const {
  char ids[32];
  std::snprintf(ids, sizeof ids, "%08x:%08x", properties_.vendorID, properties_.deviceID);
  return std::string(properties_.deviceName) + " " + ids + (float64_ ? "" : " no-fp64");
}

size_t Context::validation_message_count() const {
  std::lock_guard lock(messages_mutex_);
  return messages_.size();
}

std::vector<std::string> Context::validation_messages() const {
  std::lock_guard lock(messages_mutex_);
  return messages_;
}

}  // namespace prism::vk
