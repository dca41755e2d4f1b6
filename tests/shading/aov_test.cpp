// The depth, normal and albedo AOVs: sample 0's first hit, the same on every
// backend (docs/scene-format.md, "Output files and image channels").
#include <cmath>
#include <cstring>
#include <limits>

#include "shading_support.hpp"

namespace prism::test {
namespace {

class AovTest : public BackendTest {};

constexpr double kTolerance = 1e-5;  // float channels of double geometry

RenderSettings with_first_hit_aovs(const Scene& scene) {
  RenderSettings settings;
  settings.image = scene.image;
  settings.aov_depth = settings.aov_normal = settings.aov_albedo = true;
  return settings;
}

void expect_vec3_near(const std::vector<float>& channel, size_t pixel, glm::dvec3 expected) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(channel[pixel * 3 + size_t(c)], expected[c], kTolerance) << "pixel " << pixel << " component " << c;
}

TEST_P(AovTest, DepthNormalAndAlbedoOfAnObjectALightSphereAndAMiss) {
  // Camera at (0,0,5) looking at the origin, 3x1, fov 90: u = -2, 0, 2, rays
  // (u, 0, -1) normalised.
  // Pixel 1 (0,0,-1) meets the unit sphere at (0,0,1): t = 5 - 1 = 4, outward
  // normal (0,0,1), albedo its colour (0.8, 0.4, 0.2).
  // Pixel 2, (2,0,-1)/sqrt 5, passes 10/sqrt 5 = 4.47 from the origin (no
  // sphere) and through light 1's centre (4,0,3), 2 sqrt 5 = 4.47214 along it:
  // t = 4.47214 - 0.5 = 3.97214; normal -dir = (-2,0,1)/sqrt 5 =
  // (-0.894427, 0, 0.447214); albedo the light's colour (0.9, 0.6, 0.3).
  // Pixel 0, (-2,0,-1)/sqrt 5, misses everything: +inf, 0, 0.
  const Scene scene = load(R"({"prism": 1,
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_y": 90},
    "image": {"width": 3, "height": 1},
    "materials": {"orange": {"color": [0.8, 0.4, 0.2]}},
    "lights": [{"type": "directional", "direction": [0, -1, 0]},
               {"type": "point", "position": [4, 0, 3], "color": [0.9, 0.6, 0.3], "radius": 0.5}],
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "orange"}]})");
  const Image image = render(scene, with_first_hit_aovs(scene));
  ASSERT_EQ(image.depth.size(), 3u);
  ASSERT_EQ(image.normal.size(), 9u);
  ASSERT_EQ(image.albedo.size(), 9u);
  EXPECT_EQ(image.depth[0], std::numeric_limits<float>::infinity());
  expect_vec3_near(image.normal, 0, {0, 0, 0});
  expect_vec3_near(image.albedo, 0, {0, 0, 0});
  EXPECT_NEAR(image.depth[1], 4.0, kTolerance);
  expect_vec3_near(image.normal, 1, {0, 0, 1});
  expect_vec3_near(image.albedo, 1, {0.8, 0.4, 0.2});
  EXPECT_NEAR(image.depth[2], 3.97214, kTolerance);
  expect_vec3_near(image.normal, 2, {-0.894427, 0, 0.447214});
  expect_vec3_near(image.albedo, 2, {0.9, 0.6, 0.3});
}

TEST_P(AovTest, TheNormalIsOutwardEvenSeenFromInside) {
  // The camera at (0,0,5) inside a sphere of radius 10 round the origin: the
  // centre ray (0,0,-1) meets it at (0,0,-10), t = 15, where the outward
  // normal is (0,0,-1), away from the camera (shading uses (0,0,1)).
  const Scene scene = load(R"({"prism": 1,
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_y": 90},
    "image": {"width": 1, "height": 1},
    "materials": {"grey": {"color": [0.5, 0.5, 0.5]}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 10, "material": "grey"}]})");
  const Image image = render(scene, with_first_hit_aovs(scene));
  ASSERT_EQ(image.depth.size(), 1u);
  EXPECT_NEAR(image.depth[0], 15.0, kTolerance);
  expect_vec3_near(image.normal, 0, {0, 0, -1});
  expect_vec3_near(image.albedo, 0, {0.5, 0.5, 0.5});
}

TEST_P(AovTest, EachIsWrittenOnlyWhenAsked) {
  const Scene scene = load(one_pixel_scene(R"("objects": [{"type": "sphere", "center": [0, 0, -5], "radius": 1}])"));
  RenderSettings settings;
  settings.image = scene.image;
  settings.aov_normal = true;
  const Image image = render(scene, settings);
  EXPECT_TRUE(image.depth.empty());
  EXPECT_TRUE(image.albedo.empty());
  EXPECT_TRUE(image.id.empty());
  ASSERT_EQ(image.normal.size(), 3u);
  expect_vec3_near(image.normal, 0, {0, 0, 1});  // the sphere's near side, seen from the origin
}

// The colour is the same bits whether or not any AOV is asked for. On the
// CPU a sample that wants its path hash is traced alone, its lighting at
// once, while the others of a tile go together in waves (core/src/shading.hpp):
// at 3 spp both kinds share every pixel, and the showcase has glass (its
// one-level reflections), mirrors, alpha, textures and a torus.
TEST_P(AovTest, TheColourIsTheSameWithAndWithoutAovs) {
  const Scene scene = load(read_file(source_dir() / "scenes" / "showcase.json"), source_dir() / "scenes");
  RenderSettings plain;
  plain.image = scene.image;
  plain.image.width = 61;
  plain.image.height = 35;
  plain.image.spp = 3;
  plain.image.max_depth = 6;
  RenderSettings with_aovs = plain;
  with_aovs.aov_id = with_aovs.aov_path = with_aovs.aov_depth = with_aovs.aov_normal = with_aovs.aov_albedo = true;
  const Image a = render(scene, plain), b = render(scene, with_aovs);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) differing += std::memcmp(&a.rgb[i], &b.rgb[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u) << "of " << a.rgb.size() << " channels";
}

PRISM_INSTANTIATE_BACKEND_TESTS(AovTest);

}  // namespace
}  // namespace prism::test
