// Warnings about a scene that loads but is probably not what its author
// meant: it renders black, a colour written in 0-255, an object the camera
// cannot see. They never change whether the scene loads.
#include <algorithm>
#include <cmath>

#include "json_reader.hpp"
#include "loader_parts.hpp"

namespace prism::loader {

namespace {

// At most this many objects behind the camera are named one by one.
constexpr size_t kMaxNamedObjectsBehind = 5;

std::string vec3_text(const glm::dvec3& v) {
  return "[" + json::format_number(v.x) + ", " + json::format_number(v.y) + ", " + json::format_number(v.z) + "]";
}

// Above 1 but whole numbers up to 255: written as 8-bit channel values.
bool looks_like_0_255(const glm::dvec3& colour) {
  const double top = std::max({colour.x, colour.y, colour.z});
  if (top <= 1 || top > 255) return false;
  for (int i = 0; i < 3; ++i)
    if (colour[i] != std::floor(colour[i])) return false;
  return true;
}

void check_colour(const glm::dvec3& colour, const std::string& path, std::vector<std::string>& warnings) {
  if (looks_like_0_255(colour))
    warnings.push_back(path + ": " + vec3_text(colour) +
                       " looks like 0-255 values; colours run from 0 to 1 (divide by 255)");
}

void check_colours(const Scene& scene, std::vector<std::string>& warnings) {
  check_colour(scene.ambient, "ambient", warnings);
  if (!scene.background.has_cubemap()) check_colour(scene.background.color, "background.color", warnings);
  for (size_t i = 1; i < scene.materials.size(); ++i) {  // 0: the default material, not in the file
    const std::string path = json::child_path(json::child_path("materials", scene.materials[i].name), "color");
    check_colour(scene.materials[i].color, path, warnings);
  }
  for (size_t i = 0; i < scene.lights.size(); ++i)
    check_colour(scene.lights[i].color, json::child_path(json::index_path("lights", i), "color"), warnings);
}

// Whether the whole box lies behind the plane through the camera facing
// its view direction: even its corner farthest along the view is behind.
bool behind_camera(const Box3& box, const Camera& camera) {
  double farthest = 0;
  for (int i = 0; i < 3; ++i)
    farthest += std::max((box.lo[i] - camera.position[i]) * camera.forward[i],
                         (box.hi[i] - camera.position[i]) * camera.forward[i]);
  return farthest < 0;
}

void check_objects_in_view(const Scene& scene, std::vector<std::string>& warnings) {
  size_t behind = 0;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    if (!object.bounded || !behind_camera(object.world_bounds, scene.camera)) continue;
    if (++behind <= kMaxNamedObjectsBehind)
      warnings.push_back(json::index_path("objects", i) +
                         ": entirely behind the camera (it can show only in reflections)");
  }
  if (behind > kMaxNamedObjectsBehind)
    warnings.push_back("objects: " + std::to_string(behind - kMaxNamedObjectsBehind) +
                       " more objects entirely behind the camera");
}

// Mirrors and glass show what is around them (a sky box) without any light.
bool needs_light(const Material& material) { return material.reflect < 1 && !material.dielectric(); }

void check_lighting(const Scene& scene, std::vector<std::string>& warnings) {
  if (!scene.lights.empty() || scene.ambient != glm::dvec3(0)) return;
  for (const Object& object : scene.objects) {
    if (!needs_light(scene.materials[size_t(object.material)])) continue;
    warnings.push_back("lights: the scene has no lights and no ambient, so objects other than mirrors and glass "
                       "render black");
    return;
  }
}

}  // namespace

std::vector<std::string> scene_warnings(const Scene& scene) {
  std::vector<std::string> warnings;
  check_lighting(scene, warnings);
  check_colours(scene, warnings);
  check_objects_in_view(scene, warnings);
  return warnings;
}

}  // namespace prism::loader
