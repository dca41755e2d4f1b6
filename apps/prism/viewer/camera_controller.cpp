#include "camera_controller.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

namespace prism::viewer {

namespace {

std::optional<glm::dvec3> vec3_member(const nlohmann::json& object, const char* key) {
  auto it = object.find(key);
  if (it == object.end() || !it->is_array() || it->size() != 3) return std::nullopt;
  glm::dvec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!(*it)[i].is_number()) return std::nullopt;
    v[i] = (*it)[i].get<double>();
  }
  return v;
}

// The shortest text that reads back as exactly `v`.
std::string number_text(double v) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, v);
  return std::string(text, result.ptr);
}

std::string vec3_text(const glm::dvec3& v) {
  return "[" + number_text(v.x) + ", " + number_text(v.y) + ", " + number_text(v.z) + "]";
}

// A quarter of the diagonal: the scene crossed in about four seconds.
constexpr double kSceneDiagonalsPerSecond = 0.25;

}  // namespace

CameraHints read_camera_hints(const std::string& json_text) {
  CameraHints hints;
  nlohmann::json doc = nlohmann::json::parse(json_text, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return hints;
  auto camera = doc.find("camera");
  if (camera == doc.end() || !camera->is_object()) return hints;
  hints.look_at = vec3_member(*camera, "look_at");
  hints.up = vec3_member(*camera, "up");
  hints.rotation = camera->contains("rotation");
  return hints;
}

std::optional<Box3> scene_bounds(const Scene& scene) {
  std::optional<Box3> box;
  for (const auto& object : scene.objects) {
    if (!object.bounded) continue;
    if (!box) {
      box = object.world_bounds;
    } else {
      box->lo = glm::min(box->lo, object.world_bounds.lo);
      box->hi = glm::max(box->hi, object.world_bounds.hi);
    }
  }
  return box;
}

double fly_speed(const std::optional<Box3>& bounds, double target_distance) {
  if (bounds) {
    const double diagonal = glm::length(bounds->hi - bounds->lo);
    if (diagonal > 0.0 && std::isfinite(diagonal)) return diagonal * kSceneDiagonalsPerSecond;
  }
  return target_distance;
}

OrbitStart orbit_start(const Camera& camera, const CameraHints& hints, const std::optional<Box3>& bounds) {
  OrbitStart start;
  if (hints.up && glm::length(*hints.up) > 0.0) {
    start.world_up = glm::normalize(*hints.up);
  } else if (hints.rotation) {
    start.world_up = camera.up;
  }
  if (hints.look_at) {
    const double d = glm::length(*hints.look_at - camera.position);
    if (d > 0.0 && std::isfinite(d)) {
      start.distance = d;
      return start;
    }
  }
  if (bounds) {
    const glm::dvec3 centre = 0.5 * (bounds->lo + bounds->hi);
    const double depth = glm::dot(centre - camera.position, camera.forward);
    if (depth > CameraController::kMinDistance && std::isfinite(depth)) start.distance = depth;
  }
  return start;
}

CameraController::CameraController(const Camera& initial, const OrbitStart& start)
    : initial_(initial),
      camera_(initial),
      world_up_(start.world_up),
      target_(initial.position + initial.forward * start.distance),
      initial_distance_(start.distance),
      distance_(start.distance) {}

void CameraController::orbit(double yaw, double pitch) {
  const glm::dvec3 u = world_up_;
  const glm::dvec3 offset = camera_.position - target_;
  // The horizontal direction from the target to the camera: -forward with
  // its world-up part removed. right is perpendicular to world up by
  // construction, so cross(right, up) is that direction, even when the view
  // is almost vertical.
  glm::dvec3 horizontal = glm::normalize(glm::cross(camera_.right, u));
  const double elevation = std::atan2(glm::dot(offset, u), glm::length(offset - glm::dot(offset, u) * u));
  // Rodrigues about u for a vector perpendicular to u.
  horizontal = horizontal * std::cos(yaw) + glm::cross(u, horizontal) * std::sin(yaw);
  const double e = std::clamp(elevation + pitch, -kMaxElevation, kMaxElevation);
  camera_.position = target_ + distance_ * (std::cos(e) * horizontal + std::sin(e) * u);
  rebuild_basis();
}

void CameraController::fly(double right, double up, double forward) {
  const glm::dvec3 move = right * camera_.right + up * world_up_ + forward * camera_.forward;
  camera_.position += move;
  target_ += move;
}

void CameraController::dolly(double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  distance_ = std::clamp(distance_ * factor, kMinDistance, kMaxDistance);
  camera_.position = target_ - camera_.forward * distance_;
}

void CameraController::reset() {
  camera_ = initial_;
  distance_ = initial_distance_;
  target_ = initial_.position + initial_.forward * initial_distance_;
}

void CameraController::rebuild_basis() {
  camera_.forward = glm::normalize(target_ - camera_.position);
  camera_.right = glm::normalize(glm::cross(camera_.forward, world_up_));
  camera_.up = glm::cross(camera_.right, camera_.forward);
}

std::string camera_json(const CameraController& controller) {
  const Camera& camera = controller.camera();
  return "\"camera\": {\"position\": " + vec3_text(camera.position) + ", \"look_at\": " +
         vec3_text(controller.target()) + ", \"up\": " + vec3_text(controller.world_up()) +
         ", \"fov_y\": " + number_text(camera.fov_y) + "}";
}

}  // namespace prism::viewer
