// The viewer's camera math (apps/prism/viewer/camera_controller.hpp).
// Expected values are worked out by hand in the comments.
#include <gtest/gtest.h>

#include <cmath>

#include "prism/scene_loader.hpp"
#include "viewer/camera_controller.hpp"

namespace prism::viewer {
namespace {

constexpr double kEps = 1e-12;
constexpr double kPi = 3.141592653589793;

#define EXPECT_VEC3_NEAR(v, ex, ey, ez) \
  do {                                  \
    EXPECT_NEAR((v).x, (ex), kEps);     \
    EXPECT_NEAR((v).y, (ey), kEps);     \
    EXPECT_NEAR((v).z, (ez), kEps);     \
  } while (0)

#define EXPECT_VEC3_EQ(a, b)        \
  do {                              \
    EXPECT_EQ((a).x, (b).x);        \
    EXPECT_EQ((a).y, (b).y);        \
    EXPECT_EQ((a).z, (b).z);        \
  } while (0)

// The camera at (0,0,5) looking at the origin with up +y, as the loader
// builds it: forward (0,0,-1), right = cross(forward, up) = (1,0,0), up (0,1,0).
Camera front_camera() {
  Camera c;
  c.position = {0, 0, 5};
  c.forward = {0, 0, -1};
  c.right = {1, 0, 0};
  c.up = {0, 1, 0};
  c.fov_y = 40;
  return c;
}

OrbitStart start(double distance, glm::dvec3 up = {0, 1, 0}) {
  OrbitStart s;
  s.distance = distance;
  s.world_up = up;
  return s;
}

TEST(CameraController, StartsWithTheScenesCameraBitForBit) {
  // A basis with rounding in it: the controller must not recompute it.
  Camera c;
  c.position = {0.1, 1.2, 6.3};
  c.forward = glm::normalize(glm::dvec3(-0.1, -0.8, -6.3));
  c.right = glm::normalize(glm::cross(c.forward, glm::dvec3(0, 1, 0)));
  c.up = glm::cross(c.right, c.forward);
  c.fov_y = 35;
  CameraController controller(c, start(6.0));
  EXPECT_VEC3_EQ(controller.camera().position, c.position);
  EXPECT_VEC3_EQ(controller.camera().forward, c.forward);
  EXPECT_VEC3_EQ(controller.camera().right, c.right);
  EXPECT_VEC3_EQ(controller.camera().up, c.up);
  EXPECT_EQ(controller.camera().fov_y, 35);
}

TEST(CameraController, TargetIsPositionPlusForwardTimesDistance) {
  CameraController controller(front_camera(), start(5.0));
  EXPECT_VEC3_NEAR(controller.target(), 0, 0, 0);
  EXPECT_EQ(controller.distance(), 5.0);
}

TEST(CameraController, YawQuarterTurnMovesTheCameraToPlusX) {
  // The offset from the target, (0,0,5), turned +90 degrees about +y is (5,0,0).
  // forward = (-1,0,0); right = cross((-1,0,0),(0,1,0)) = (0,0,-1);
  // up = cross((0,0,-1),(-1,0,0)) = (0,1,0).
  CameraController controller(front_camera(), start(5.0));
  controller.orbit(kPi / 2, 0.0);
  EXPECT_VEC3_NEAR(controller.camera().position, 5, 0, 0);
  EXPECT_VEC3_NEAR(controller.camera().forward, -1, 0, 0);
  EXPECT_VEC3_NEAR(controller.camera().right, 0, 0, -1);
  EXPECT_VEC3_NEAR(controller.camera().up, 0, 1, 0);
  EXPECT_VEC3_NEAR(controller.target(), 0, 0, 0);
  EXPECT_EQ(controller.camera().fov_y, 40);
}

TEST(CameraController, PitchRaisesTheCameraAndTiltsTheBasis) {
  // Elevation 0 -> 45 degrees at distance 5: position (0, 5 sin 45, 5 cos 45)
  // = (0, 3.5355339059327373, 3.5355339059327373).
  // forward = -position / 5 = (0, -s, -s) with s = 0.7071067811865476;
  // right = cross((0,-s,-s),(0,1,0)) = (s,0,0) -> (1,0,0);
  // up = cross((1,0,0),(0,-s,-s)) = (0, s, -s).
  CameraController controller(front_camera(), start(5.0));
  controller.orbit(0.0, kPi / 4);
  const double s = 0.7071067811865476;
  EXPECT_VEC3_NEAR(controller.camera().position, 0, 3.5355339059327373, 3.5355339059327373);
  EXPECT_VEC3_NEAR(controller.camera().forward, 0, -s, -s);
  EXPECT_VEC3_NEAR(controller.camera().right, 1, 0, 0);
  EXPECT_VEC3_NEAR(controller.camera().up, 0, s, -s);
}

TEST(CameraController, PitchStopsHalfADegreeShortOfTheZenith) {
  // Asking for +180 degrees stops at 89.5: (0, 5 sin 89.5, 5 cos 89.5)
  // = (0, 4.999809615320856, 0.043632677491869484); the same going down.
  CameraController controller(front_camera(), start(5.0));
  controller.orbit(0.0, kPi);
  EXPECT_VEC3_NEAR(controller.camera().position, 0, 4.999809615320856, 0.043632677491869484);
  EXPECT_VEC3_NEAR(controller.camera().right, 1, 0, 0);
  controller.orbit(0.0, -2 * kPi);
  EXPECT_VEC3_NEAR(controller.camera().position, 0, -4.999809615320856, 0.043632677491869484);
  EXPECT_VEC3_NEAR(controller.camera().right, 1, 0, 0);
}

TEST(CameraController, YawNearTheZenithStillTurnsAboutWorldUp) {
  // At the 89.5 degree limit the horizontal offset is 0.043632677491869484
  // along +z; a +90 degree yaw turns it to +x and right to (0,0,-1).
  CameraController controller(front_camera(), start(5.0));
  controller.orbit(0.0, kPi);
  controller.orbit(kPi / 2, 0.0);
  EXPECT_VEC3_NEAR(controller.camera().position, 0.043632677491869484, 4.999809615320856, 0);
  EXPECT_VEC3_NEAR(controller.camera().right, 0, 0, -1);
}

TEST(CameraController, OrbitKeepsDistanceAndTarget) {
  CameraController controller(front_camera(), start(5.0));
  controller.fly(1, 2, 3);  // target now (1, 2, -3)
  controller.orbit(0.3, 0.2);
  controller.orbit(-1.1, -0.5);
  EXPECT_VEC3_NEAR(controller.target(), 1, 2, -3);
  EXPECT_NEAR(glm::length(controller.camera().position - controller.target()), 5.0, kEps);
  const glm::dvec3 f = glm::normalize(controller.target() - controller.camera().position);
  EXPECT_VEC3_NEAR(controller.camera().forward, f.x, f.y, f.z);
  EXPECT_NEAR(glm::dot(controller.camera().right, glm::dvec3(0, 1, 0)), 0.0, kEps);
  EXPECT_NEAR(glm::dot(controller.camera().up, controller.camera().forward), 0.0, kEps);
}

TEST(CameraController, OrbitsAboutTheScenesUp) {
  // World up +z, camera at (5,0,0) looking at the origin:
  // forward (-1,0,0), right = cross((-1,0,0),(0,0,1)) = (0,1,0), up = cross((0,1,0),(-1,0,0)) = (0,0,1).
  // +90 degrees about +z takes (5,0,0) to (0,5,0): forward (0,-1,0),
  // right = cross((0,-1,0),(0,0,1)) = (-1,0,0), up (0,0,1).
  Camera c;
  c.position = {5, 0, 0};
  c.forward = {-1, 0, 0};
  c.right = {0, 1, 0};
  c.up = {0, 0, 1};
  CameraController controller(c, start(5.0, {0, 0, 1}));
  controller.orbit(kPi / 2, 0.0);
  EXPECT_VEC3_NEAR(controller.camera().position, 0, 5, 0);
  EXPECT_VEC3_NEAR(controller.camera().forward, 0, -1, 0);
  EXPECT_VEC3_NEAR(controller.camera().right, -1, 0, 0);
  EXPECT_VEC3_NEAR(controller.camera().up, 0, 0, 1);
}

TEST(CameraController, FlyMovesCameraAndTargetAndKeepsTheBasis) {
  // right*1 + world_up*2 + forward*3 = (1,0,0) + (0,2,0) + (0,0,-3) = (1,2,-3).
  CameraController controller(front_camera(), start(5.0));
  controller.fly(1, 2, 3);
  EXPECT_VEC3_NEAR(controller.camera().position, 1, 2, 2);
  EXPECT_VEC3_NEAR(controller.target(), 1, 2, -3);
  EXPECT_VEC3_EQ(controller.camera().forward, front_camera().forward);
  EXPECT_VEC3_EQ(controller.camera().right, front_camera().right);
  EXPECT_VEC3_EQ(controller.camera().up, front_camera().up);
}

TEST(CameraController, FlyUpFollowsWorldUpNotTheTiltedCameraUp) {
  // After pitching 45 degrees the camera's up is (0, s, -s); flying up still
  // moves along world +y: (0, 3.5355339059327373 + 1, 3.5355339059327373).
  CameraController controller(front_camera(), start(5.0));
  controller.orbit(0.0, kPi / 4);
  controller.fly(0, 1, 0);
  EXPECT_VEC3_NEAR(controller.camera().position, 0, 4.5355339059327373, 3.5355339059327373);
  EXPECT_VEC3_NEAR(controller.target(), 0, 1, 0);
}

TEST(CameraController, DollyScalesTheDistanceWithinLimits) {
  CameraController controller(front_camera(), start(5.0));
  controller.dolly(0.5);  // 5 -> 2.5: position (0,0,2.5)
  EXPECT_VEC3_NEAR(controller.camera().position, 0, 0, 2.5);
  EXPECT_EQ(controller.distance(), 2.5);
  controller.dolly(1e-9);  // clamped to 0.001
  EXPECT_VEC3_NEAR(controller.camera().position, 0, 0, 0.001);
  EXPECT_EQ(controller.distance(), 0.001);
  controller.dolly(0.0);  // ignored
  controller.dolly(-2.0);
  EXPECT_EQ(controller.distance(), 0.001);
  controller.dolly(4000.0);  // 0.001 -> 4
  EXPECT_NEAR(controller.distance(), 4.0, kEps);
  EXPECT_VEC3_NEAR(controller.camera().position, 0, 0, 4);
  EXPECT_VEC3_EQ(controller.camera().forward, front_camera().forward);
}

TEST(CameraController, ResetReturnsToTheScenesCamera) {
  Camera c = front_camera();
  c.position = {0.1, 0.2, 5.3};
  CameraController controller(c, start(5.3));
  controller.orbit(0.7, -0.3);
  controller.fly(1, 1, 1);
  controller.dolly(0.3);
  controller.reset();
  EXPECT_VEC3_EQ(controller.camera().position, c.position);
  EXPECT_VEC3_EQ(controller.camera().forward, c.forward);
  EXPECT_VEC3_EQ(controller.camera().right, c.right);
  EXPECT_VEC3_EQ(controller.camera().up, c.up);
  EXPECT_EQ(controller.distance(), 5.3);
  EXPECT_VEC3_NEAR(controller.target(), 0.1, 0.2, 0);
}

TEST(OrbitStart, LookAtGivesTheDistanceAndDefaultUp) {
  // position (0,3,4), look_at the origin: distance sqrt(9 + 16) = 5.
  Camera c;
  c.position = {0, 3, 4};
  c.forward = glm::normalize(-c.position);
  CameraHints hints;
  hints.look_at = glm::dvec3(0, 0, 0);
  const OrbitStart s = orbit_start(c, hints, std::nullopt);
  EXPECT_EQ(s.distance, 5.0);
  EXPECT_VEC3_EQ(s.world_up, glm::dvec3(0, 1, 0));
}

TEST(OrbitStart, TheScenesUpIsNormalized) {
  Camera c;
  CameraHints hints;
  hints.look_at = glm::dvec3(0, 0, -2);
  hints.up = glm::dvec3(0, 0, 2);  // -> (0,0,1)
  const OrbitStart s = orbit_start(c, hints, std::nullopt);
  EXPECT_VEC3_EQ(s.world_up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(s.distance, 2.0);
}

TEST(OrbitStart, RotationUsesTheCamerasUpAndTheBoundsCentre) {
  // Camera at the origin looking down -z; objects' box centre (0,0,-10):
  // depth along forward = 10.
  Camera c;
  c.up = {0, 0.6, 0.8};
  CameraHints hints;
  hints.rotation = true;
  Box3 box;
  box.lo = {-1, -1, -11};
  box.hi = {1, 1, -9};
  const OrbitStart s = orbit_start(c, hints, box);
  EXPECT_VEC3_EQ(s.world_up, glm::dvec3(0, 0.6, 0.8));
  EXPECT_EQ(s.distance, 10.0);
}

TEST(OrbitStart, FiveUnitsWhenNothingBetterIsKnown) {
  Camera c;
  CameraHints hints;
  hints.rotation = true;
  Box3 behind;
  behind.lo = {-1, -1, 1};
  behind.hi = {1, 1, 3};
  EXPECT_EQ(orbit_start(c, hints, behind).distance, 5.0);
  EXPECT_EQ(orbit_start(c, hints, std::nullopt).distance, 5.0);
}

TEST(CameraHints, ReadFromTheSceneText) {
  CameraHints a = read_camera_hints(
      R"({"prism": 1, "camera": {"position": [0, 1, 2], "look_at": [0, 0.5, -1], "up": [0, 0, 1]}, "objects": []})");
  ASSERT_TRUE(a.look_at.has_value());
  EXPECT_VEC3_EQ(*a.look_at, glm::dvec3(0, 0.5, -1));
  ASSERT_TRUE(a.up.has_value());
  EXPECT_VEC3_EQ(*a.up, glm::dvec3(0, 0, 1));
  EXPECT_FALSE(a.rotation);

  CameraHints b = read_camera_hints(R"({"camera": {"position": [0, 1, 2], "rotation": {"axis": [1, 0, 0], "degrees": 5}}})");
  EXPECT_FALSE(b.look_at.has_value());
  EXPECT_FALSE(b.up.has_value());
  EXPECT_TRUE(b.rotation);

  CameraHints c = read_camera_hints("not json");
  EXPECT_FALSE(c.look_at.has_value());
  EXPECT_FALSE(c.rotation);
}

TEST(SceneBounds, UnionOfTheBoundedObjects) {
  Scene scene;
  scene.objects.resize(3);
  scene.objects[0].bounded = true;
  scene.objects[0].world_bounds = {{-1, 0, 0}, {1, 1, 1}};
  scene.objects[1].bounded = false;  // a plane: left out
  scene.objects[2].bounded = true;
  scene.objects[2].world_bounds = {{0, -2, -3}, {4, 0.5, 0}};
  auto box = scene_bounds(scene);
  ASSERT_TRUE(box.has_value());
  EXPECT_VEC3_EQ(box->lo, glm::dvec3(-1, -2, -3));
  EXPECT_VEC3_EQ(box->hi, glm::dvec3(4, 1, 1));
  Scene empty;
  EXPECT_FALSE(scene_bounds(empty).has_value());
}

// A box from (0,0,0) to (3,4,12) has the diagonal sqrt(9 + 16 + 144) = 13:
// a quarter of it, 3.25 units, per second.
TEST(FlySpeed, AQuarterOfTheScenesDiagonalPerSecond) {
  EXPECT_DOUBLE_EQ(fly_speed(Box3{{0, 0, 0}, {3, 4, 12}}, 7.0), 3.25);
  // The same scene in millimetres flies 1000 times as fast.
  EXPECT_DOUBLE_EQ(fly_speed(Box3{{0, 0, 0}, {3000, 4000, 12000}}, 7.0), 3250.0);
}

TEST(FlySpeed, TheTargetDistanceWithoutABoxOrWithAPoint) {
  EXPECT_EQ(fly_speed(std::nullopt, 7.0), 7.0);
  EXPECT_EQ(fly_speed(Box3{{1, 2, 3}, {1, 2, 3}}, 7.0), 7.0);
}

TEST(CameraJson, WritesTheCameraAsASceneMember) {
  CameraController controller(front_camera(), OrbitStart{{0, 1, 0}, 5.0});
  EXPECT_EQ(camera_json(controller),
            R"("camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40})");
  controller.fly(0.5, -0.25, 1.0);  // camera (0.5, -0.25, 4), target (0.5, -0.25, -1)
  EXPECT_EQ(camera_json(controller),
            R"("camera": {"position": [0.5, -0.25, 4], "look_at": [0.5, -0.25, -1], "up": [0, 1, 0], "fov_y": 40})");
}

// What C prints, put in a scene file, loads as the camera on screen.
TEST(CameraJson, TheLoaderReadsBackTheCameraOnScreen) {
  CameraController controller(front_camera(), OrbitStart{{0, 1, 0}, 5.0});
  controller.orbit(0.7, 0.4);
  controller.dolly(0.37);
  controller.fly(0.1, 0.2, 0.3);
  Registry registry;
  const Scene scene =
      load_scene_from_string("{\"prism\": 1, " + camera_json(controller) + "}", ".", registry, "c.json");
  const Camera& want = controller.camera();
  EXPECT_VEC3_NEAR(scene.camera.position, want.position.x, want.position.y, want.position.z);
  EXPECT_VEC3_NEAR(scene.camera.forward, want.forward.x, want.forward.y, want.forward.z);
  EXPECT_VEC3_NEAR(scene.camera.right, want.right.x, want.right.y, want.right.z);
  EXPECT_VEC3_NEAR(scene.camera.up, want.up.x, want.up.y, want.up.z);
  EXPECT_EQ(scene.camera.fov_y, 40.0);
}

}  // namespace
}  // namespace prism::viewer
