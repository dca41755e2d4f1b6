// The viewer's camera: orbit about a target point, fly, dolly. Pure math in
// double, no window or GL: unit-tested in tests/view/camera_controller_test.cpp.
//
// The basis is rebuilt exactly as the scene loader builds it from look_at/up:
//   forward = normalize(target - position)
//   right   = normalize(cross(forward, world_up))
//   up      = cross(right, forward)            (true_up)
// Until the first move, camera() is the scene's camera bit for bit, so the
// first frame equals what `prism render` draws.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "prism/scene.hpp"

namespace prism::viewer {

// Where orbiting starts: the world up to orbit about and the distance from
// the camera to the target point along its forward axis.
struct OrbitStart {
  glm::dvec3 world_up{0, 1, 0};  // unit length
  double distance = 5.0;         // > 0
};

// What the scene file said about its camera beyond what the Scene keeps.
struct CameraHints {
  std::optional<glm::dvec3> look_at;  // camera.look_at, when given
  std::optional<glm::dvec3> up;       // camera.up, when given
  bool rotation = false;              // camera.rotation given (then up = the camera's true up)
};

// Reads camera.look_at / camera.up / camera.rotation from a scene file the
// loader has already accepted. Anything unreadable gives empty hints.
CameraHints read_camera_hints(const std::string& json_text);

// The orbit target and world up:
// - distance: |look_at - position| when the scene aims with look_at (the
//   point the author aimed at); otherwise the depth along forward of the
//   centre of the bounded objects' box when that lies in front of the
//   camera; otherwise 5 units.
// - world up: the scene's `up` (normalized) when given; with a rotation, the
//   camera's own up (which is the rotated +y); else [0,1,0].
OrbitStart orbit_start(const Camera& camera, const CameraHints& hints, const std::optional<Box3>& bounds);

// The union of the bounded objects' world boxes, if any object is bounded.
std::optional<Box3> scene_bounds(const Scene& scene);

// How fast W/A/S/D/E/Q fly, in world units per second: a quarter of the
// diagonal of the bounded objects' box (the scene crossed in about four
// seconds, whatever its units), or `target_distance` per second when no
// object is bounded or the box is a point.
double fly_speed(const std::optional<Box3>& bounds, double target_distance);

class CameraController {
 public:
  CameraController(const Camera& initial, const OrbitStart& start);

  const Camera& camera() const { return camera_; }
  glm::dvec3 target() const { return target_; }
  double distance() const { return distance_; }
  glm::dvec3 world_up() const { return world_up_; }

  // Turns the camera about the target: `yaw` radians about world up
  // (right-handed), then `pitch` radians of elevation (positive raises the
  // camera and so looks further down). Elevation is kept within
  // +-kMaxElevation of the horizon so the view never aligns with world up.
  void orbit(double yaw, double pitch);

  // Moves camera and target together by `right` along the camera's right,
  // `up` along world up and `forward` along the view direction (world units).
  void fly(double right, double up, double forward);

  // Moves the camera along its view axis: distance to the target times
  // `factor` (> 0), kept within [kMinDistance, kMaxDistance].
  void dolly(double factor);

  // Back to the camera and target it started with.
  void reset();

  static constexpr double kMaxElevation = 89.5 * 3.141592653589793 / 180.0;  // radians
  static constexpr double kMinDistance = 1e-3;
  static constexpr double kMaxDistance = 1e7;

 private:
  void rebuild_basis();

  Camera initial_, camera_;
  glm::dvec3 world_up_;
  glm::dvec3 target_;
  double initial_distance_, distance_;
};

// The controller's camera as a scene file's camera member, one line:
//   "camera": {"position": [...], "look_at": [...], "up": [...], "fov_y": 35}
// look_at is the orbit target and up the world up, from which the loader
// builds this same basis; numbers are written to read back exactly.
std::string camera_json(const CameraController& controller);

}  // namespace prism::viewer
