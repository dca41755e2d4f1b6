// An Embree device that turns Embree's errors into prism::RuntimeError.
// Embree reports errors through a callback that may run on any thread and
// inside Embree's own frames, where throwing is not allowed; the callback
// records the first message and check() throws it on the caller's side.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include <embree3/rtcore.h>

namespace prism::embree {

class Device {
 public:
  Device();  // throws RuntimeError when Embree cannot start here
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  RTCDevice get() const { return device_; }
  // Throws RuntimeError("Embree error during <what>: ...") when Embree has
  // reported an error since the last check.
  void check(const char* what);
  // "3.13.5 (tasking: TBB)", or "3.13.5 (tasking: TBB, kernels up to AVX2)"
  // where Embree's kernels are capped (on AMD processors; embree_device.cpp).
  std::string describe() const;
  // Bytes Embree holds now (its memory monitor's running total).
  int64_t bytes() const { return bytes_.load(); }

 private:
  static void on_error(void* self, RTCError code, const char* message);
  static bool on_memory(void* self, ssize_t bytes, bool post);
  bool capped_at_avx2_ = false;
  RTCDevice device_ = nullptr;
  std::mutex mutex_;
  std::string error_;  // first unreported error, empty when none
  std::atomic<int64_t> bytes_{0};
};

// Embree's name for an error code ("RTC_ERROR_OUT_OF_MEMORY").
const char* error_name(RTCError code);

}  // namespace prism::embree
