// Pieces of the scene loader shared between its source files.
#pragma once

#include <map>
#include <string>

#include "json_reader.hpp"
#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism::loader {

// A Rotation of the format (axis + degrees, or a quaternion) as a matrix,
// computed in long double (kept for polishing hits) and rounded to double.
RotationExt read_rotation_ext(const json::Json& value, const std::string& path);
glm::dmat3 rounded(const RotationExt& rotation);
inline glm::dmat3 read_rotation(const json::Json& value, const std::string& path) {
  return rounded(read_rotation_ext(value, path));
}

// One entry of `objects`: its plugin's fields, frame and material.
Object read_object(const json::Json& value, const std::string& path, Registry& registry,
                   const std::map<std::string, int>& materials, Scene& scene);

}  // namespace prism::loader
