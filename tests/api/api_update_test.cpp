// Live updates through the API: after an edit a renderer sends its backend
// only what changed, says so in its counters, and renders exactly what a
// renderer starting from scratch renders of the edited scene.
#include <cstring>

#include "prism/api.hpp"
#include "test_support.hpp"

namespace prism::test {
namespace {

class ApiUpdate : public BackendTest {};

bool has_bvh(const std::string& backend) { return backend != "reference"; }

// A grid of `n` small spheres over a floor, lit, seen from above.
std::vector<ObjectId> sphere_field(LiveScene& scene, int n, int width) {
  scene.set_camera({.position = {0, 60, 60}, .look_at = {0, 0, 0}, .fov_y = 50});
  scene.set_image({.width = width, .height = width * 3 / 4, .spp = 1, .max_depth = 2});
  scene.set_material("red", {.color = {0.8, 0.2, 0.1}, .specular = 0.3});
  scene.add_light(PointLight{.position = {10, 40, 20}});
  scene.add_object("plane", {{"point", glm::dvec3{0, -0.5, 0}}, {"normal", glm::dvec3{0, 1, 0}}});
  std::vector<ObjectId> ids;
  const int side = int(std::ceil(std::sqrt(double(n))));
  for (int i = 0; i < n; ++i) {
    const double x = (i % side - side / 2) * 0.5, z = (i / side - side / 2) * 0.5;
    ids.push_back(scene.add_object("sphere", {{"center", glm::dvec3{x, 0, z}}, {"radius", 0.2}}, "red"));
  }
  return ids;
}

void expect_same_pixels(const Image& a, const Image& b) {
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) differing += std::memcmp(&a.rgb[i], &b.rgb[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u) << "of " << a.rgb.size() << " channel values";
}

// The edited scene rendered from scratch: saved and loaded again, so no
// state of the live scene or of the first renderer is shared.
Image from_scratch(Engine& engine, const LiveScene& scene, const std::string& backend) {
  const auto file = fresh_temp_dir() / "edited.json";
  scene.save(file);
  LiveScene fresh = LiveScene::load(engine, file);
  Renderer renderer(engine, backend);
  return renderer.render(fresh);
}

TEST_P(ApiUpdate, MovingOneSphereOfTenThousandSendsOneObjectAndRefits) {
  const std::string backend = GetParam();
  Engine engine;
  LiveScene scene(engine);
  // The brute-force reference pays per object per ray: a smaller picture.
  const auto ids = sphere_field(scene, 10000, backend == "reference" ? 24 : 64);
  Renderer renderer(engine, backend);
  renderer.render(scene);
  const UpdateCounters first = renderer.counters();
  EXPECT_EQ(first.prepares, 1u);
  EXPECT_EQ(first.objects_uploaded, 10001u);  // the floor and the spheres

  scene.move_object(ids[5000], {3.3, 1.5, -2.1});
  const Image moved = renderer.render(scene);
  const UpdateCounters after = renderer.counters();
  EXPECT_EQ(after.prepares, 1u);
  EXPECT_EQ(after.updates, 1u);
  EXPECT_EQ(after.objects_uploaded - first.objects_uploaded, 1u);
  EXPECT_EQ(after.bvh_builds, first.bvh_builds) << "one moved sphere must not rebuild the BVH";
  EXPECT_EQ(after.bvh_refits - first.bvh_refits, has_bvh(backend) ? 1u : 0u);
  EXPECT_EQ(after.kernel_builds, first.kernel_builds);
  expect_same_pixels(moved, from_scratch(engine, scene, backend));
}

TEST_P(ApiUpdate, EveryKindOfEditRendersLikeAFreshRenderer) {
  const std::string backend = GetParam();
  Engine engine;
  LiveScene scene(engine);
  const auto ids = sphere_field(scene, 50, 48);
  Renderer renderer(engine, backend);
  renderer.render(scene);

  scene.update_object(ids[3], {{"radius", 0.6}});
  scene.rotate_object(ids[4], Rotation{.axis = {1, 0, 0}, .degrees = 90});
  scene.set_object_material(ids[5], "");
  scene.set_material("red", {.color = {0.1, 0.3, 0.9}, .reflect = 0.3});
  const LightId second = scene.add_light(DirectionalLight{.direction = {0, -1, -1}, .intensity = 0.3});
  scene.set_background({0.2, 0.3, 0.4});
  scene.set_camera({.position = {5, 30, 40}, .look_at = {1, 0, 0}, .fov_y = 40});
  expect_same_pixels(renderer.render(scene), from_scratch(engine, scene, backend));

  scene.remove_object(ids[7]);
  scene.add_object("box", {{"center", glm::dvec3{1, 0.5, 1}}, {"half_size", glm::dvec3{0.3, 0.3, 0.3}}}, "red");
  scene.update_light(second, DirectionalLight{.direction = {1, -1, 0}, .intensity = 0.5});
  const UpdateCounters before = renderer.counters();
  expect_same_pixels(renderer.render(scene), from_scratch(engine, scene, backend));
  const UpdateCounters after = renderer.counters();
  EXPECT_EQ(after.bvh_builds - before.bvh_builds, has_bvh(backend) ? 1u : 0u)
      << "adding and removing objects rebuilds";
  EXPECT_EQ(after.prepares, 1u);
}

TEST_P(ApiUpdate, ADielectricMaterialRebuildsTheKernelOnlyOnGpus) {
  const std::string backend = GetParam();
  Engine engine;
  LiveScene scene(engine);
  sphere_field(scene, 20, 32);
  Renderer renderer(engine, backend);
  renderer.render(scene);
  const UpdateCounters first = renderer.counters();
  scene.set_material("red", {.color = {0.9, 0.2, 0.1}, .specular = 0.5});  // the same features
  renderer.render(scene);
  EXPECT_EQ(renderer.counters().kernel_builds, first.kernel_builds);
  scene.set_material("red", {.ior = 1.5});  // dielectrics: a feature the kernel lacked
  expect_same_pixels(renderer.render(scene), from_scratch(engine, scene, backend));
  const bool gpu = backend == "opengl" || backend == "vulkan";
  EXPECT_EQ(renderer.counters().kernel_builds - first.kernel_builds, gpu ? 1u : 0u);
  EXPECT_EQ(renderer.counters().objects_uploaded, first.objects_uploaded) << "a material edit sends no object";
}

TEST_P(ApiUpdate, AnotherSceneIsPreparedAfresh) {
  Engine engine;
  LiveScene a(engine), b(engine);
  sphere_field(a, 10, 16);
  sphere_field(b, 12, 16);
  Renderer renderer(engine, GetParam());
  renderer.render(a);
  renderer.render(b);
  renderer.render(a);
  EXPECT_EQ(renderer.counters().prepares, 3u);
  EXPECT_EQ(renderer.counters().updates, 0u);
}

PRISM_INSTANTIATE_BACKEND_TESTS(ApiUpdate);

}  // namespace
}  // namespace prism::test
