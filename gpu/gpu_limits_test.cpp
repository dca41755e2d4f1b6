// A scene too large for a device's storage buffers is refused with the part
// of the scene that fills the buffer and the limit, checked here with literal
// sizes (llvmpipe's and lavapipe's limit is 134217728 bytes), without a
// device or a scene of a million objects. The per-frame buffers and dispatch
// sizes stay within what every GL 4.3 or Vulkan device allows.
#include "gpu_limits.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "gpu_dispatch.hpp"
#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"

namespace prism::gpu {
namespace {

const std::string kGl = "this OpenGL driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE";

TEST(GpuLimits, ObjectsOverTheStorageBufferLimitNameThePathAndTheLimit) {
  // 838861 objects of 160 bytes are 32 bytes over 128 MiB.
  const std::vector<BufferNeed> needs = {{"objects", "objects", 838861, 160, 2147483647}};
  EXPECT_EQ(buffer_limit_error(needs, 134217728, kGl),
            "objects: 838861 objects need a 134217760-byte storage buffer, more than this OpenGL driver's "
            "GL_MAX_SHADER_STORAGE_BLOCK_SIZE of 134217728 bytes");
}

TEST(GpuLimits, ABufferExactlyAtTheLimitFits) {
  const std::vector<BufferNeed> needs = {{"objects", "objects", 838860, 160, 2147483647},
                                         {"textures", "texels", 8388608, 16, 2147483647}};
  EXPECT_EQ(buffer_limit_error(needs, 134217728, kGl), "");
}

TEST(GpuLimits, TheFirstBufferOverTheLimitIsNamed) {
  const std::vector<BufferNeed> needs = {{"objects", "objects", 10, 160, 2147483647},
                                         {"materials", "materials (the default one included)", 1677722, 80, 2147483647},
                                         {"textures", "texels", 8388609, 16, 2147483647}};
  EXPECT_EQ(buffer_limit_error(needs, 134217728, "this Vulkan device's maxStorageBufferRange"),
            "materials: 1677722 materials (the default one included) need a 134217760-byte storage buffer, more "
            "than this Vulkan device's maxStorageBufferRange of 134217728 bytes");
}

TEST(GpuLimits, MoreElementsThanA32BitIndexAddressesAreRefusedWhateverTheDevice) {
  const std::vector<BufferNeed> needs = {{"objects", "numbers in object records", 4294967296, 8, 4294967295}};
  EXPECT_EQ(buffer_limit_error(needs, uint64_t(1) << 40, kGl),
            "objects: 4294967296 numbers in object records are more than the kernel's 32-bit indices address "
            "(4294967295)");
}

TEST(GpuLimits, EveryBufferOfAPackedSceneIsChecked) {
  Registry registry;
  const Scene scene = load_scene_from_string(R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"red": {"color": [1, 0, 0]}},
    "lights": [{"type": "directional", "direction": [0, -1, 0]}],
    "objects": [{"type": "sphere", "radius": 1, "material": "red"}, {"type": "sphere", "center": [2, 0, 0], "radius": 0.5},
                {"type": "plane", "point": [0, -1, 0], "normal": [0, 1, 0]}]})",
                                             ".", registry, "scene.json");
  const PackedScene packed = pack_scene(scene);
  const std::vector<BufferNeed> needs = buffer_needs(packed);
  ASSERT_EQ(needs.size(), 6u);
  EXPECT_EQ(needs[0].path, "objects");
  EXPECT_EQ(needs[0].count, 3u);
  EXPECT_EQ(needs[0].element_bytes, 160u);
  EXPECT_EQ(needs[3].path, "materials");
  EXPECT_EQ(needs[3].count, 2u);
  EXPECT_EQ(needs[4].path, "lights");
  EXPECT_EQ(needs[4].count, 1u);
  EXPECT_EQ(needs[5].path, "textures");
  EXPECT_EQ(needs[5].count, 0u);
  EXPECT_NO_THROW(check_buffer_limits(packed, "scene.json", 134217728, kGl));
  try {
    check_buffer_limits(packed, "scene.json", 479, "a test limit");
    FAIL() << "480 bytes of objects passed a 479-byte limit";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scene.json: objects: 3 objects need a 480-byte storage buffer, more than a test limit of "
                           "479 bytes");
  }
}

// Every image size and spp the format allows cuts into tiles whose output
// buffer fits GL's smallest storage-block limit (2^24 bytes) and whose
// dispatch stays within 65535 work groups per dimension.
TEST(GpuLimits, TilesFitTheSmallestLimitsOfEveryDevice) {
  for (int width : {1, 7, 8, 9, 511, 512, 513, 4097, 16384}) {
    for (int height : {1, 8, 9, 4097, 16384}) {
      for (int spp : {1, 2, 3, 63, 64, 65, 4095, 4096}) {
        ImageSettings image;
        image.width = width;
        image.height = height;
        image.spp = spp;
        const auto [tw, th] = tile_size(image);
        EXPECT_LE(size_t(tw) * size_t(th), size_t(1) << 18) << width << "x" << height << " spp " << spp;
        EXPECT_LE(kOutputHeaderBytes + size_t(tw) * size_t(th) * sizeof(GpuPixel), size_t(1) << 24);
        EXPECT_LE((th + kRenderLocalSize - 1) / kRenderLocalSize, 65535);
        EXPECT_LE((tw + kRenderLocalSize - 1) / kRenderLocalSize, 65535);
      }
    }
  }
}

}  // namespace
}  // namespace prism::gpu
