// Prism as a library: build or load a scene in code, edit it live, render it
// with any backend, and render again after an edit at the cost of what
// changed. docs/api.md is the reference; examples/animated uses all of it.
//
//   prism::Engine engine;                        // finds the plugins
//   prism::LiveScene scene(engine);              // an empty scene
//   scene.set_camera({.position = {0, 2, 8}, .look_at = {0, 1, 0}});
//   scene.set_material("red", {.color = {0.8, 0.1, 0.1}});
//   prism::ObjectId ball = scene.add_object("sphere", {{"center", {0, 1, 0}}, {"radius", 1.0}}, "red");
//   scene.add_light(prism::PointLight{.position = {4, 6, 4}});
//   prism::Renderer renderer(engine, "auto");    // or "embree", "vulkan", ...
//   prism::Image first = renderer.render(scene);
//   scene.move_object(ball, {0.5, 1, 0});
//   prism::Image second = renderer.render(scene); // only the sphere is sent again
//
// Every value is checked by the same code that checks a scene file, with the
// same messages; the path names the API call instead of the JSON key:
//   add_object("sphere").radius: must be > 0, got -1
// Errors are prism::InputError (bad values) and prism::RuntimeError (a
// backend that cannot start or fails).
//
// Threads: an Engine may be shared by any number of threads. A LiveScene and
// a Renderer are each used by one thread at a time; two scenes rendered by
// two renderers on two threads at once is fine, and so is one scene rendered
// by several renderers in turn. Do not edit a scene while a renderer renders it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "prism/backend.hpp"
#include "prism/errors.hpp"
#include "prism/scene.hpp"

namespace prism {

class Registry;

// Finds and loads plugins (primitive types and backends). Searches
// PRISM_PLUGIN_PATH, then <folder of libprism_core.so>/prism, then
// <folder of the executable>/../lib/prism, unless told where to look.
class Engine {
 public:
  Engine();
  explicit Engine(std::vector<std::filesystem::path> plugin_path);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  std::vector<std::string> primitive_types() const;  // found, not necessarily loadable
  std::vector<std::string> backends() const;          // found, not necessarily usable here
  // The name `auto` resolves to: the fastest backend that can run here.
  std::string auto_backend() const;
  Registry& registry() const { return *registry_; }

 private:
  std::unique_ptr<Registry> registry_;
};

// A rotation: `degrees` about `axis` (right-hand rule), or a quaternion.
struct Rotation {
  glm::dvec3 axis{0, 1, 0};
  double degrees = 0;
  // (w, x, y, z) in components 0..3, any non-zero length; when set, axis and degrees are not used.
  std::optional<glm::dvec4> quaternion{};
};

// One value of an object's field: a number, an array of numbers (or nulls,
// where the type allows them), a string or a boolean.
class Value {
 public:
  using Array = std::vector<std::optional<double>>;
  Value(double number) : v_(number) {}
  Value(int number) : v_(double(number)) {}
  Value(glm::dvec2 v) : v_(Array{v.x, v.y}) {}
  Value(glm::dvec3 v) : v_(Array{v.x, v.y, v.z}) {}
  Value(std::initializer_list<double> v) : v_(Array(v.begin(), v.end())) {}
  Value(Array v) : v_(std::move(v)) {}
  Value(const char* text) : v_(std::string(text)) {}
  Value(std::string text) : v_(std::move(text)) {}
  Value(bool flag) : v_(flag) {}
  const std::variant<double, Array, std::string, bool>& get() const { return v_; }

 private:
  std::variant<double, Array, std::string, bool> v_;
};

// An object's fields by name, as in a scene file: {{"radius", 1.0}, {"center", glm::dvec3{0, 1, 0}}}.
using Params = std::vector<std::pair<std::string, Value>>;

// A material; the defaults are the scene format's. `texture`: a texture's name, empty for none.
struct MaterialDesc {
  glm::dvec3 color{0.8, 0.8, 0.8};
  std::string texture{};
  glm::dvec2 uv_scale{1, 1};
  glm::dvec2 uv_offset{0, 0};
  double diffuse = 1.0;
  double specular = 0.0;
  double shininess = 32.0;
  double reflect = 0.0;
  double ior = 0.0;  // 0: opaque; >= 1: a dielectric
  glm::dvec3 absorb{0, 0, 0};
};

struct PointLight {
  glm::dvec3 position{0, 0, 0};
  glm::dvec3 color{1, 1, 1};
  double intensity = 1.0;
  double linear = 0.0;
  double quadratic = 0.0;
  double radius = 0.0;  // > 0: a visible sphere
};

struct DirectionalLight {
  glm::dvec3 direction{0, -1, 0};  // any non-zero length
  glm::dvec3 color{1, 1, 1};
  double intensity = 1.0;
};

using LightDesc = std::variant<PointLight, DirectionalLight>;

struct CameraDesc {
  glm::dvec3 position{0, 0, 5};
  glm::dvec3 look_at{0, 0, 0};
  glm::dvec3 up{0, 1, 0};
  double fov_y = 60.0;  // degrees, vertical
};

// Stable handles: they stay valid while other objects and lights come and go.
struct ObjectId {
  uint64_t value = 0;
  friend bool operator==(ObjectId, ObjectId) = default;
};
struct LightId {
  uint64_t value = 0;
  friend bool operator==(LightId, LightId) = default;
};

// A scene that code builds and edits. It is always valid: an edit that
// fails leaves the scene as it was. Renderers that render it pick up only
// what changed since they last rendered it.
class LiveScene {
 public:
  // An empty scene: default camera, 640x360, 1 spp, depth 5, black background.
  explicit LiveScene(Engine& engine);
  // A scene file; its objects get ids in file order, its lights too.
  static LiveScene load(Engine& engine, const std::filesystem::path& file);
  // The same from a scene file's text (e.g. a Python dict turned into JSON);
  // relative texture paths resolve against `base_dir`, and errors begin with
  // `source_name` as they begin with the file's name.
  static LiveScene load_json(Engine& engine, const std::string& json, const std::filesystem::path& base_dir,
                             const std::string& source_name = "<string>");
  ~LiveScene();
  LiveScene(LiveScene&&) noexcept;
  LiveScene& operator=(LiveScene&&) noexcept;

  // --- whole-scene settings
  void set_camera(const CameraDesc& camera);
  void set_camera(const glm::dvec3& position, const Rotation& rotation, double fov_y = 60.0);
  void set_image(const ImageSettings& image);
  void set_background(const glm::dvec3& color);
  void set_background_cubemap(const std::array<std::string, 6>& faces);  // texture names: +x -x +y -y +z -z
  void set_ambient(const glm::dvec3& ambient);
  void set_shadow_ambient(const glm::dvec3& shadow_ambient);

  // --- textures and materials, by name
  void add_texture(const std::string& name, const std::filesystem::path& file, bool srgb = true);
  // Adds the material, or replaces the one of that name (objects using it follow).
  void set_material(const std::string& name, const MaterialDesc& material);

  // --- objects: any primitive type through its plugin. There are no
  // per-type helpers: `params` are the fields the plugin declares, checked
  // against its own field table, so a new primitive plugin needs no API edit.
  ObjectId add_object(const std::string& type, const Params& params, const std::string& material = "",
                      const std::optional<Rotation>& rotation = std::nullopt);
  // Changes some fields of an object (the others keep their values).
  void update_object(ObjectId id, const Params& params);
  void move_object(ObjectId id, const glm::dvec3& center);
  void rotate_object(ObjectId id, const std::optional<Rotation>& rotation);  // nullopt: no rotation
  void set_object_material(ObjectId id, const std::string& material);
  void remove_object(ObjectId id);

  // --- lights
  LightId add_light(const LightDesc& light);
  void update_light(LightId id, const LightDesc& light);
  void remove_light(LightId id);

  // --- reading back
  const Scene& scene() const;                    // the validated model the backends render
  size_t object_count() const;
  int object_index(ObjectId id) const;           // its index in scene().objects (the id AOV's id); -1 if removed
  ObjectId object_at(size_t index) const;        // the id of scene().objects[index] (e.g. of a loaded scene)
  LightId light_at(size_t index) const;          // the id of scene().lights[index]
  std::string to_json() const;                   // the scene as a scene file, textures by absolute path
  void save(const std::filesystem::path& file) const;  // written atomically

  struct State;  // the document, its model and its change stamps (api_scene.cpp)
  State& state() const { return *state_; }

 private:
  std::unique_ptr<State> state_;
};

// Counters of what a renderer's backend did, since the renderer was made.
struct UpdateCounters {
  uint64_t prepares = 0;         // full preparations (first render, another scene)
  uint64_t updates = 0;          // incremental updates
  uint64_t objects_uploaded = 0; // object records the backend read or sent again
  uint64_t bvh_builds = 0;
  uint64_t bvh_refits = 0;
  uint64_t kernel_builds = 0;    // GPU kernels generated and built
};

// What one render may change from the scene's image settings, and the AOVs
// it adds to the Image (as `prism render --aov id,path,depth,normal,albedo`
// writes them).
struct RenderOptions {
  std::optional<int> width, height, spp, max_depth;  // unset: the scene's
  bool aov_id = false;    // Image::id: the object seen in each pixel
  bool aov_path = false;  // Image::path: each pixel's path signature (sample 0)
  bool aov_depth = false;   // Image::depth: sample 0's first-hit t (+inf: a miss)
  bool aov_normal = false;  // Image::normal: its outward unit normal (0: a miss)
  bool aov_albedo = false;  // Image::albedo: its surface colour (0: a miss)
};

// One backend, prepared for one scene at a time. Each render brings the
// backend up to date with the scene first.
class Renderer {
 public:
  // `precision` as `--precision` (Backend::set_precision): a backend that
  // cannot compute in it throws InputError here.
  Renderer(Engine& engine, const std::string& backend = "auto", Precision precision = Precision::automatic);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const std::string& backend_name() const;

  // The scene's camera and image settings.
  Image render(const LiveScene& scene);
  // The same with `options` applied; an override out of range is an InputError
  // ("render().width: must be in [1, 16384], got 0").
  Image render(const LiveScene& scene, const RenderOptions& options);
  // The same into a caller-owned buffer of width * height * 3 floats (linear RGB, row 0 at the top).
  void render_into(const LiveScene& scene, std::span<float> rgb);
  // The same to an image file (.png, .exr, ... by extension), written atomically.
  void render_to_file(const LiveScene& scene, const std::filesystem::path& file);
  // Closest hits, light spheres included (`prism trace`).
  std::vector<TraceResult> trace(const LiveScene& scene, std::span<const TraceQuery> rays);

  UpdateCounters counters() const;
  BackendStats stats() const;

 private:
  void sync(const LiveScene& scene);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace prism
