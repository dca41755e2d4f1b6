// The precision rule (gpu/precision.hpp): which scenes a float world serves
// and which objects send a scene to double. Expectations follow from the
// rule's figures by hand: a float hit point's error is about
// 4 * 2^-24 * (distance of the object's farthest corner from the camera).
#include <gtest/gtest.h>

#include "precision.hpp"
#include "prism/scene_loader.hpp"

namespace prism::gpu {
namespace {

Scene load_file(Registry& registry, const std::string& path) {
  return load_scene(std::string(PRISM_SOURCE_DIR) + "/" + path, registry);
}

std::vector<bool> needs_double(const WorldChoice& choice) {
  std::vector<bool> out;
  for (const ObjectPrecision& p : choice.per_object) out.push_back(p.needs_double);
  return out;
}

TEST(PrecisionRule, TheShowcaseIsFloatThroughout) {
  Registry registry;
  const Scene scene = load_file(registry, "scenes/showcase.json");
  const WorldChoice choice = choose_world(scene, Precision::automatic);
  EXPECT_TRUE(choice.float_world);
  EXPECT_EQ(needs_double(choice), std::vector<bool>(scene.objects.size(), false));
  EXPECT_EQ(choice.anchor, scene.camera.position);
  EXPECT_EQ(choice.description, "float");
}

// Camera ~1.06e5 from objects near the origin: error ~4 * 6e-8 * 1.06e5 =
// 0.025, against an offset 1e-4 (1 + ~0.5): every bounded object needs
// double; the plane (unbounded) does not.
TEST(PrecisionRule, AFarCameraSendsItsObjectsToDouble) {
  Registry registry;
  const Scene scene = load_file(registry, "scenes/conformance/far_camera.json");
  const WorldChoice choice = choose_world(scene, Precision::automatic);
  EXPECT_FALSE(choice.float_world);
  EXPECT_EQ(needs_double(choice), (std::vector<bool>{false, true, true, true}));
  EXPECT_NE(choice.objects.find("object 3 (torus)"), std::string::npos) << choice.objects;
}

// A ground sphere of radius 1e4 under the camera: corners ~2.4e4 away, error
// ~5.8e-3 against an offset ~1e-4 at its top; the 0.001 sphere 0.01 from the
// camera and the 0.5 one stay float.
TEST(PrecisionRule, AHugeSphereNearTheCameraNeedsDouble) {
  Registry registry;
  const Scene scene = load_file(registry, "scenes/conformance/tiny_huge.json");
  const WorldChoice choice = choose_world(scene, Precision::automatic);
  EXPECT_FALSE(choice.float_world);
  EXPECT_EQ(needs_double(choice), (std::vector<bool>{true, false, false}));
}

// A torus of tube 0.001 about 100 away: error ~4 * 6e-8 * 101 = 2.4e-5 over
// 1e-3 of its tube (1e-6). Its twin with tube 0.1 three units away: ~1e-6
// against 1e-4.
TEST(PrecisionRule, AThinTorusFarAwayNeedsDouble) {
  Registry registry;
  const Scene scene = load_scene_from_string(R"({"prism": 1, "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1]},
    "objects": [{"type": "torus", "center": [0, 0, -100], "major_radius": 1, "minor_radius": 0.001},
                {"type": "torus", "center": [0, 0, -3], "major_radius": 1, "minor_radius": 0.1}]})",
                                             ".", registry);
  const WorldChoice choice = choose_world(scene, Precision::automatic);
  EXPECT_FALSE(choice.float_world);
  EXPECT_EQ(needs_double(choice), (std::vector<bool>{true, false}));
}

// A ray query's rays are arbitrary: automatic means double for `trace`;
// an explicit request wins over the rule either way.
TEST(PrecisionRule, TraceIsDoubleAndRequestsWin) {
  Registry registry;
  const Scene plain = load_file(registry, "scenes/showcase.json");
  EXPECT_FALSE(choose_world(plain, Precision::automatic, true).float_world);
  EXPECT_FALSE(choose_world(plain, Precision::float64).float_world);
  const Scene far = load_file(registry, "scenes/conformance/far_camera.json");
  EXPECT_TRUE(choose_world(far, Precision::float32).float_world);
  EXPECT_TRUE(choose_world(far, Precision::float32, true).float_world);
}

TEST(PrecisionRule, TraceAnchorIsTheMeanOrigin) {
  const std::vector<TraceQuery> rays = {{{1, 2, 3}, {0, 0, 1}, 0}, {{3, 4, 5}, {0, 1, 0}, 0}};
  EXPECT_EQ(trace_anchor(rays), glm::dvec3(2, 3, 4));
}

}  // namespace
}  // namespace prism::gpu
