// The scene file, top to bottom. Each section reads its keys through an
// ObjectReader, so unknown keys, wrong types and out-of-range values are
// reported with their JSON path before anything is rendered.
#include "prism/scene_loader.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <system_error>
#include <vector>

#include "loader_parts.hpp"
#include "prism/errors.hpp"
#include "prism/limits.hpp"
#include "prism/texture.hpp"
#include "unit_vector.hpp"

namespace prism {

using json::Json;
using json::ObjectReader;

namespace loader {

Camera read_camera(const Json& value, const std::string& path) {
  ObjectReader r(value, path);
  Camera camera;
  camera.position = r.required_vec3("position", json::kLength);
  camera.fov_y = r.number("fov_y", 60.0, {0.0, 180.0, true, true});
  if (const Json* rot = r.find("rotation")) {
    r.require_absent("look_at", "not allowed together with rotation");
    r.require_absent("up", "not allowed together with rotation");
    glm::dmat3 R = loader::read_rotation(*rot, r.path_of("rotation"));
    camera.forward = glm::normalize(R * glm::dvec3(0, 0, -1));
    glm::dvec3 up = glm::normalize(R * glm::dvec3(0, 1, 0));
    camera.right = glm::normalize(glm::cross(camera.forward, up));
    camera.up = glm::cross(camera.right, camera.forward);
  } else {
    glm::dvec3 look_at = r.required_vec3("look_at", json::kLength);
    // rescaled: `up` may have any magnitude, and look_at may differ from
    // position by as little as 5e-324; |v|^2 must neither overflow nor vanish.
    glm::dvec3 up = rescaled(r.vec3("up", {0, 1, 0}));
    if (look_at == camera.position) json::fail(r.path_of("look_at"), "must differ from camera.position");
    camera.forward = glm::normalize(rescaled(look_at - camera.position));
    glm::dvec3 right = glm::cross(camera.forward, up);
    if (glm::length(right) <= 1e-12 * glm::length(up))
      json::fail(r.path_of("up"), "must not be zero or parallel to the view direction");
    camera.right = glm::normalize(right);
    camera.up = glm::cross(camera.right, camera.forward);
  }
  r.finish();
  return camera;
}

ImageSettings read_image(const Json& value, const std::string& path) {
  ImageSettings image;
  ObjectReader r(value, path);
  image.width = r.integer("width", image.width, 1, limits::kMaxImageSide);
  image.height = r.integer("height", image.height, 1, limits::kMaxImageSide);
  image.spp = r.integer("spp", image.spp, 1, limits::kMaxSpp);
  image.max_depth = r.integer("max_depth", image.max_depth, 1, limits::kMaxDepth);
  r.finish();
  return image;
}

TextureRequest read_texture_request(const Json& value, const std::string& name, const std::string& path,
                                    const std::filesystem::path& base_dir) {
  std::string file;
  bool srgb = true;
  if (value.is_string()) {
    file = value.get<std::string>();
  } else {
    ObjectReader r(value, path);
    file = json::read_string(r.at("path"), r.path_of("path"));
    if (const Json* s = r.find("srgb")) {
      if (!s->is_boolean()) json::fail(r.path_of("srgb"), "must be true or false, got " + json::describe(*s));
      srgb = s->get<bool>();
    }
    r.finish();
  }
  std::filesystem::path resolved = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : base_dir / file;
  return {name, resolved, srgb, path};
}

Texture read_texture(const Json& value, const std::string& name, const std::string& path,
                     const std::filesystem::path& base_dir, size_t pixels_left) {
  return std::move(load_textures({read_texture_request(value, name, path, base_dir)}, pixels_left).front());
}

size_t texture_pixels_left(const Scene& scene) {
  size_t used = 0;
  for (const Texture& t : scene.textures) used += size_t(t.width) * size_t(t.height);
  return used >= limits::kMaxTexturePixels ? 0 : limits::kMaxTexturePixels - used;
}

std::vector<std::string> names_of(const std::map<std::string, int>& by_name) {
  std::vector<std::string> names;
  for (const auto& entry : by_name) names.push_back(entry.first);
  return names;
}

int texture_index(const std::map<std::string, int>& textures, const std::string& name, const std::string& path) {
  auto it = textures.find(name);
  if (it == textures.end()) json::fail(path, json::unknown_name("texture", "textures", name, names_of(textures)));
  return it->second;
}

Material read_material(const Json& value, const std::string& path, const std::map<std::string, int>& textures) {
  ObjectReader r(value, path);
  Material m;
  m.color = r.vec3("color", m.color, json::kNonNegative);
  if (auto name = r.string("texture")) m.texture = texture_index(textures, *name, r.path_of("texture"));
  m.uv_scale = r.vec2("uv_scale", m.uv_scale);
  m.uv_offset = r.vec2("uv_offset", m.uv_offset);
  m.diffuse = r.number("diffuse", m.diffuse, json::kNonNegative);
  m.specular = r.number("specular", m.specular, json::kNonNegative);
  m.shininess = r.number("shininess", m.shininess, {1.0, INFINITY, false, false});
  m.reflect = r.number("reflect", m.reflect, json::kUnit);
  m.ior = r.number("ior", m.ior, json::kNonNegative);
  if ((m.ior > 0 && m.ior < 1) || m.ior > limits::kMaxIor)
    json::fail(r.path_of("ior"), "must be 0 (opaque) or in [1, " + json::format_number(limits::kMaxIor) + "], got " +
                                     json::format_number(m.ior));
  m.absorb = r.vec3("absorb", m.absorb, json::kNonNegative);
  if (!m.dielectric() && m.absorb != glm::dvec3(0))
    json::fail(r.path_of("absorb"), "must be [0, 0, 0] on an opaque material (ior 0)");
  r.finish();
  return m;
}

glm::dvec3 read_ambient(ObjectReader& r) { return r.vec3("ambient", {0, 0, 0}, json::kNonNegative); }
glm::dvec3 read_shadow_ambient(ObjectReader& r) { return r.vec3("shadow_ambient", {0, 0, 0}, json::kUnit); }

Light read_light(const Json& value, const std::string& path) {
  ObjectReader r(value, path);
  const std::string type = json::read_string(r.at("type"), r.path_of("type"));
  Light light;
  light.color = r.vec3("color", light.color, json::kNonNegative);
  light.intensity = r.number("intensity", light.intensity, json::kNonNegative);
  if (type == "point") {
    light.type = Light::Type::Point;
    light.position = r.required_vec3("position", json::kLength);
    light.linear = r.number("linear", 0.0, json::kNonNegative);
    light.quadratic = r.number("quadratic", 0.0, json::kNonNegative);
    light.radius = r.number("radius", 0.0, {0.0, json::kMaxLength, false, false});
  } else if (type == "directional") {
    light.type = Light::Type::Directional;
    glm::dvec3 direction = r.required_vec3("direction");
    json::require_nonzero(direction, r.path_of("direction"));
    light.direction = glm::normalize(rescaled(direction));  // any magnitude: 1e-200 and 1e300 too
  } else {
    json::fail(r.path_of("type"), "unknown light type " + quote(type) + " (expected point or directional)");
  }
  r.finish();
  return light;
}

Background read_background(const Json& value, const std::string& path, const std::map<std::string, int>& textures,
                           const Scene& scene) {
  Background bg;
  ObjectReader r(value, path);
  if (const Json* faces = r.find("cubemap")) {
    r.require_absent("color", "a background has either color or cubemap, not both");
    const std::string path = r.path_of("cubemap");
    if (!faces->is_array() || faces->size() != 6)
      json::fail(path, "must be an array of 6 texture names (+x, -x, +y, -y, +z, -z), got " + json::describe(*faces));
    for (size_t i = 0; i < 6; ++i) {
      const std::string face_path = json::index_path(path, i);
      bg.cubemap[i] = texture_index(textures, json::read_string((*faces)[i], face_path), face_path);
      const Texture& t = scene.textures[size_t(bg.cubemap[i])];
      const Texture& first = scene.textures[size_t(bg.cubemap[0])];
      if (t.width != t.height) json::fail(face_path, "cube-map faces must be square, got " +
                                                         std::to_string(t.width) + "x" + std::to_string(t.height));
      if (t.width != first.width)
        json::fail(face_path, "cube-map faces must all be the same size, got " + std::to_string(t.width) + " and " +
                                  std::to_string(first.width));
    }
  } else {
    bg.color = r.required_vec3("color", json::kNonNegative);
  }
  r.finish();
  return bg;
}

}  // namespace loader

namespace {

using namespace loader;

// Every texture shares one pixel budget (limits::kMaxTexturePixels); a file named twice counts once.
void read_textures(const Json* value, const std::filesystem::path& base_dir, Scene& scene,
                   std::map<std::string, int>& by_name) {
  if (!value) return;
  if (!value->is_object()) json::fail("textures", "must be an object of name: path, got " + json::describe(*value));
  // All at once: every header and the budget are checked before any file is decoded.
  std::vector<TextureRequest> requests;
  for (auto it = value->begin(); it != value->end(); ++it)
    requests.push_back(read_texture_request(it.value(), it.key(), json::child_path("textures", it.key()), base_dir));
  for (Texture& texture : load_textures(requests, texture_pixels_left(scene))) {
    by_name[texture.name] = static_cast<int>(scene.textures.size());
    scene.textures.push_back(std::move(texture));
  }
}

std::map<std::string, int> read_materials(const Json* value, const std::map<std::string, int>& textures, Scene& scene) {
  std::map<std::string, int> by_name;
  scene.materials.push_back(Material{});  // index 0: what an object without `material` gets
  if (!value) return by_name;
  if (!value->is_object()) json::fail("materials", "must be an object of name: material, got " + json::describe(*value));
  for (auto it = value->begin(); it != value->end(); ++it) {
    Material m = read_material(it.value(), json::child_path("materials", it.key()), textures);
    m.name = it.key();
    by_name[it.key()] = static_cast<int>(scene.materials.size());
    scene.materials.push_back(m);
  }
  return by_name;
}

template <typename ReadFn>
void for_each_in_array(const Json* value, const std::string& path, ReadFn read) {
  if (!value) return;
  if (!value->is_array()) json::fail(path, "must be an array, got " + json::describe(*value));
  for (size_t i = 0; i < value->size(); ++i) read((*value)[i], json::index_path(path, i));
}

Scene read_scene(const Json& root, const std::filesystem::path& base_dir, Registry& registry) {
  ObjectReader r(root, "");
  Scene scene;
  const Json& version = r.at("prism");
  if (!version.is_number_integer()) json::fail("prism", "must be the integer 1, got " + json::describe(version));
  if (version.get<long long>() != 1)
    json::fail("prism", "unsupported format version " + json::describe(version) + " (this build reads 1)");
  scene.camera = read_camera(r.at("camera"), "camera");
  if (const Json* image = r.find("image")) scene.image = read_image(*image, "image");
  scene.ambient = read_ambient(r);
  scene.shadow_ambient = read_shadow_ambient(r);
  std::map<std::string, int> textures;
  read_textures(r.find("textures"), base_dir, scene, textures);
  if (const Json* background = r.find("background")) scene.background = read_background(*background, "background", textures, scene);
  auto materials = read_materials(r.find("materials"), textures, scene);
  for_each_in_array(r.find("lights"), "lights",
                    [&](const Json& v, const std::string& p) { scene.lights.push_back(read_light(v, p)); });
  for_each_in_array(r.find("objects"), "objects", [&](const Json& v, const std::string& p) {
    scene.objects.push_back(loader::read_object(v, p, registry, materials, scene));
  });
  r.finish();
  return scene;
}

// Refuses a scene over the size limit. `truncated`: the text was cut one
// byte past the limit, so its size is a lower bound.
void check_scene_size(std::uintmax_t bytes, const std::string& source_name, bool truncated) {
  if (bytes <= limits::kMaxSceneFileBytes) return;
  throw InputError(source_name + ": the scene is " + (truncated ? "at least " : "") + std::to_string(bytes) +
                   " bytes, more than the limit of " + std::to_string(limits::kMaxSceneFileBytes) + " bytes (" +
                   std::to_string(limits::kMaxSceneFileBytes >> 20) + " MiB)");
}

std::string read_at_most(std::istream& in, std::uintmax_t limit) {
  std::string text;
  std::vector<char> chunk(size_t(1) << 16);
  while (text.size() < limit && in) {
    in.read(chunk.data(), std::streamsize(std::min<std::uintmax_t>(chunk.size(), limit - text.size())));
    text.append(chunk.data(), size_t(in.gcount()));
  }
  return text;
}

}  // namespace

void check_image_settings(const ImageSettings& image, const std::string& where) {
  auto check = [&](const char* name, int v, int lo, int hi) {
    if (v < lo || v > hi)
      throw InputError(where + name + ": must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                       std::to_string(v));
  };
  check("width", image.width, 1, limits::kMaxImageSide);
  check("height", image.height, 1, limits::kMaxImageSide);
  check("spp", image.spp, 1, limits::kMaxSpp);
  check("max-depth", image.max_depth, 1, limits::kMaxDepth);
}

Scene load_scene_from_string(const std::string& text, const std::filesystem::path& base_dir, Registry& registry,
                             const std::string& source_name) {
  check_scene_size(text.size(), source_name, false);
  Json root = json::parse_strict(text, source_name);
  Scene scene;
  try {
    scene = read_scene(root, base_dir, registry);
  } catch (const InputError& e) {
    throw InputError(source_name + ": " + e.what());
  }
  scene.source = source_name;
  for (const std::string& warning : loader::scene_warnings(scene))
    scene.warnings.push_back(source_name + ": " + warning);
  return scene;
}

std::string read_scene_text(const std::filesystem::path& file) {
  if (file == kStandardInput) {
    const std::string text = read_at_most(std::cin, limits::kMaxSceneFileBytes + 1);
    if (std::cin.bad()) throw InputError(std::string(kStandardInputName) + ": cannot read the scene");
    check_scene_size(text.size(), kStandardInputName, true);
    return text;
  }
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (!error) check_scene_size(size, file.string(), false);  // before reading a byte
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open scene file");
  // Pipes and devices have no size: read one byte past the limit at most.
  const std::string text = read_at_most(in, limits::kMaxSceneFileBytes + 1);
  if (in.bad()) throw InputError(file.string() + ": cannot read scene file");
  check_scene_size(text.size(), file.string(), true);
  return text;
}

Scene load_scene(const std::filesystem::path& file, Registry& registry) {
  // From standard input, texture paths are relative to the current directory (an empty base).
  if (file == kStandardInput) return load_scene_from_string(read_scene_text(file), {}, registry, kStandardInputName);
  return load_scene_from_string(read_scene_text(file), file.parent_path(), registry, file.string());
}

void write_warnings(const Scene& scene, std::ostream& out) {
  for (const std::string& warning : scene.warnings) out << "prism: warning: " << warning << "\n";
  out.flush();
}

std::vector<Camera> load_cameras_from_string(const std::string& text, const std::string& source_name) {
  check_scene_size(text.size(), source_name, false);
  const Json root = json::parse_strict(text, source_name);
  std::vector<Camera> cameras;
  try {
    ObjectReader r(root, "");
    const Json& list = r.at("cameras");
    if (!list.is_array() || list.empty())
      json::fail("cameras", "must be a non-empty array of cameras, got " + json::describe(list));
    for (size_t i = 0; i < list.size(); ++i) cameras.push_back(read_camera(list[i], json::index_path("cameras", i)));
    r.finish();
  } catch (const InputError& e) {
    throw InputError(source_name + ": " + e.what());
  }
  return cameras;
}

std::vector<Camera> load_cameras(const std::filesystem::path& file) {
  return load_cameras_from_string(read_scene_text(file), file.string());
}

}  // namespace prism
