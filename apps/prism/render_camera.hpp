// `prism render --camera-position X,Y,Z --look-at X,Y,Z [--fov DEG]`: one
// camera given on the command line in place of the scene's.
#pragma once

#include <optional>
#include <string>

#include "prism/scene.hpp"

namespace prism::cli {

struct CameraFlags {
  std::string position, look_at;  // "X,Y,Z"; empty when not given
  std::optional<double> fov;      // vertical, degrees
};

// Checks the flags before anything is loaded (InputError naming the flag):
// both points or neither, three finite numbers each within the scene
// format's 1e7, position != look_at, fov in (0, 180).
void check_camera_flags(const CameraFlags& flags);

// The scene's camera with the flags applied: the camera a scene file with
// these position, look_at and fov_y would have (up is +y, or -z when the
// view is straight up or down). Without flags, `scene_camera` itself.
Camera camera_from_flags(const CameraFlags& flags, const Camera& scene_camera);

}  // namespace prism::cli
