// Scene loader regressions found with the fuzz targets (tests/fuzz; the
// inputs are kept in tests/fuzz/regressions/scene_loader): valid scenes the
// loader turned into a broken Scene, and bad input it mishandled (a hang,
// the wrong plugin opened). Ordinary bad input belongs in the command-line
// table (tests/cli/bad_scenes.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"

namespace prism {
namespace {

Scene load(const std::string& camera, const std::string& lights = "[]") {
  Registry registry;
  return load_scene_from_string(R"({"prism": 1, "camera": )" + camera + R"(, "lights": )" + lights + "}", ".",
                                registry, "scene.json");
}

void expect_near(const glm::dvec3& got, const glm::dvec3& want) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], 1e-15) << "component " << i;
}

// look_at 1e-300 from position: |look_at - position|^2 underflowed to 0 and
// the camera basis came out NaN.
TEST(LoaderRegression, CameraLookAtATinyDistanceAway) {
  const Camera c = load(R"({"position": [0, 0, 1e-300], "look_at": [0, 0, 0]})").camera;
  expect_near(c.forward, {0, 0, -1});
  expect_near(c.right, {1, 0, 0});
  expect_near(c.up, {0, 1, 0});
}

// An up vector of 1e200: |up|^2 overflowed and the scene was refused as
// "must not be zero or parallel to the view direction"; 1e-170 lost bits to
// underflow. Any magnitude gives the basis of the unit vector; a power of
// two times it gives the same bits.
TEST(LoaderRegression, CameraUpOfAnyMagnitude) {
  const std::string camera = R"({"position": [0, 0, -5], "look_at": [1, 2, 3], "up": )";
  const Camera unit = load(camera + "[0.25, 1, 0]}").camera;
  for (const char* up : {"[0.25e200, 1e200, 0]", "[0.25e-170, 1e-170, 0]"}) {
    SCOPED_TRACE(up);
    const Camera c = load(camera + up + "}").camera;
    expect_near(c.right, unit.right);
    expect_near(c.up, unit.up);
  }
  const Camera four = load(camera + "[1, 4, 0]}").camera;
  EXPECT_EQ(four.right, unit.right);
  EXPECT_EQ(four.up, unit.up);
}

// A directional light along (1e-200, 0, 0) came out NaN, and along
// (1e300, 1e300, 0) as (0, 0, 0): |d|^2 underflowed or overflowed.
TEST(LoaderRegression, DirectionalLightOfAnyMagnitude) {
  const Scene s = load(R"({"position": [0, 0, -5], "look_at": [0, 0, 0]})",
                       R"([{"type": "directional", "direction": [1e-200, 0, 0]},
                           {"type": "directional", "direction": [1e300, 1e300, 0]},
                           {"type": "directional", "direction": [0, -4.9e-324, 0]}])");
  ASSERT_EQ(s.lights.size(), 3u);
  expect_near(s.lights[0].direction, {1, 0, 0});
  expect_near(s.lights[1].direction, {std::sqrt(0.5), std::sqrt(0.5), 0});
  expect_near(s.lights[2].direction, {0, -1, 0});
}

// A texture naming /dev/zero hung the loader: OpenImageIO's IFF reader,
// asked whether the endless stream is an IFF file, never returned.
TEST(LoaderRegression, TextureThatIsNotARegularFile) {
  Registry registry;
  try {
    load_scene_from_string(R"({"prism": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]},
                               "textures": {"a": "/dev/zero"}})",
                           ".", registry, "scene.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scene.json: textures.a: cannot read image '/dev/zero': not a regular file");
  }
}

// The type "sphere.so" + NUL opened libprism_primitive_sphere.so (dlopen
// reads the path as a C string) and crashed the fuzzer when the plugin,
// declaring "sphere", was refused and unloaded. A name with a NUL or a '/'
// now matches no plugin file. (The message stops at the NUL: what() is a C
// string.)
TEST(LoaderRegression, TypeWithNulOrSlashIsUnknown) {
  for (const std::string type : {"sphere.so\\u0000", "../prism/libprism_primitive_sphere"}) {
    Registry registry;
    try {
      load_scene_from_string(R"({"prism": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]},
                                 "objects": [{"type": ")" + type + R"(", "radius": 1}]})",
                             ".", registry, "scene.json");
      FAIL() << "no error for " << type;
    } catch (const InputError& e) {
      const std::string shown = type == "sphere.so\\u0000" ? "sphere.so" : type + "' (primitive plugins found: ";
      EXPECT_EQ(std::string(e.what()).rfind("scene.json: objects[0].type: unknown object type '" + shown, 0), 0u)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace prism
