// Step 4 of the shading rules: ambient, Lambert and Phong terms, light
// falloff, and shadow rays. Unless a test says otherwise the camera is the
// one-pixel camera of shading_support.hpp (ray (0,0,-1) from the origin) and
// it sees a plane at z = -5 whose normal (0,0,1) faces it, so P = (0,0,-5),
// n = (0,0,1) and the direction back to the eye is (0,0,1).
#include "shading_support.hpp"

#include <algorithm>
#include <vector>

namespace prism::test {
namespace {

class LightingTest : public BackendTest {};

constexpr const char* kWall = R"({"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "wall"})";

TEST_P(LightingTest, AmbientOnlyMultipliesSurfaceColour) {
  // Local = ambient * c = (0.2*0.5, 0.4*0.25, 0.6*1) = (0.1, 0.1, 0.6); no lights, F = 0.
  Scene scene = load(one_pixel_scene(R"(
    "background": {"color": [9, 9, 9]},
    "ambient": [0.2, 0.4, 0.6],
    "materials": {"wall": {"color": [0.5, 0.25, 1.0]}},
    "objects": [)" + std::string(kWall) + "]"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.1, 0.1, 0.6}));
}

TEST_P(LightingTest, DirectionalLightAtSixtyDegrees) {
  // direction (-sqrt(3), 0, -1) -> l = (sqrt(3)/2, 0, 1/2): dot(n, l) = cos 60 = 0.5.
  // E = color * intensity = (1.5, 0.75, 3); Local = E * kd * c * 0.5
  //   = (1.5*0.8, 0.75*0.6, 3*0.4) * 0.5 = (0.6, 0.225, 0.6).
  Scene scene = load(one_pixel_scene(R"(
    "materials": {"wall": {"color": [0.8, 0.6, 0.4]}},
    "lights": [{"type": "directional", "direction": [-1.7320508075688772, 0, -1],
                "color": [1, 0.5, 2], "intensity": 1.5}],
    "objects": [)" + std::string(kWall) + "]"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.6, 0.225, 0.6}));
}

TEST_P(LightingTest, LightBelowOrGrazingTheSurfaceAddsNothing) {
  // Three lights, none with dot(n, l) > 0: directional from behind (l = (0,0,-1)),
  // directional grazing (l = (-1,0,0), dot = 0), point behind the plane
  // (l = (0,0,-1)). Neither Lambert nor Phong (ks = 1, shininess 1) may add.
  // Only ambient remains: 0.1 * 0.5 = 0.05.
  Scene scene = load(one_pixel_scene(R"(
    "ambient": [0.1, 0.1, 0.1],
    "materials": {"wall": {"color": [0.5, 0.5, 0.5], "specular": 1, "shininess": 1}},
    "lights": [{"type": "directional", "direction": [0, 0, 1], "intensity": 5},
               {"type": "directional", "direction": [1, 0, 0], "intensity": 5},
               {"type": "point", "position": [0, 0, -6], "intensity": 5}],
    "objects": [)" + std::string(kWall) + "]"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.05, 0.05, 0.05}));
}

TEST_P(LightingTest, BackFacingPlaneIsShadedWithTheFacingNormal) {
  // The plane's normal (0,0,-1) points away from the camera: front = false,
  // n = -N = (0,0,1). A light with l = (0,0,1) lights it fully (0.5 * 1), one
  // with l = (0,0,-1) (from the far side) adds nothing.
  Scene scene = load(one_pixel_scene(R"(
    "materials": {"wall": {"color": [0.5, 0.5, 0.5]}},
    "lights": [{"type": "directional", "direction": [0, 0, -1]},
               {"type": "directional", "direction": [0, 0, 1], "intensity": 3}],
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, -1], "material": "wall"}])"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.5, 0.5, 0.5}));
}

// A directional light with l = (0.6, 0, 0.8) (dot(n, l) = 0.8) and a blocker
// on the shadow ray only: the ray from P along l passes (1.5, 0, -3) at
// distance 2.5; the camera ray (the z axis) passes 1.5 from that centre.
std::string shadow_scene(const std::string& blocker_material) {
  return one_pixel_scene(R"(
    "ambient": [0.1, 0.1, 0.1],
    "shadow_ambient": [0.5, 0.25, 0],
    "materials": {"wall": {"color": [0.5, 0.5, 0.5]}, "glass": {"ior": 1.5},
                  "white": {"color": [1, 1, 1]}},
    "lights": [{"type": "directional", "direction": [-3, 0, -4]}],
    "objects": [)" + std::string(kWall) + R"(,
      {"type": "sphere", "center": [1.5, 0, -3], "radius": 0.5, "material": ")" +
                         blocker_material + R"("}])");
}

TEST_P(LightingTest, ShadowAmbientScalesABlockedLightPerChannel) {
  // Unblocked the light would add kd * c * 0.8 = 0.4; blocked it adds
  // S * 0.4 with S = shadow_ambient = (0.5, 0.25, 0). Plus ambient 0.1 * 0.5:
  // (0.05 + 0.2, 0.05 + 0.1, 0.05 + 0) = (0.25, 0.15, 0.05).
  EXPECT_TRUE(pixel_near(render(load(shadow_scene("white"))), 0, 0, {0.25, 0.15, 0.05}));
}

TEST_P(LightingTest, DielectricsBlockShadowRaysToo) {
  // The same blocker made of glass: shadow rays are blocked by every object.
  EXPECT_TRUE(pixel_near(render(load(shadow_scene("glass"))), 0, 0, {0.25, 0.15, 0.05}));
}

TEST_P(LightingTest, ShadowsAlongARowChangeBlockerFromPixelToPixel) {
  // A 16x1 image with fov 90 (tan = 1, aspect 16): pixel i's ray is
  // (2i - 15, 0, -1) and hits the wall z = -1 at P = (2i - 15, 0, -1), n = (0,0,1).
  // Light 1 (red) has l = (0,1,1)/sqrt2, light 2 (green) l = (0,-1,1)/sqrt2,
  // both dot(n, l) = 1/sqrt2. P's shadow ray toward light 1 passes
  // (x, 0.6, -0.4) (up to the 1e-4 offset), toward light 2 (x, -0.6, -0.4): a
  // sphere of radius 0.4 centred there at an odd x blocks exactly the pixel
  // with that x (the next is 2 away), and no camera ray (y = 0) reaches one.
  // Pixels in one row share a tile, so consecutive shadow rays are blocked by
  // one sphere, then another, then none: whatever a renderer remembers
  // between rays must not leak into the answer.
  const std::vector<int> red_blockers = {-9, -7, 3, 5, 11}, green_blockers = {-7, -5, 3, 13};
  std::string objects = R"({"type": "plane", "point": [0, 0, -1], "normal": [0, 0, 1], "material": "wall"})";
  auto add_spheres = [&](const std::vector<int>& xs, const char* yz) {
    for (int x : xs)
      objects += R"(, {"type": "sphere", "radius": 0.4, "material": "wall", "center": [)" + std::to_string(x) + yz + "]}";
  };
  add_spheres(red_blockers, ", 0.6, -0.4");
  add_spheres(green_blockers, ", -0.6, -0.4");
  Scene scene = load(R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_y": 90},
    "image": {"width": 16, "height": 1},
    "materials": {"wall": {"color": [1, 1, 1]}},
    "lights": [{"type": "directional", "direction": [0, -1, -1], "color": [1, 0, 0]},
               {"type": "directional", "direction": [0, 1, -1], "color": [0, 1, 0]}],
    "objects": [)" + objects + "]}");
  const Image image = render(scene);
  const double lit = 0.70710678118654752;  // kd * c * dot(n, l) = 1/sqrt2
  for (int i = 0; i < 16; ++i) {
    const int x = 2 * i - 15;
    const bool red_blocked = std::ranges::count(red_blockers, x) > 0;
    const bool green_blocked = std::ranges::count(green_blockers, x) > 0;
    EXPECT_TRUE(pixel_near(image, i, 0, {red_blocked ? 0.0 : lit, green_blocked ? 0.0 : lit, 0.0})) << "x = " << x;
  }
}

TEST_P(LightingTest, PointLightFalloffAtKnownDistance) {
  // Light at (0,3,-1): P - light = (0,-3,-4), d = 5, l = (0,0.6,0.8), dot(n,l) = 0.8.
  // E = 3 / (1 + 0.2*5 + 0.04*25) = 3 / 3 = 1. Local = 1 * c * 0.8 = (0.64, 0.48, 0.32).
  Scene scene = load(one_pixel_scene(R"(
    "materials": {"wall": {"color": [0.8, 0.6, 0.4]}},
    "lights": [{"type": "point", "position": [0, 3, -1], "intensity": 3, "linear": 0.2, "quadratic": 0.04}],
    "objects": [)" + std::string(kWall) + "]"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.64, 0.48, 0.32}));
}

TEST_P(LightingTest, ObjectBeyondAPointLightDoesNotShadow) {
  // As PointLightFalloffAtKnownDistance, plus a sphere centred on the line from
  // P through the light, 2.5 beyond the light (at (0,4.5,1), behind the camera).
  // The shadow ray ends at the light: nothing changes, (0.64, 0.48, 0.32).
  Scene scene = load(one_pixel_scene(R"(
    "materials": {"wall": {"color": [0.8, 0.6, 0.4]}},
    "lights": [{"type": "point", "position": [0, 3, -1], "intensity": 3, "linear": 0.2, "quadratic": 0.04}],
    "objects": [)" + std::string(kWall) + R"(,
      {"type": "sphere", "center": [0, 4.5, 1], "radius": 0.5}])"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.64, 0.48, 0.32}));
}

TEST_P(LightingTest, PhongSpecularAtKnownAngle) {
  // l = (0.6, 0, 0.8); reflect(-l, n) = (-0.6, 0, -0.8) + 2*0.8*(0,0,1) = (-0.6, 0, 0.8);
  // dot with -dir = (0,0,1) is 0.8, so the Phong term is 0.8^3 = 0.512 (white:
  // not tinted by c). Lambert: kd * c * 0.8 = 0.5 * (1, 0.5, 0) * 0.8 = (0.4, 0.2, 0).
  // E = 1: (0.912, 0.712, 0.512).
  Scene scene = load(one_pixel_scene(R"(
    "materials": {"wall": {"color": [1, 0.5, 0], "diffuse": 0.5, "specular": 1, "shininess": 3}},
    "lights": [{"type": "directional", "direction": [-0.6, 0, -0.8]}],
    "objects": [)" + std::string(kWall) + "]"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.912, 0.712, 0.512}));
}

TEST_P(LightingTest, LightSphereNeverBlocksAShadowRay) {
  // Camera at (1,0,0) looking down -z: P = (1,0,-5). The point light at (0,0,-3)
  // has a visible sphere of radius 0.5 that the shadow ray enters before it
  // reaches the light's position; it must not block. d = sqrt(5),
  // l = (-1,0,2)/sqrt(5), dot(n,l) = 2/sqrt(5) = 0.894427191; E = 1.
  // Local = 0.5 * 0.894427191 = 0.4472135955.
  Scene scene = load(R"({"prism": 1,
    "camera": {"position": [1, 0, 0], "look_at": [1, 0, -1]},
    "image": {"width": 1, "height": 1},
    "materials": {"wall": {"color": [0.5, 0.5, 0.5]}},
    "lights": [{"type": "point", "position": [0, 0, -3], "radius": 0.5}],
    "objects": [)" + std::string(kWall) + "]}");
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.4472135955, 0.4472135955, 0.4472135955}));
}

PRISM_INSTANTIATE_BACKEND_TESTS(LightingTest);

}  // namespace
}  // namespace prism::test
