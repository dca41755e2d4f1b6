// Camera rays, pixel order, the R2 sample offsets, visible light spheres and
// the id AOV.
#include <cmath>

#include "shading_support.hpp"

namespace prism::test {
namespace {

class CameraTest : public BackendTest {};

// fov_y 90 (tan 45 = 1) on a 1x1 image: sample (ox, oy) looks along
// (u, v, -1) with u = 2 ox - 1, v = 1 - 2 oy. A red box (Local = ambient * c =
// (1,0,0)) covers x < 0.5, y > -2.5 of the plane z = -5, i.e. u < 0.1 and
// v > -0.5; the rest is the blue background.
std::string edge_scene(int spp) {
  return R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 90},
    "image": {"width": 1, "height": 1, "spp": )" + std::to_string(spp) + R"(},
    "background": {"color": [0, 0, 1]},
    "ambient": [1, 1, 1],
    "materials": {"red": {"color": [1, 0, 0]}},
    "objects": [{"type": "box", "center": [-49.75, 48.75, -5.5], "half_size": [50.25, 51.25, 0.5],
                 "material": "red"}]})";
}

TEST_P(CameraTest, FourSamplesUseTheR2Offsets) {
  // R2: ox = frac(0.5 + k*0.7548776662466927), oy = frac(0.5 + k*0.5698402909980532):
  //   k = 0: (0.5, 0.5)             -> (u, v) = (0, 0)              red
  //   k = 1: (0.25487767, 0.06984029) -> (-0.49024467, 0.86031942)  red
  //   k = 2: (0.00975533, 0.63968058) -> (-0.98048933, -0.27936116) red
  //   k = 3: (0.76463300, 0.20952087) -> (0.52926600, 0.58095825)   blue (u > 0.1)
  // Mean of 4: (0.75, 0, 0.25). (A regular 2x2 grid would give 0.5 red.)
  EXPECT_TRUE(pixel_near(render(load(edge_scene(4))), 0, 0, {0.75, 0, 0.25}));
  // spp = 1 shoots through the pixel centre only: red.
  EXPECT_TRUE(pixel_near(render(load(edge_scene(1))), 0, 0, {1, 0, 0}));
}

TEST_P(CameraTest, RenderSettingsOverrideSpp) {
  Scene scene = load(edge_scene(1));
  RenderSettings settings;
  settings.image = scene.image;
  settings.image.spp = 4;
  EXPECT_TRUE(pixel_near(render(scene, settings), 0, 0, {0.75, 0, 0.25}));
}

TEST_P(CameraTest, RowZeroIsTheTopAndColumnZeroTheLeft) {
  // 2x2, fov 90: pixel (i, j) looks along (u, v, -1) with u = (i+0.5) - 1 and
  // v = 1 - (j+0.5): (0,0) -> (-0.5, 0.5), top left. Spheres (ambient-lit,
  // colour = Local) sit on those rays at z = -5: red top left, blue top right,
  // green bottom right; bottom left sees the black background.
  Scene scene = load(R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 90},
    "image": {"width": 2, "height": 2},
    "ambient": [1, 1, 1],
    "materials": {"r": {"color": [1, 0, 0]}, "g": {"color": [0, 1, 0]}, "b": {"color": [0, 0, 1]}},
    "objects": [{"type": "sphere", "center": [-2.5, 2.5, -5], "radius": 1, "material": "r"},
                {"type": "sphere", "center": [2.5, 2.5, -5], "radius": 1, "material": "b"},
                {"type": "sphere", "center": [2.5, -2.5, -5], "radius": 1, "material": "g"}]})");
  Image image = render(scene);
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 2);
  EXPECT_TRUE(pixel_near(image, 0, 0, {1, 0, 0}));
  EXPECT_TRUE(pixel_near(image, 1, 0, {0, 0, 1}));
  EXPECT_TRUE(pixel_near(image, 1, 1, {0, 1, 0}));
  EXPECT_TRUE(pixel_near(image, 0, 1, {0, 0, 0}));
}

TEST_P(CameraTest, AspectRatioWidensTheHorizontalField) {
  // 2x1, fov 90: u = ((i+0.5)/2*2 - 1) * 1 * W/H = -1, +1; v = 0. The right
  // pixel's ray (1, 0, -1) passes through (5, 0, -5), the centre of a small
  // white sphere; without the W/H factor it would pass (2.5, 0, -5) and miss.
  Scene scene = load(R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 90},
    "image": {"width": 2, "height": 1},
    "ambient": [1, 1, 1],
    "materials": {"w": {"color": [1, 1, 1]}},
    "objects": [{"type": "sphere", "center": [5, 0, -5], "radius": 0.5, "material": "w"}]})");
  Image image = render(scene);
  EXPECT_TRUE(pixel_near(image, 1, 0, {1, 1, 1}));
  EXPECT_TRUE(pixel_near(image, 0, 0, {0, 0, 0}));
}

TEST_P(CameraTest, CameraSeesALightSphereInItsColour) {
  // Light 1 (point, radius 0.5 at (0,0,-3)) is in front of the wall at z = -5:
  // the camera ray hits the sphere first and adds its colour (not scaled by
  // intensity). Its id is -2 - 1 = -3.
  Scene scene = load(one_pixel_scene(R"(
    "ambient": [1, 1, 1],
    "lights": [{"type": "directional", "direction": [0, 0, -1]},
               {"type": "point", "position": [0, 0, -3], "color": [0.9, 0.6, 0.3], "intensity": 7, "radius": 0.5}],
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1]}])"));
  RenderSettings settings;
  settings.image = scene.image;
  settings.aov_id = true;
  Image image = render(scene, settings);
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.9, 0.6, 0.3}));
  ASSERT_EQ(image.id.size(), 1u);
  EXPECT_EQ(image.id[0], -3.0f);
}

TEST_P(CameraTest, MirrorSeesALightSphere) {
  // reflect 1 at normal incidence: F = 1; the reflected ray (0,0,1) passes the
  // camera and hits the light sphere at (0,0,3): + 1 * (0.2, 0.7, 0.4).
  Scene scene = load(one_pixel_scene(R"(
    "materials": {"mirror": {"reflect": 1}},
    "lights": [{"type": "point", "position": [0, 0, 3], "color": [0.2, 0.7, 0.4], "radius": 0.5}],
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "mirror"}])"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.2, 0.7, 0.4}));
}

TEST_P(CameraTest, IdAovNamesMissObjectAndLightSphere) {
  // 3x1, fov 90: u = ((i+0.5)/3*2 - 1) * 3 = -2, 0, 2; rays (u, 0, -1).
  // Pixel 0 (-2,0,-1) misses: -1. Pixel 1 hits object 1 (the sphere at
  // (0,0,-5); object 0 is behind the camera): 1. Pixel 2 passes through the
  // centre (4,0,-2) of light 1's sphere: -2 - 1 = -3.
  Scene scene = load(R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 90},
    "image": {"width": 3, "height": 1},
    "lights": [{"type": "directional", "direction": [0, -1, 0]},
               {"type": "point", "position": [4, 0, -2], "radius": 0.5}],
    "objects": [{"type": "sphere", "center": [0, 0, 10], "radius": 1},
                {"type": "sphere", "center": [0, 0, -5], "radius": 1}]})");
  RenderSettings settings;
  settings.image = scene.image;
  settings.aov_id = true;
  settings.aov_path = true;
  Image image = render(scene, settings);
  ASSERT_EQ(image.id.size(), 3u);
  EXPECT_EQ(image.id[0], -1.0f);
  EXPECT_EQ(image.id[1], 1.0f);
  EXPECT_EQ(image.id[2], -3.0f);
  // The path AOV: one integer-valued float per pixel.
  ASSERT_EQ(image.path.size(), 3u);
  for (float hash : image.path) EXPECT_EQ(hash, std::floor(hash));
}

TEST_P(CameraTest, NoAovsUnlessAsked) {
  Image image = render(load(edge_scene(1)));
  EXPECT_TRUE(image.id.empty());
  EXPECT_TRUE(image.path.empty());
  EXPECT_EQ(image.rgb.size(), 3u);
}

PRISM_INSTANTIATE_BACKEND_TESTS(CameraTest);

}  // namespace
}  // namespace prism::test
