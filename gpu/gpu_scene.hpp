// A scene packed for the GPU kernels: the buffers of gpu_layout.hpp, the
// primitive types the kernel needs, and the features it must compile in.
// Shared by the OpenGL and Vulkan backends.
#pragma once

#include <cstdint>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh.hpp"
#include "gpu_layout.hpp"
#include "prism/backend.hpp"
#include "prism/scene.hpp"

namespace prism::gpu {

// What a scene uses, each a switch of the generated kernel (PRISM_FEATURE_*).
enum class Feature {
  PointLights,
  DirectionalLights,
  LightSpheres,
  Specular,
  Reflection,
  Dielectrics,
  Absorption,
  Textures,
  Alpha,
  Skybox,
};
const std::vector<Feature>& all_features();
const char* feature_name(Feature f);    // "point_lights", ...
std::string feature_macro(Feature f);   // "PRISM_FEATURE_POINT_LIGHTS"

struct PackedScene {
  std::vector<const PrismPrimitiveDesc*> types;  // kernel type index -> plugin
  std::set<Feature> features;
  std::vector<double> records;
  std::vector<GpuObject> objects;  // BVH leaf order, then unbounded objects
  std::vector<GpuNode> nodes;
  std::vector<GpuMaterial> materials;
  std::vector<GpuLight> lights;
  std::vector<glm::vec4> texels;
  GpuFrame frame{};  // scene constants; camera and image fields filled per render
  int bounded_objects = 0;
  int bvh_depth = 0;
  // At most kUnrolledObjects objects: the kernel tests every object in turn,
  // each with its slot and record fixed in the source (gpu/scene.glsl,
  // PRISM_UNROLLED_OBJECTS), instead of walking the BVH.
  bool unrolled = false;

  // What a live update (gpu_update.hpp) changes the packing with, in place.
  Bvh bvh;                                // the host tree, double bounds; nodes[i] packs bvh.nodes[i]
  std::vector<Box3> boxes;                // per bounded object, as the tree last saw it (the BVH's input)
  std::vector<uint32_t> bounded_ids;      // the BVH's input index -> object id
  std::vector<uint32_t> slot_of;          // object id -> its index in `objects`
  std::vector<int32_t> texture_offset;    // per scene texture: its first texel
  std::vector<uint8_t> texture_alpha;     // per scene texture: 1 when a texel is transparent

  // A float world (PRISM_WORLD_FLOAT: gpu/scene.glsl): the kernels hold no
  // double, and read these copies of the buffers that carry positions or
  // numbers of the plugins' records: positions relative to `anchor`,
  // subtracted in double, then rounded (boxes outward).
  bool float_world = false;
  glm::dvec3 anchor{0};
  std::vector<float> records_f;
  std::vector<GpuObjectF> objects_f;
  std::vector<GpuNode> nodes_f;
  std::vector<GpuLightF> lights_f;

  // Bytes of the buffers the kernel reads (records, objects, BVH, materials, lights, texels).
  size_t buffer_bytes() const;
};

// Makes `packed` a float world anchored at `anchor` (the float copies made
// from the double buffers), or a double one.
void set_world(PackedScene& packed, bool float_world, const glm::dvec3& anchor = glm::dvec3(0));
// Makes the float copies again from the double buffers (after an update).
void refresh_float_world(PackedScene& packed);

// Up to this many objects the kernel tests them all in turn, unrolled (measured:
// docs/architecture.md, "Objects unrolled"); above it walks the BVH.
constexpr size_t kUnrolledObjects = 16;
// kUnrolledObjects, or PRISM_GPU_UNROLLED_OBJECTS (0 to 64) to measure the
// crossover again.
size_t unrolled_objects_limit();

// Up to this many lights the kernel reads each at a fixed offset (prism_light, gpu/scene.glsl).
constexpr size_t kLightsByConstant = 16;

// What of the packing the generated kernel's source holds (its slots' types,
// records, ids and rotations when unrolled; the light and material counts):
// a change there needs a new kernel.
std::vector<uint32_t> kernel_layout(const PackedScene& packed);

// Packs `scene`. Throws RuntimeError when an object's plugin has no GLSL.
// Types in `type_order` that the scene still uses keep their kernel index
// order (a repack after an edit then generates the same kernel); others
// follow in the order the BVH's leaves meet them.
PackedScene pack_scene(const Scene& scene, std::span<const PrismPrimitiveDesc* const> type_order = {});

// The storage buffers that hold the scene: bindings 0 .. kSceneBufferCount - 1.
constexpr uint32_t kSceneBufferCount = kBindFrame;
struct SceneBuffer {
  const void* data;
  size_t count;          // elements
  size_t element_bytes;
  const char* name;      // "object records", "objects", "BVH", "materials", "lights", "texels"
  size_t bytes() const { return count * element_bytes; }
};
SceneBuffer scene_buffer(const PackedScene& packed, uint32_t binding);

// How many planes of the render output a frame fills: 1 (rgb and id), or
// all 3 when it asks for the path, normal, albedo or depth AOV.
int output_planes(const RenderSettings& settings);

// The per-render part of the frame: camera, image size, samples, flags.
GpuFrame frame_for(const PackedScene& packed, const Camera& camera, const RenderSettings& settings);
std::vector<glm::dvec2> sample_offsets(int spp);
// The frame buffer's bytes: the frame and the sample offsets, in the
// packing's world precision (a float world's relative to its anchor).
std::vector<unsigned char> frame_bytes(const PackedScene& packed, const GpuFrame& frame,
                                       const std::vector<glm::dvec2>& offsets);

}  // namespace prism::gpu
