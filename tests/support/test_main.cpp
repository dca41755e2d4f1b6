// The main() of every Prism test executable: GoogleTest's, with Vulkan's
// validation layer on, plus one thing for the sanitizer build.
//
// PRISM_VULKAN_VALIDATION=1 (unless the environment says otherwise) puts the
// Khronos validation layer under every Vulkan render and trace the tests
// make, in process or in a `prism` child: the backend then fails any
// operation that drew a validation message.
//
// Sanitizer build: the leak check runs here, after the tests and before
// exit() tears down the threads that libraries loaded with dlopen started
// (OpenImageIO's log4cplus pool, GL and Vulkan drivers), so LeakSanitizer
// scans a quiet process; it then skips its own check at exit. (The tracer
// crashes CI saw came from LeakSanitizer's dynamic-TLS tracking; see
// scripts/test.sh for the option that ends them.)
#include <gtest/gtest.h>

#include <cstdlib>

#if defined(__SANITIZE_ADDRESS__)
#define PRISM_HAS_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PRISM_HAS_LSAN 1
#endif
#endif

#ifdef PRISM_HAS_LSAN
#include <sanitizer/lsan_interface.h>
#endif

int main(int argc, char** argv) {
  ::setenv("PRISM_VULKAN_VALIDATION", "1", 0);
  testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
#ifdef PRISM_HAS_LSAN
  __lsan_do_leak_check();
#endif
  return status;
}
