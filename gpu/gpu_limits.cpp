#include "gpu_limits.hpp"

#include <limits>

#include "gpu_dispatch.hpp"
#include "prism/errors.hpp"
#include "prism/limits.hpp"

namespace prism::gpu {

namespace {

// The smallest limits the APIs allow a device: GL 4.3 guarantees 2^24-byte
// storage blocks (Vulkan 2^27) and 65535 work groups per dimension (both).
constexpr uint64_t kGuaranteedStorageBytes = uint64_t(1) << 24;
constexpr uint64_t kGuaranteedWorkGroups = 65535;

// The per-frame buffers stay within those whatever the scene and flags, so
// only the scene buffers need checking against the device.
static_assert(sizeof(GpuFrame) + limits::kMaxSpp * sizeof(double[2]) <= kGuaranteedStorageBytes);
static_assert(kTraceRaysPerDispatch * sizeof(GpuTraceRay) <= kGuaranteedStorageBytes);
static_assert(kTraceRaysPerDispatch / kTraceLocalSize <= kGuaranteedWorkGroups);
static_assert(limits::kMaxImageSide / kRenderLocalSize <= kGuaranteedWorkGroups);
// Texel offsets are int32 in GpuMaterial and GpuFrame: the loader's limit keeps them in range.
static_assert(limits::kMaxTexturePixels <= size_t(std::numeric_limits<int32_t>::max()));

constexpr size_t kInt32Count = size_t(std::numeric_limits<int32_t>::max());
constexpr size_t kUint32Count = size_t(std::numeric_limits<uint32_t>::max());

}  // namespace

std::vector<BufferNeed> buffer_needs(const PackedScene& p) {
  // Objects carry int32 ids; records, nodes and materials are addressed by uint32.
  return {
      {"objects", "objects", p.objects.size(), sizeof(GpuObject), kInt32Count},
      {"objects", "numbers in object records", p.records.size(), sizeof(double), kUint32Count},
      {"objects", "BVH nodes", p.nodes.size(), sizeof(GpuNode), kUint32Count},
      {"materials", "materials (the default one included)", p.materials.size(), sizeof(GpuMaterial), kInt32Count},
      {"lights", "lights", p.lights.size(), sizeof(GpuLight), kInt32Count},
      {"textures", "texels", p.texels.size(), sizeof(glm::vec4), kInt32Count},
  };
}

std::string buffer_limit_error(std::span<const BufferNeed> needs, uint64_t max_bytes, const std::string& limit_name) {
  for (const BufferNeed& need : needs) {
    const std::string count = std::to_string(need.count) + " " + need.what;
    if (need.count > need.max_count)
      return need.path + ": " + count + " are more than the kernel's 32-bit indices address (" +
             std::to_string(need.max_count) + ")";
    // count <= 2^32 and element_bytes <= 160: the product cannot overflow 64 bits.
    const uint64_t bytes = uint64_t(need.count) * need.element_bytes;
    if (bytes > max_bytes)
      return need.path + ": " + count + " need a " + std::to_string(bytes) + "-byte storage buffer, more than " +
             limit_name + " of " + std::to_string(max_bytes) + " bytes";
  }
  return "";
}

void check_buffer_limits(const PackedScene& packed, const std::string& source, uint64_t max_bytes,
                         const std::string& limit_name) {
  const std::string error = buffer_limit_error(buffer_needs(packed), max_bytes, limit_name);
  if (!error.empty()) throw InputError(source.empty() ? error : source + ": " + error);
}

}  // namespace prism::gpu
