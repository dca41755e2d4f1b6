// LiveScene: a scene file held as JSON fragments (one per material, light,
// object, ...) beside the model the backends render. Every edit rewrites a
// fragment and reads it again through the scene loader's own readers
// (loader_parts.hpp), so the API checks exactly what a file is checked for,
// with the same messages. A fragment is committed only once it has read
// cleanly: a failed edit leaves the scene as it was.
#include "api_state.hpp"

#include <atomic>

#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"

namespace prism {

using json::Json;

namespace {

uint64_t next_serial() {
  static std::atomic<uint64_t> serial{0};
  return ++serial;
}

Json vec_json(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }
Json vec_json(const glm::dvec2& v) { return Json::array({v.x, v.y}); }

Json value_json(const Value& value) {
  return std::visit(
      [](const auto& v) -> Json {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, Value::Array>) {
          Json array = Json::array();
          for (const auto& e : v) array.push_back(e ? Json(*e) : Json(nullptr));
          return array;
        } else {
          return Json(v);
        }
      },
      value.get());
}

Json rotation_json(const Rotation& rotation) {
  if (rotation.quaternion) {
    const glm::dvec4& q = *rotation.quaternion;
    return {{"quaternion", Json::array({q[0], q[1], q[2], q[3]})}};
  }
  return {{"axis", vec_json(rotation.axis)}, {"degrees", rotation.degrees}};
}

Json material_json(const MaterialDesc& m) {
  Json j = {{"color", vec_json(m.color)},       {"uv_scale", vec_json(m.uv_scale)},
            {"uv_offset", vec_json(m.uv_offset)}, {"diffuse", m.diffuse},
            {"specular", m.specular},           {"shininess", m.shininess},
            {"reflect", m.reflect},             {"ior", m.ior},
            {"absorb", vec_json(m.absorb)}};
  if (!m.texture.empty()) j["texture"] = m.texture;
  return j;
}

Json light_json(const LightDesc& light) {
  if (const auto* p = std::get_if<PointLight>(&light))
    return {{"type", "point"},          {"position", vec_json(p->position)}, {"color", vec_json(p->color)},
            {"intensity", p->intensity}, {"linear", p->linear},             {"quadratic", p->quadratic},
            {"radius", p->radius}};
  const auto& d = std::get<DirectionalLight>(light);
  return {{"type", "directional"}, {"direction", vec_json(d.direction)}, {"color", vec_json(d.color)},
          {"intensity", d.intensity}};
}

Json image_json(const ImageSettings& image) {
  return {{"width", image.width}, {"height", image.height}, {"spp", image.spp}, {"max_depth", image.max_depth}};
}

std::string quoted(const std::string& text) { return "\"" + text + "\""; }
std::string call(const std::string& name, const std::string& argument = "") { return name + "(" + argument + ")"; }
std::string object_call(const char* name, ObjectId id) { return call(name, "#" + std::to_string(id.value)); }
std::string light_call(const char* name, LightId id) { return call(name, "#" + std::to_string(id.value)); }

// The object's fields merged over `base`; `type` and `material` are not fields.
Json merged_fields(Json base, const Params& params, const std::string& path) {
  for (const auto& [key, value] : params) {
    if (key == "type") json::fail(json::child_path(path, key), "an object's type cannot change (remove it and add another)");
    base[key] = value_json(value);
  }
  return base;
}

}  // namespace

// ---- State

LiveScene::State::State(Engine& e) : engine(&e), serial(next_serial()) {}

void LiveScene::State::touch_object(size_t index) { object_stamp[index] = ++revision; }

size_t LiveScene::State::index_of(ObjectId id, const std::string& path) const {
  auto it = object_index.find(id.value);
  if (it == object_index.end()) json::fail(path, "no object has this id (removed, or from another scene)");
  return it->second;
}

ObjectId LiveScene::State::new_object_id() {
  object_ids.push_back(next_id++);
  object_index[object_ids.back()] = object_ids.size() - 1;
  return {object_ids.back()};
}

size_t LiveScene::State::light_index_of(LightId id, const std::string& path) const {
  auto it = std::ranges::find(light_ids, id.value);
  if (it == light_ids.end()) json::fail(path, "no light has this id (removed, or from another scene)");
  return size_t(it - light_ids.begin());
}

std::map<std::string, int> LiveScene::State::texture_names() const {
  std::map<std::string, int> names;
  for (size_t i = 0; i < scene.textures.size(); ++i) names[scene.textures[i].name] = int(i);
  return names;
}

std::map<std::string, int> LiveScene::State::material_names() const {
  std::map<std::string, int> names;
  for (size_t i = 1; i < scene.materials.size(); ++i) names[scene.materials[i].name] = int(i);
  return names;
}

Object LiveScene::State::read_object(const Json& fragment, const std::string& path) {
  // The plugin list only grows while the scene lives: a plugin stays loaded
  // for the backends that were prepared with it.
  return loader::read_object(fragment, path, engine->registry(), material_names(), scene);
}

ObjectId LiveScene::State::append_object(Json fragment, const std::string& path) {
  Object object = read_object(fragment, path);
  scene.objects.push_back(std::move(object));
  object_docs.push_back(std::move(fragment));
  object_stamp.push_back(++revision);
  structure_stamp = revision;
  return new_object_id();
}

void LiveScene::State::replace_object(size_t index, Json fragment, const std::string& path) {
  Object object = read_object(fragment, path);
  scene.objects[index] = std::move(object);
  object_docs[index] = std::move(fragment);
  touch_object(index);
}

LightId LiveScene::State::append_light(Json fragment, const std::string& path) {
  Light light = loader::read_light(fragment, path);
  scene.lights.push_back(light);
  light_docs.push_back(std::move(fragment));
  light_ids.push_back(next_id++);
  lights_stamp = ++revision;
  return {light_ids.back()};
}

// ---- LiveScene

LiveScene::LiveScene(Engine& engine) : state_(std::make_unique<State>(engine)) {
  State& s = *state_;
  s.scene.source = "LiveScene";
  s.scene.materials.push_back(Material{});  // index 0: what an object without `material` gets
  set_camera(CameraDesc{});
  s.image_doc = image_json(s.scene.image);
  s.background_doc = {{"color", vec_json(s.scene.background.color)}};
}

LiveScene::~LiveScene() = default;
LiveScene::LiveScene(LiveScene&&) noexcept = default;
LiveScene& LiveScene::operator=(LiveScene&&) noexcept = default;

LiveScene LiveScene::load(Engine& engine, const std::filesystem::path& file) {
  return load_json(engine, read_scene_text(file), file.parent_path(), file.string());
}

LiveScene LiveScene::load_json(Engine& engine, const std::string& text, const std::filesystem::path& base_dir,
                               const std::string& source_name) {
  LiveScene live(engine);
  State& s = *live.state_;
  s.scene = load_scene_from_string(text, base_dir, engine.registry(), source_name);
  // The text has just been read cleanly: its fragments are valid as they stand.
  const Json root = json::parse_strict(text, source_name);
  s.camera_doc = root.at("camera");
  s.image_doc = image_json(s.scene.image);
  s.background_doc = root.value("background", Json{{"color", Json::array({0, 0, 0})}});
  for (const Texture& t : s.scene.textures)
    s.texture_docs[t.name] = {{"path", std::filesystem::absolute(t.path).string()}, {"srgb", true}};
  if (root.contains("textures"))
    for (auto it = root["textures"].begin(); it != root["textures"].end(); ++it)
      if (it.value().is_object() && it.value().contains("srgb")) s.texture_docs[it.key()]["srgb"] = it.value()["srgb"];
  if (root.contains("materials"))
    for (auto it = root["materials"].begin(); it != root["materials"].end(); ++it) s.material_docs[it.key()] = it.value();
  for (const Json& light : root.value("lights", Json::array())) {
    s.light_docs.push_back(light);
    s.light_ids.push_back(s.next_id++);
  }
  for (const Json& object : root.value("objects", Json::array())) {
    s.object_docs.push_back(object);
    s.new_object_id();
    s.object_stamp.push_back(0);
  }
  s.revision = 1;
  s.structure_stamp = s.materials_stamp = s.lights_stamp = s.textures_stamp = s.environment_stamp = 1;
  return live;
}

void LiveScene::set_camera(const CameraDesc& camera) {
  Json fragment = {{"position", vec_json(camera.position)},
                   {"look_at", vec_json(camera.look_at)},
                   {"up", vec_json(camera.up)},
                   {"fov_y", camera.fov_y}};
  state_->scene.camera = loader::read_camera(fragment, call("set_camera"));
  state_->camera_doc = std::move(fragment);
  ++state_->revision;  // the camera travels with each render, not in the backend's data
}

void LiveScene::set_camera(const glm::dvec3& position, const Rotation& rotation, double fov_y) {
  Json fragment = {{"position", vec_json(position)}, {"rotation", rotation_json(rotation)}, {"fov_y", fov_y}};
  state_->scene.camera = loader::read_camera(fragment, call("set_camera"));
  state_->camera_doc = std::move(fragment);
  ++state_->revision;
}

void LiveScene::set_image(const ImageSettings& image) {
  Json fragment = image_json(image);
  state_->scene.image = loader::read_image(fragment, call("set_image"));
  state_->image_doc = std::move(fragment);
  ++state_->revision;
}

void LiveScene::set_background(const glm::dvec3& color) {
  Json fragment = {{"color", vec_json(color)}};
  State& s = *state_;
  s.scene.background = loader::read_background(fragment, call("set_background"), s.texture_names(), s.scene);
  s.background_doc = std::move(fragment);
  s.environment_stamp = ++s.revision;
}

void LiveScene::set_background_cubemap(const std::array<std::string, 6>& faces) {
  Json fragment = {{"cubemap", Json(faces)}};
  State& s = *state_;
  s.scene.background = loader::read_background(fragment, call("set_background_cubemap"), s.texture_names(), s.scene);
  s.background_doc = std::move(fragment);
  s.environment_stamp = ++s.revision;
}

void LiveScene::set_ambient(const glm::dvec3& ambient) {
  Json fragment = {{"ambient", vec_json(ambient)}};
  json::ObjectReader r(fragment, call("set_ambient"));
  state_->scene.ambient = loader::read_ambient(r);
  state_->environment_stamp = ++state_->revision;
}

void LiveScene::set_shadow_ambient(const glm::dvec3& shadow_ambient) {
  Json fragment = {{"shadow_ambient", vec_json(shadow_ambient)}};
  json::ObjectReader r(fragment, call("set_shadow_ambient"));
  state_->scene.shadow_ambient = loader::read_shadow_ambient(r);
  state_->environment_stamp = ++state_->revision;
}

void LiveScene::add_texture(const std::string& name, const std::filesystem::path& file, bool srgb) {
  State& s = *state_;
  const std::string path = call("add_texture", quoted(name));
  if (s.texture_docs.count(name)) json::fail(path, "a texture of this name exists already");
  const std::filesystem::path absolute = std::filesystem::absolute(file);
  Json fragment = {{"path", absolute.string()}, {"srgb", srgb}};
  Texture texture = loader::read_texture(fragment, name, path, {}, loader::texture_pixels_left(s.scene));
  s.scene.textures.push_back(std::move(texture));
  s.texture_docs[name] = std::move(fragment);
  s.textures_stamp = ++s.revision;
}

void LiveScene::set_material(const std::string& name, const MaterialDesc& material) {
  State& s = *state_;
  const std::string path = call("set_material", quoted(name));
  if (name.empty()) json::fail(path, "a material needs a name");
  Json fragment = material_json(material);
  Material m = loader::read_material(fragment, path, s.texture_names());
  m.name = name;
  auto names = s.material_names();
  if (auto it = names.find(name); it != names.end()) {
    s.scene.materials[size_t(it->second)] = m;
  } else {
    s.scene.materials.push_back(m);
  }
  s.material_docs[name] = std::move(fragment);
  s.materials_stamp = ++s.revision;
}

ObjectId LiveScene::add_object(const std::string& type, const Params& params, const std::string& material,
                               const std::optional<Rotation>& rotation) {
  const std::string path = call("add_object", quoted(type));
  Json fragment = merged_fields(Json{{"type", type}}, params, path);
  if (!material.empty()) fragment["material"] = material;
  if (rotation) fragment["rotation"] = rotation_json(*rotation);
  return state_->append_object(std::move(fragment), path);
}

void LiveScene::update_object(ObjectId id, const Params& params) {
  const std::string path = object_call("update_object", id);
  const size_t index = state_->index_of(id, path);
  state_->replace_object(index, merged_fields(state_->object_docs[index], params, path), path);
}

void LiveScene::move_object(ObjectId id, const glm::dvec3& center) {
  const std::string path = object_call("move_object", id);
  const size_t index = state_->index_of(id, path);
  Json fragment = state_->object_docs[index];
  fragment["center"] = vec_json(center);
  state_->replace_object(index, std::move(fragment), path);
}

void LiveScene::rotate_object(ObjectId id, const std::optional<Rotation>& rotation) {
  const std::string path = object_call("rotate_object", id);
  const size_t index = state_->index_of(id, path);
  Json fragment = state_->object_docs[index];
  if (rotation) {
    fragment["rotation"] = rotation_json(*rotation);
  } else {
    fragment.erase("rotation");
  }
  state_->replace_object(index, std::move(fragment), path);
}

void LiveScene::set_object_material(ObjectId id, const std::string& material) {
  const std::string path = object_call("set_object_material", id);
  const size_t index = state_->index_of(id, path);
  Json fragment = state_->object_docs[index];
  if (material.empty()) {
    fragment.erase("material");
  } else {
    fragment["material"] = material;
  }
  state_->replace_object(index, std::move(fragment), path);
}

void LiveScene::remove_object(ObjectId id) {
  State& s = *state_;
  const size_t index = s.index_of(id, object_call("remove_object", id));
  const auto at = [index](auto& v) { v.erase(v.begin() + std::ptrdiff_t(index)); };
  at(s.scene.objects);
  at(s.object_docs);
  at(s.object_stamp);
  s.object_index.erase(s.object_ids[index]);
  at(s.object_ids);
  for (size_t i = index; i < s.object_ids.size(); ++i) s.object_index[s.object_ids[i]] = i;
  s.structure_stamp = ++s.revision;
}

LightId LiveScene::add_light(const LightDesc& light) { return state_->append_light(light_json(light), call("add_light")); }

void LiveScene::update_light(LightId id, const LightDesc& light) {
  State& s = *state_;
  const std::string path = light_call("update_light", id);
  const size_t index = s.light_index_of(id, path);
  Json fragment = light_json(light);
  s.scene.lights[index] = loader::read_light(fragment, path);
  s.light_docs[index] = std::move(fragment);
  s.lights_stamp = ++s.revision;
}

void LiveScene::remove_light(LightId id) {
  State& s = *state_;
  const size_t index = s.light_index_of(id, light_call("remove_light", id));
  const auto at = [index](auto& v) { v.erase(v.begin() + std::ptrdiff_t(index)); };
  at(s.scene.lights);
  at(s.light_docs);
  at(s.light_ids);
  s.lights_stamp = ++s.revision;
}

const Scene& LiveScene::scene() const { return state_->scene; }
size_t LiveScene::object_count() const { return state_->scene.objects.size(); }

int LiveScene::object_index(ObjectId id) const {
  auto it = state_->object_index.find(id.value);
  return it == state_->object_index.end() ? -1 : int(it->second);
}

ObjectId LiveScene::object_at(size_t index) const {
  if (index >= state_->object_ids.size())
    throw InputError(call("object_at", std::to_string(index)) + ": the scene has " +
                     std::to_string(state_->object_ids.size()) + " objects");
  return {state_->object_ids[index]};
}

LightId LiveScene::light_at(size_t index) const {
  if (index >= state_->light_ids.size())
    throw InputError(call("light_at", std::to_string(index)) + ": the scene has " +
                     std::to_string(state_->light_ids.size()) + " lights");
  return {state_->light_ids[index]};
}

std::string LiveScene::to_json() const {
  const State& s = *state_;
  Json root = {{"prism", 1},
               {"camera", s.camera_doc},
               {"image", s.image_doc},
               {"background", s.background_doc},
               {"ambient", vec_json(s.scene.ambient)},
               {"shadow_ambient", vec_json(s.scene.shadow_ambient)},
               {"textures", Json::object()},
               {"materials", Json::object()},
               {"lights", Json(s.light_docs)},
               {"objects", Json(s.object_docs)}};
  for (const auto& [name, doc] : s.texture_docs) root["textures"][name] = doc;
  for (const auto& [name, doc] : s.material_docs) root["materials"][name] = doc;
  return root.dump(2) + "\n";
}

void LiveScene::save(const std::filesystem::path& file) const {
  write_text_file_atomically(file, to_json());
}

}  // namespace prism
