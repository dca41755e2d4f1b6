// The main() of every Prism test executable: GoogleTest's, with Vulkan's
// validation layer on.
//
// PRISM_VULKAN_VALIDATION=1 (unless the environment says otherwise) puts the
// Khronos validation layer under every Vulkan render and trace the tests
// make, in process or in a `prism` child: the backend then fails any
// operation that drew a validation message.
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
  ::setenv("PRISM_VULKAN_VALIDATION", "1", 0);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
