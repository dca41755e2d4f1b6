// The parts pack_scene (gpu_scene.cpp) is made of, for update_packed_scene
// (gpu_update.cpp) to redo only those a change touches. Internal to gpu/.
#pragma once

#include <cstdint>
#include <set>
#include <span>
#include <vector>

#include "gpu_scene.hpp"

namespace prism::gpu::detail {

// texels, texture_offset and texture_alpha.
void pack_textures(const Scene& scene, PackedScene& out);
// Needs the texture offsets.
std::vector<GpuMaterial> pack_materials(const Scene& scene, const PackedScene& packed);
std::vector<GpuLight> pack_lights(const Scene& scene);
// The frame's scene constants: ambient, shadow ambient, background, cubemap faces.
void pack_environment(const Scene& scene, PackedScene& out);
// What the kernel must compile in: the lights' kinds, the background, and
// the materials objects use (needs texture_alpha).
std::set<Feature> scene_features(const Scene& scene, const PackedScene& packed);
// types, records, objects, nodes and the BVH with what updates it (bvh,
// boxes, bounded_ids, slot_of), all made again. `type_order`: as pack_scene's.
void pack_objects(const Scene& scene, std::span<const PrismPrimitiveDesc* const> type_order, PackedScene& out);
// An object's GPU entry; `record` is the index of its record's first double.
GpuObject object_entry(const Object& object, size_t id, uint32_t type, uint32_t record);
// A node with its bounds, relative to `anchor`, rounded outward to float.
GpuNode node_entry(const BvhNode& node, const glm::dvec3& anchor = glm::dvec3(0));
// The frame's element counts (objects, bounded objects, lights, nodes).
void set_counts(PackedScene& out);

}  // namespace prism::gpu::detail
