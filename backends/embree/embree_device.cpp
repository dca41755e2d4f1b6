#include "embree_device.hpp"

#include "prism/errors.hpp"

namespace prism::embree {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
  }
  return "unknown Embree error";
}

namespace {

// Embree's 512-bit kernels were slower than its AVX2 kernels on AMD Zen 4,
// whose vector unit splits 512-bit operations in two: the 100,000-sphere
// scene (all Embree traversal) took ~7 % less processor time a frame with
// the cap, in six interleaved pairs of 30-frame benches; the showcase, whose
// rays rarely enter Embree, was unchanged, and every image is the same bit
// for bit (the padding argument of embree_query.cpp holds for any float
// traversal). Intel processors, for which those kernels were written, keep
// Embree's own choice. max_isa only lowers the ceiling: a processor without
// AVX2 still gets the best kernels it has.
bool cap_at_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_is("amd") != 0;
#else
  return false;
#endif
}

}  // namespace

Device::Device() : capped_at_avx2_(cap_at_avx2()) {
  // "verbose=0": Embree prints nothing; errors come through on_error.
  device_ = rtcNewDevice(capped_at_avx2_ ? "verbose=0,max_isa=avx2" : "verbose=0");
  if (device_ == nullptr) {
    throw RuntimeError(std::string("Embree: cannot create a device (") +
                       error_name(rtcGetDeviceError(nullptr)) + ")");
  }
  rtcSetDeviceErrorFunction(device_, &Device::on_error, this);
  rtcSetDeviceMemoryMonitorFunction(device_, &Device::on_memory, this);
}

bool Device::on_memory(void* self, ssize_t bytes, bool) {
  static_cast<Device*>(self)->bytes_ += bytes;  // negative when Embree frees
  return true;                                  // never refuse an allocation
}

Device::~Device() { rtcReleaseDevice(device_); }

void Device::on_error(void* self, RTCError code, const char* message) {
  auto* device = static_cast<Device*>(self);
  std::lock_guard lock(device->mutex_);
  if (device->error_.empty()) {
    device->error_ = std::string(error_name(code)) + (message != nullptr ? ": " : "") +
                     (message != nullptr ? message : "");
  }
}

void Device::check(const char* what) {
  std::string error;
  {
    std::lock_guard lock(mutex_);
    error.swap(error_);
  }
  if (!error.empty()) throw RuntimeError(std::string("Embree error during ") + what + ": " + error);
}

std::string Device::describe() const {
  const auto property = [this](RTCDeviceProperty p) { return rtcGetDeviceProperty(device_, p); };
  std::string text = std::to_string(property(RTC_DEVICE_PROPERTY_VERSION_MAJOR)) + "." +
                     std::to_string(property(RTC_DEVICE_PROPERTY_VERSION_MINOR)) + "." +
                     std::to_string(property(RTC_DEVICE_PROPERTY_VERSION_PATCH));
  std::string details;
  switch (property(RTC_DEVICE_PROPERTY_TASKING_SYSTEM)) {
    case 0: details = "tasking: internal"; break;
    case 1: details = "tasking: TBB"; break;
    case 2: details = "tasking: PPL"; break;
    default: break;
  }
  if (capped_at_avx2_) details += (details.empty() ? "" : ", ") + std::string("kernels up to AVX2");
  return details.empty() ? text : text + " (" + details + ")";
}

}  // namespace prism::embree
