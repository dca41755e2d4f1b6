// Live updates of a packed scene, on the host: what update_packed_scene
// rewrites for each kind of change (the element runs each backend sends),
// when it refits and when it rebuilds the BVH, and when the kernel must be
// generated again. The packing after an update must match a fresh
// pack_scene of the edited scene wherever the two share a layout.
#include "gpu_update.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "gpu_update_test_scenes.hpp"
#include "prism/scene_loader.hpp"

namespace prism::gpu {
namespace {

using testing_scenes::Options;
using testing_scenes::spheres_json;

class PackedUpdateTest : public testing::Test {
 protected:
  Scene load(const Options& o) { return load_scene_from_string(spheres_json(o), ".", registry_, "<test scene>"); }
  Registry registry_;
};

bool same_bytes(const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(Runs, ConsecutiveIndicesMergeInAscendingOrder) {
  const std::vector<Range> expected = {{0, 1}, {3, 3}, {9, 2}};
  EXPECT_EQ(runs_of({5, 3, 4, 9, 9, 10, 0}), expected);
  EXPECT_TRUE(runs_of({}).empty());
}

TEST_F(PackedUpdateTest, AMovedSphereRewritesItsEntryAndRecordAndRefits) {
  Scene scene = load({});
  PackedScene packed = pack_scene(scene);
  const PackedScene before = packed;
  scene.objects[37] = load({.moved = 37}).objects[37];
  const PackedUpdate u = update_packed_scene(packed, scene, {.objects = {37}});

  EXPECT_TRUE(u.bvh_refitted);
  EXPECT_FALSE(u.bvh_built);
  EXPECT_FALSE(u.kernel);
  EXPECT_EQ(u.objects_written, 1u);
  const uint32_t slot = packed.slot_of[37];
  EXPECT_EQ(slot, before.slot_of[37]);  // nothing moves in the buffers
  const std::vector<Range> entry = {{slot, 1}};
  EXPECT_EQ(u.buffers[kBindObjects].runs, entry);
  const std::vector<Range> record = {{packed.objects[slot].record, 2}};  // a sphere's record: radius, padding
  EXPECT_EQ(u.buffers[kBindRecords].runs, record);
  EXPECT_FALSE(u.buffers[kBindNodes].whole);
  EXPECT_FALSE(u.buffers[kBindNodes].runs.empty());
  for (uint32_t b : {kBindMaterials, kBindLights, kBindTexels}) EXPECT_FALSE(u.buffers[b].any()) << b;

  // The entry is the one a fresh packing of the moved scene has (but for where its record sits).
  const PackedScene fresh = pack_scene(scene);
  GpuObject now = packed.objects[slot], expected = fresh.objects[fresh.slot_of[37]];
  expected.record = now.record;
  EXPECT_TRUE(same_bytes(now, expected));
  EXPECT_EQ(now.center[2], -2.0);
  // Every node sent matches the refitted tree; every other node is as it was.
  size_t sent = 0;
  for (const Range& run : u.buffers[kBindNodes].runs)
    for (size_t n = run.first; n < run.first + run.count; ++n, ++sent)
      EXPECT_FALSE(same_bytes(packed.nodes[n], before.nodes[n])) << n;
  size_t differ = 0;
  for (size_t n = 0; n < packed.nodes.size(); ++n) differ += !same_bytes(packed.nodes[n], before.nodes[n]);
  EXPECT_EQ(sent, differ);
  EXPECT_EQ(packed.frame.counts[3], int32_t(before.nodes.size()));
}

TEST_F(PackedUpdateTest, ManySpheresScatteringFarRebuildTheBvh) {
  Scene scene = load({});
  PackedScene packed = pack_scene(scene);
  const Scene scattered = load({.scattered_every = 5});
  SceneChanges changes;
  for (uint32_t i = 0; i < scene.objects.size(); i += 5) {
    scene.objects[i] = scattered.objects[i];
    changes.objects.push_back(i);
  }
  const PackedUpdate u = update_packed_scene(packed, scene, changes);
  EXPECT_TRUE(u.bvh_built);
  EXPECT_FALSE(u.bvh_refitted);
  EXPECT_EQ(u.objects_written, 200u);
  for (uint32_t b : {kBindRecords, kBindObjects, kBindNodes}) EXPECT_TRUE(u.buffers[b].whole) << b;
  const PackedScene fresh = pack_scene(scene);
  EXPECT_EQ(packed.bvh.nodes.size(), fresh.bvh.nodes.size());
  EXPECT_EQ(packed.bvh.built_cost, fresh.bvh.built_cost);
}

TEST_F(PackedUpdateTest, ALightChangeRewritesOnlyTheLights) {
  Scene scene = load({});
  PackedScene packed = pack_scene(scene);
  scene.lights = load({.light_x = -6}).lights;
  const PackedUpdate u = update_packed_scene(packed, scene, {.objects = {}, .lights = true});
  const std::vector<Range> light = {{0, 1}};
  EXPECT_EQ(u.buffers[kBindLights].runs, light);
  for (uint32_t b : {kBindRecords, kBindObjects, kBindNodes, kBindMaterials, kBindTexels}) EXPECT_FALSE(u.buffers[b].any()) << b;
  EXPECT_EQ(u.objects_written, 0u);
  EXPECT_FALSE(u.bvh_built || u.bvh_refitted || u.kernel);
  EXPECT_EQ(packed.lights[0].position[0], -6.0);
}

TEST_F(PackedUpdateTest, AMaterialTurningDielectricRegeneratesTheKernel) {
  Scene scene = load({});
  PackedScene packed = pack_scene(scene);
  EXPECT_EQ(packed.features.count(Feature::Dielectrics), 0u);
  scene.materials = load({.red_is_glass = true}).materials;
  const PackedUpdate u = update_packed_scene(packed, scene, {.objects = {}, .materials = true});
  EXPECT_TRUE(u.kernel);
  EXPECT_EQ(packed.features.count(Feature::Dielectrics), 1u);
  const std::vector<Range> red = {{1, 1}};  // after the default material
  EXPECT_EQ(u.buffers[kBindMaterials].runs, red);
  EXPECT_EQ(packed.materials[1].ior, 1.5f);
  EXPECT_EQ(u.objects_written, 0u);
}

// An unrolled kernel holds which objects are rotated (the unrotated ones
// skip the multiply): a sphere that moves keeps the kernel, one that gains
// a rotation needs a new one.
TEST_F(PackedUpdateTest, AnUnrolledObjectGainingARotationRegeneratesTheKernel) {
  Scene scene = load({.count = 4});
  PackedScene packed = pack_scene(scene);
  ASSERT_TRUE(packed.unrolled);
  scene.objects[1] = load({.count = 4, .moved = 1}).objects[1];
  EXPECT_FALSE(update_packed_scene(packed, scene, {.objects = {1}}).kernel);
  scene.objects[1].has_rotation = true;
  scene.objects[1].rotation = glm::dmat3(0, 1, 0, -1, 0, 0, 0, 0, 1);  // 90 degrees about z
  EXPECT_TRUE(update_packed_scene(packed, scene, {.objects = {1}}).kernel);
}

TEST_F(PackedUpdateTest, AnAddedSphereRebuildsTheBvhAndKeepsTheKernel) {
  Scene scene = load({});
  PackedScene packed = pack_scene(scene);
  scene.objects.push_back(load({.count = 201}).objects[200]);
  const PackedUpdate u = update_packed_scene(packed, scene, {.objects = {}, .objects_added_or_removed = true});
  EXPECT_TRUE(u.bvh_built);
  EXPECT_FALSE(u.kernel);
  EXPECT_EQ(u.objects_written, 201u);
  EXPECT_EQ(packed.frame.counts[0], 201);
  EXPECT_EQ(packed.slot_of.size(), 201u);
}

TEST_F(PackedUpdateTest, AnObjectTurningUnboundedIsPackedAgain) {
  Scene scene = load({});
  PackedScene packed = pack_scene(scene);
  const Scene with_plane = load_scene_from_string(
      R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "objects": [{"type": "plane", "point": [0, -6, 0], "normal": [0, 1, 0]}]})", ".", registry_);
  scene.objects[3] = with_plane.objects[0];
  const PackedUpdate u = update_packed_scene(packed, scene, {.objects = {3}});
  EXPECT_TRUE(u.bvh_built);
  EXPECT_TRUE(u.kernel);  // a plane's intersector joins the kernel
  EXPECT_EQ(packed.bounded_objects, 199);
  EXPECT_EQ(packed.slot_of[3], 199u);  // unbounded objects follow the BVH's leaves
  ASSERT_EQ(packed.types.size(), 2u);
  EXPECT_EQ(packed.types[0], scene.objects[0].desc);  // the sphere keeps its kernel index
}

}  // namespace
}  // namespace prism::gpu
