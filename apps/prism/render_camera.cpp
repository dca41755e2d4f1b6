#include "render_camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <glm/glm.hpp>

#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"

namespace prism::cli {

namespace {

constexpr double kMaxCoordinate = 1e7;  // the scene format's bound on a position

// "X,Y,Z" as three finite numbers within kMaxCoordinate.
glm::dvec3 parse_point(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    const std::string part = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double value = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0')
      throw InputError(flag + ": expected three numbers X,Y,Z, got '" + text + "'");
    if (!std::isfinite(value) || std::abs(value) > kMaxCoordinate)
      throw InputError(flag + ": '" + part + "' is not a finite number of magnitude at most 1e7");
    values.push_back(value);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != 3) throw InputError(flag + ": expected three numbers X,Y,Z, got '" + text + "'");
  return {values[0], values[1], values[2]};
}

std::string json_vector(const glm::dvec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.17g, %.17g, %.17g]", v.x, v.y, v.z);
  return text;
}

}  // namespace

void check_camera_flags(const CameraFlags& flags) {
  if (flags.position.empty() != flags.look_at.empty())
    throw InputError(flags.position.empty() ? "--look-at needs --camera-position" : "--camera-position needs --look-at");
  if (flags.fov && !(*flags.fov > 0.0 && *flags.fov < 180.0)) {
    char given[32];
    std::snprintf(given, sizeof given, "%g", *flags.fov);
    throw InputError(std::string("--fov: must be between 0 and 180 degrees (both excluded), got ") + given);
  }
  if (flags.position.empty()) return;
  if (parse_point(flags.position, "--camera-position") == parse_point(flags.look_at, "--look-at"))
    throw InputError("--look-at: must differ from --camera-position");
}

Camera camera_from_flags(const CameraFlags& flags, const Camera& scene_camera) {
  Camera camera = scene_camera;
  if (!flags.position.empty()) {
    const glm::dvec3 position = parse_point(flags.position, "--camera-position");
    const glm::dvec3 look_at = parse_point(flags.look_at, "--look-at");
    // Straight up or down (as the loader judges parallel), +y cannot be the
    // image's up. Scaled to its largest component first: the difference may
    // be as small as a denormal.
    const glm::dvec3 view = look_at - position;
    const glm::dvec3 direction = view / std::max({std::abs(view.x), std::abs(view.y), std::abs(view.z)});
    const bool vertical = std::hypot(direction.x, direction.z) <= 1e-9 * glm::length(direction);
    const std::string json = "{\"cameras\": [{\"position\": " + json_vector(position) +
                             ", \"look_at\": " + json_vector(look_at) +
                             ", \"up\": " + (vertical ? "[0, 0, -1]" : "[0, 1, 0]") + "}]}";
    camera = load_cameras_from_string(json, "--camera-position").front();
  }
  if (flags.fov) camera.fov_y = *flags.fov;
  return camera;
}

}  // namespace prism::cli
