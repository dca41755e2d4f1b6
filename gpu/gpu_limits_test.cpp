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
// buffer fits the device's storage-block limit (GL's smallest, 2^24 bytes,
// and a GPU's 2 GiB) and whose dispatch stays within 65535 work groups per
// dimension, for a CPU driver's budget and a GPU's.
TEST(GpuLimits, TilesFitTheSmallestLimitsOfEveryDevice) {
  for (bool cpu : {true, false}) {
    for (size_t limit : {size_t(1) << 24, size_t(1) << 31}) {
      const TileBudget budget = tile_budget(cpu, limit, 1);
      for (int width : {1, 7, 8, 9, 511, 512, 513, 1920, 4097, 16384}) {
        for (int height : {1, 8, 9, 1080, 4097, 16384}) {
          for (int spp : {1, 2, 3, 63, 64, 65, 4095, 4096}) {
            ImageSettings image;
            image.width = width;
            image.height = height;
            image.spp = spp;
            const auto [tw, th] = tile_size(image, budget);
            const size_t pixels = size_t(tw) * size_t(th);
            EXPECT_LE(pixels, size_t(cpu ? 1 << 18 : 1 << 21)) << width << "x" << height << " spp " << spp;
            EXPECT_LE(output_bytes(pixels, kMaxOutputPlanes), limit);
            EXPECT_LE((th + kRenderLocalSize - 1) / kRenderLocalSize, 65535);
            EXPECT_LE((tw + kRenderLocalSize - 1) / kRenderLocalSize, 65535);
          }
        }
      }
    }
  }
}

// A GPU renders 1920x1080 at 1 spp in one tile; a CPU driver in 512x512-ish
// tiles of 2^18 samples (512 x 512 = 2^18).
TEST(GpuLimits, AGpuTakesAFullHdFrameInOneTile) {
  ImageSettings image;
  image.width = 1920;
  image.height = 1080;
  image.spp = 1;
  image.max_depth = 5;
  EXPECT_EQ(tile_size(image, tile_budget(false, size_t(1) << 31, 3)), std::make_pair(1920, 1080));
  EXPECT_EQ(tile_size(image, tile_budget(true, size_t(1) << 31, 3)), std::make_pair(512, 512));
  // 2^24 bytes hold (2^24 - 32) / 48 = 349524 pixels of three planes: 1920 x 176.
  EXPECT_EQ(tile_size(image, tile_budget(false, size_t(1) << 24, 3)), std::make_pair(1920, 176));
}

// A backend with two tiles in flight (OpenGL on a GPU) asks for at least two
// bands: 1080 rows in bands of ceil(1080 / 2) = 540 rounded up to the work
// group's 8, 544 (so two tiles, not three); a frame of 9 rows in bands of 8.
TEST(GpuLimits, TwoTilesInFlightCutAFrameIntoTwoBands) {
  ImageSettings image;
  image.width = 1920;
  image.height = 1080;
  image.spp = 1;
  image.max_depth = 5;
  EXPECT_EQ(tile_size(image, tile_budget(false, size_t(1) << 31, 3, 2)), std::make_pair(1920, 544));
  image.height = 9;
  EXPECT_EQ(tile_size(image, tile_budget(false, size_t(1) << 31, 3, 2)), std::make_pair(1920, 8));
  // A CPU driver's tiles are small already: two bands change nothing there.
  image.height = 1080;
  EXPECT_EQ(tile_size(image, tile_budget(true, size_t(1) << 31, 3, 2)), std::make_pair(512, 512));
}

// 32-bit ray counters: a tile holds fewer than 2^32 rays of one kind, at most
// max_depth * lights a sample. Depth 64 and 4096 lights: 2^18 rays a sample,
// so at most 16383 samples a tile (2^32 / (2^18 + 1) = 16383.9): 512-pixel
// rows (a CPU-sized tile), 31 of them rounded down to the work group's 8: 24.
TEST(GpuLimits, TilesAreCutSoThatRayCountersCannotOverflow) {
  ImageSettings image;
  image.width = 1024;
  image.height = 1024;
  image.spp = 1;
  image.max_depth = 64;
  const auto [tw, th] = tile_size(image, tile_budget(false, size_t(1) << 31, 4096));
  EXPECT_LE(size_t(tw) * size_t(th), size_t(16384));
  EXPECT_EQ(tw, 512);
  EXPECT_EQ(th, 24);
}

}  // namespace
}  // namespace prism::gpu
