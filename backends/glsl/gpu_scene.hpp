// A scene packed for the GPU kernels: the buffers of gpu_layout.hpp, the
// primitive types the kernel needs, and the features it must compile in.
// Shared by the OpenGL and Vulkan backends.
#pragma once

#include <cstdint>
#include <set>
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
  // Bytes of the buffers the kernel reads (records, objects, BVH, materials, lights, texels).
  size_t buffer_bytes() const;
};

// Packs `scene`. Throws RuntimeError when an object's plugin has no GLSL.
PackedScene pack_scene(const Scene& scene);

// The per-render part of the frame: camera, image size, samples, flags.
GpuFrame frame_for(const PackedScene& packed, const Camera& camera, const RenderSettings& settings);
std::vector<glm::dvec2> sample_offsets(int spp);

}  // namespace prism::gpu
