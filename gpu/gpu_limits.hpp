// Whether a packed scene fits a device: every scene buffer the kernel reads
// is one storage buffer, and a device caps the size of one
// (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, Vulkan's maxStorageBufferRange; 128 MiB
// on llvmpipe and lavapipe). A scene over it is bad input for that backend:
// the backends refuse it in `prepare` with the part of the scene that fills
// the buffer, instead of letting the upload or the kernel fail.
//
// Textures are texels in a storage buffer too, never GL or Vulkan images, so
// GL_MAX_TEXTURE_SIZE and maxImageDimension2D do not apply. (The kernels
// read them through a buffer texture over that buffer where the texels fit
// GL_MAX_TEXTURE_BUFFER_SIZE / maxTexelBufferElements, and through the
// storage buffer otherwise: those limits never refuse a scene.) The per-frame
// buffers (frame constants, a tile's output, trace rays) are bounded by
// constants far below the smallest limit either API allows (see the .cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpu_scene.hpp"

namespace prism::gpu {

// One scene buffer: what fills it and how large it is.
struct BufferNeed {
  std::string path;     // the JSON path of what fills it: "objects", "materials", "lights", "textures"
  std::string what;     // what its elements are, for the message: "objects", "BVH nodes", ...
  size_t count;         // elements
  size_t element_bytes;
  size_t max_count;     // what the kernel's 32-bit indices can address
};

// The buffers of `packed`, in the order they are checked.
std::vector<BufferNeed> buffer_needs(const PackedScene& packed);

// The message for the first buffer that holds more elements than its index
// can address or needs more than `max_bytes`, the device's limit named by
// `limit_name` ("this OpenGL driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE");
// empty when every buffer fits.
std::string buffer_limit_error(std::span<const BufferNeed> needs, uint64_t max_bytes, const std::string& limit_name);

// Throws InputError with buffer_limit_error's message, after the scene's
// `source` (its file name), when it is not empty.
void check_buffer_limits(const PackedScene& packed, const std::string& source, uint64_t max_bytes,
                         const std::string& limit_name);

}  // namespace prism::gpu
