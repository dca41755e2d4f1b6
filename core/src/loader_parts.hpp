// Pieces of the scene loader shared between its source files.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "json_reader.hpp"
#include "prism/registry.hpp"
#include "prism/scene.hpp"
#include "prism/texture.hpp"

namespace prism::loader {

// A Rotation of the format (axis + degrees, or a quaternion) as a matrix,
// computed in long double (kept for polishing hits) and rounded to double.
RotationExt read_rotation_ext(const json::Json& value, const std::string& path);
glm::dmat3 rounded(const RotationExt& rotation);
inline glm::dmat3 read_rotation(const json::Json& value, const std::string& path) {
  return rounded(read_rotation_ext(value, path));
}

// Each part of a scene file, read from `value` with errors naming `path`
// (the JSON path in a file, the API call in prism/api.hpp).
Camera read_camera(const json::Json& value, const std::string& path);
ImageSettings read_image(const json::Json& value, const std::string& path);
// One texture: a path string or {path, srgb}, resolved against `base_dir`.
TextureRequest read_texture_request(const json::Json& value, const std::string& name, const std::string& path,
                                    const std::filesystem::path& base_dir);
Texture read_texture(const json::Json& value, const std::string& name, const std::string& path,
                     const std::filesystem::path& base_dir, size_t pixels_left);
// What the scene's textures leave of limits::kMaxTexturePixels.
size_t texture_pixels_left(const Scene& scene);
// The names of a name-to-index map, in its (alphabetical) order, for messages.
std::vector<std::string> names_of(const std::map<std::string, int>& by_name);
int texture_index(const std::map<std::string, int>& textures, const std::string& name, const std::string& path);
Material read_material(const json::Json& value, const std::string& path, const std::map<std::string, int>& textures);
Light read_light(const json::Json& value, const std::string& path);
Background read_background(const json::Json& value, const std::string& path,
                           const std::map<std::string, int>& textures, const Scene& scene);
// The top-level `ambient` and `shadow_ambient` of the object `r` reads.
glm::dvec3 read_ambient(json::ObjectReader& r);
glm::dvec3 read_shadow_ambient(json::ObjectReader& r);

// One entry of `objects`: its plugin's fields, frame and material.
Object read_object(const json::Json& value, const std::string& path, Registry& registry,
                   const std::map<std::string, int>& materials, Scene& scene);

// What looks wrong in a scene that loaded ("materials.red.color: [255, 0, 0]
// looks like 0-255 values; ..."), each with its JSON path: lighting first,
// then colours, then objects out of view.
std::vector<std::string> scene_warnings(const Scene& scene);

}  // namespace prism::loader
