// Step 5 (opaque surfaces: Schlick reflection, alpha pass-through) and step 7
// (the max_depth cut-off). The camera is the one-pixel camera of
// shading_support.hpp: one ray (0,0,-1) from the origin.
#include "shading_support.hpp"

namespace prism::test {
namespace {

class ReflectionTest : public BackendTest {};

TEST_P(ReflectionTest, MirrorWithReflectOneShowsOnlyWhatItFaces) {
  // Mirror at z = -5 facing the camera: cosi = 1, F = r + (1-r)*0^5 = 1, so its
  // own Local (ambient * c = 1) is weighted by 1 - F = 0. The reflected ray
  // (0,0,1) passes the camera and hits the plane at z = 5, whose Local is
  // ambient * c = (0.3, 0.6, 0.9); weight F = 1.
  Scene scene = load(one_pixel_scene(R"(
    "background": {"color": [5, 5, 5]},
    "ambient": [1, 1, 1],
    "materials": {"mirror": {"color": [1, 1, 1], "reflect": 1}, "back": {"color": [0.3, 0.6, 0.9]}},
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "mirror"},
                {"type": "plane", "point": [0, 0, 5], "normal": [0, 0, -1], "material": "back"}])"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.3, 0.6, 0.9}));
}

TEST_P(ReflectionTest, SchlickWeightOnAnOpaqueSurfaceAtAnAngle) {
  // Plane through (0,0,-5) with normal (0,0.6,0.8): cosi = 0.8,
  // F = 0.5 + 0.5*(1-0.8)^5 = 0.5 + 0.5*0.00032 = 0.50016.
  // reflect((0,0,-1), n) = (0,0,-1) + 1.6*(0,0.6,0.8) = (0,0.96,0.28): a miss,
  // background B = (1, 0.5, 0). Local = ambient * c = 0.2.
  // (1-F)*0.2 + F*B = 0.099968 + 0.50016*B = (0.600128, 0.350048, 0.099968).
  Scene scene = load(one_pixel_scene(R"(
    "background": {"color": [1, 0.5, 0]},
    "ambient": [1, 1, 1],
    "materials": {"m": {"color": [0.2, 0.2, 0.2], "reflect": 0.5}},
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0.6, 0.8], "material": "m"}])"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.600128, 0.350048, 0.099968}));
}

std::string facing_mirrors(int max_depth) {
  return R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1]},
    "image": {"width": 1, "height": 1, "max_depth": )" + std::to_string(max_depth) + R"(},
    "background": {"color": [5, 5, 5]},
    "ambient": [1, 1, 1],
    "materials": {"m": {"color": [1, 0.5, 0.25], "reflect": 0.5}},
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "m"},
                {"type": "plane", "point": [0, 0, 5], "normal": [0, 0, -1], "material": "m"}]})";
}

TEST_P(ReflectionTest, MaxDepthCutsOffBetweenFacingMirrors) {
  // The ray bounces along the z axis between two mirrors, always at normal
  // incidence: F = 0.5. Interaction i adds w_i * 0.5 * c with w_i = 0.5^(i-1)
  // (c = ambient * colour = (1, 0.5, 0.25)); after interaction max_depth the
  // sample ends with nothing more added (the background, 5, is never reached).
  // max_depth 1: 0.5 c = (0.5, 0.25, 0.125).
  EXPECT_TRUE(pixel_near(render(load(facing_mirrors(1))), 0, 0, {0.5, 0.25, 0.125}));
  // max_depth 3: (0.5 + 0.25 + 0.125) c = 0.875 c = (0.875, 0.4375, 0.21875).
  EXPECT_TRUE(pixel_near(render(load(facing_mirrors(3))), 0, 0, {0.875, 0.4375, 0.21875}));
}

TEST_P(ReflectionTest, RenderSettingsOverrideMaxDepth) {
  // The scene says 1; settings (as from --max-depth 3) win: 0.875 c as above.
  Scene scene = load(facing_mirrors(1));
  RenderSettings settings;
  settings.image = scene.image;
  settings.image.max_depth = 3;
  EXPECT_TRUE(pixel_near(render(scene, settings), 0, 0, {0.875, 0.4375, 0.21875}));
}

// A plane at z = -5 textured with a 1x1 EXR texel (1, 0.5, 0.25, alpha 0.25)
// (one texel: every uv samples exactly it) in front of an opaque plane at
// z = -10 with Local = ambient * c = (0.2, 0.4, 0.8).
class AlphaTest : public BackendTest {
 protected:
  std::string scene(const std::string& front_extra, int max_depth) {
    dir_ = fresh_temp_dir();
    write_exr(dir_ / "quarter.exr", 1, 1, 4, {1.0f, 0.5f, 0.25f, 0.25f});
    return R"({"prism": 1,
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1]},
      "image": {"width": 1, "height": 1, "max_depth": )" + std::to_string(max_depth) + R"(},
      "background": {"color": [1, 1, 1]},
      "ambient": [1, 1, 1],
      "textures": {"quarter": "quarter.exr"},
      "materials": {"front": {"color": [1, 1, 1], "texture": "quarter")" + front_extra + R"(},
                    "back": {"color": [0.2, 0.4, 0.8]}},
      "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "front"},
                  {"type": "plane", "point": [0, 0, -10], "normal": [0, 0, 1], "material": "back"}]})";
  }
  std::filesystem::path dir_;
};

TEST_P(AlphaTest, PassThroughBlendsByAlpha) {
  // a * c_front + (1-a) * back = 0.25*(1, 0.5, 0.25) + 0.75*(0.2, 0.4, 0.8)
  //   = (0.25+0.15, 0.125+0.3, 0.0625+0.6) = (0.4, 0.425, 0.6625).
  const std::string json = scene("", 5);
  EXPECT_TRUE(pixel_near(render(load(json, dir_)), 0, 0, {0.4, 0.425, 0.6625}));
}

TEST_P(AlphaTest, PassThroughDropsTheReflection) {
  // reflect 0.5 at normal incidence: F = 0.5. Adds a*(1-F)*Local =
  // 0.25*0.5*(1, 0.5, 0.25) = (0.125, 0.0625, 0.03125); a < 1, so the ray goes
  // on straight (no reflection toward the white background) with w = 1 - a:
  // + 0.75*(0.2, 0.4, 0.8) = (0.275, 0.3625, 0.63125).
  const std::string json = scene(R"(, "reflect": 0.5)", 5);
  EXPECT_TRUE(pixel_near(render(load(json, dir_)), 0, 0, {0.275, 0.3625, 0.63125}));
}

TEST_P(AlphaTest, PassThroughCountsAsAnInteraction) {
  // max_depth 1: the alpha hit is interaction 1 and would continue, so the
  // sample ends: a * c_front = 0.25*(1, 0.5, 0.25) = (0.25, 0.125, 0.0625).
  const std::string json = scene("", 1);
  EXPECT_TRUE(pixel_near(render(load(json, dir_)), 0, 0, {0.25, 0.125, 0.0625}));
}

PRISM_INSTANTIATE_BACKEND_TESTS(ReflectionTest);
PRISM_INSTANTIATE_BACKEND_TESTS(AlphaTest);

}  // namespace
}  // namespace prism::test
