// A scene built through the library API renders the same image, bit for
// bit, as the equivalent scene file, on every backend; a scene loaded from a
// file and edited renders as the edited file would.
#include <algorithm>
#include <cstring>

#include "prism/api.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

class ApiScene : public BackendTest {};

fs::path textures() { return source_dir() / "scenes" / "textures"; }

// Every primitive type, textures and a cube map, both light kinds and a
// light sphere, a dielectric with absorption, a mirror.
constexpr const char* kSceneJson = R"({
  "prism": 1,
  "camera": { "position": [0, 2.5, 9], "look_at": [0, 0.8, 0], "fov_y": 45 },
  "image": { "width": 64, "height": 40, "spp": 2, "max_depth": 4 },
  "background": { "cubemap": ["sky_px", "sky_nx", "sky_py", "sky_ny", "sky_pz", "sky_nz"] },
  "ambient": [0.05, 0.06, 0.07],
  "shadow_ambient": [0.1, 0.1, 0.12],
  "textures": {
    "checker": "checker.png", "planet": "planet.png",
    "sky_px": "sky_px.png", "sky_nx": "sky_nx.png", "sky_py": "sky_py.png",
    "sky_ny": "sky_ny.png", "sky_pz": "sky_pz.png", "sky_nz": "sky_nz.png"
  },
  "materials": {
    "floor": { "color": [0.6, 0.6, 0.6], "texture": "checker", "uv_scale": [0.25, 0.25], "reflect": 0.1 },
    "glass": { "ior": 1.5, "absorb": [0.2, 0.05, 0.02] },
    "mirror": { "color": [0.9, 0.9, 0.9], "reflect": 0.8, "specular": 0.5, "shininess": 100 },
    "planet": { "texture": "planet", "color": [1, 1, 1], "specular": 0.3 },
    "copper": { "color": [0.85, 0.45, 0.25], "specular": 0.7, "shininess": 60, "reflect": 0.2 }
  },
  "lights": [
    { "type": "directional", "direction": [-0.5, -0.5, 0.7], "intensity": 0.6 },
    { "type": "point", "position": [2, 3.5, 2], "color": [1, 0.8, 0.6], "linear": 0.1, "radius": 0.15 }
  ],
  "objects": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
    { "type": "sphere", "center": [-1.5, 1, 1], "radius": 1, "material": "glass" },
    { "type": "sphere", "center": [1.8, 1, -0.5], "radius": 1, "material": "mirror" },
    { "type": "sphere", "center": [0, 1.3, -3], "radius": 0.8, "material": "planet",
      "rotation": { "axis": [1, 0, -0.5], "degrees": 30 } },
    { "type": "ring", "center": [0, 1.3, -3], "inner_radius": 1, "outer_radius": 1.4, "material": "copper",
      "rotation": { "axis": [1, 0, -0.5], "degrees": 30 } },
    { "type": "box", "center": [-3, 0.6, 2.5], "half_size": [0.6, 0.6, 0.6], "material": "copper",
      "rotation": { "axis": [0, 1, 0], "degrees": 30 } },
    { "type": "torus", "center": [-4, 0.9, -2], "major_radius": 0.6, "minor_radius": 0.2,
      "rotation": { "quaternion": [0.8, 0.6, 0, 0] } },
    { "type": "cylinder", "center": [3, 0, 2.5], "radius": 0.45, "height": 1.1, "material": "copper" },
    { "type": "cone", "center": [4, 1.6, -1.8], "radius": 0.6, "height": 1.6,
      "rotation": { "axis": [1, 0, 0], "degrees": 180 } },
    { "type": "quadric", "coefficients": [1, 0, 1, 0, 0, 0, 0, -0.2, 0, -0.3],
      "center": [0, 0.5, 3], "clip_min": [null, 0, null], "clip_max": [null, 1.5, null], "material": "mirror" }
  ]
})";

// kSceneJson, built in code.
void build_in_code(LiveScene& s) {
  s.set_camera({.position = {0, 2.5, 9}, .look_at = {0, 0.8, 0}, .fov_y = 45});
  s.set_image({.width = 64, .height = 40, .spp = 2, .max_depth = 4});
  for (const char* name : {"checker", "planet", "sky_px", "sky_nx", "sky_py", "sky_ny", "sky_pz", "sky_nz"})
    s.add_texture(name, textures() / (std::string(name) + ".png"));
  s.set_background_cubemap({"sky_px", "sky_nx", "sky_py", "sky_ny", "sky_pz", "sky_nz"});
  s.set_ambient({0.05, 0.06, 0.07});
  s.set_shadow_ambient({0.1, 0.1, 0.12});
  s.set_material("floor", {.color = {0.6, 0.6, 0.6}, .texture = "checker", .uv_scale = {0.25, 0.25}, .reflect = 0.1});
  s.set_material("glass", {.ior = 1.5, .absorb = {0.2, 0.05, 0.02}});
  s.set_material("mirror", {.color = {0.9, 0.9, 0.9}, .specular = 0.5, .shininess = 100, .reflect = 0.8});
  s.set_material("planet", {.color = {1, 1, 1}, .texture = "planet", .specular = 0.3});
  s.set_material("copper", {.color = {0.85, 0.45, 0.25}, .specular = 0.7, .shininess = 60, .reflect = 0.2});
  s.add_light(DirectionalLight{.direction = {-0.5, -0.5, 0.7}, .intensity = 0.6});
  s.add_light(PointLight{.position = {2, 3.5, 2}, .color = {1, 0.8, 0.6}, .linear = 0.1, .radius = 0.15});
  const Rotation tilt{.axis = {1, 0, -0.5}, .degrees = 30};
  s.add_object("plane", {{"point", glm::dvec3{0, 0, 0}}, {"normal", glm::dvec3{0, 1, 0}}}, "floor");
  s.add_object("sphere", {{"center", glm::dvec3{-1.5, 1, 1}}, {"radius", 1}}, "glass");
  s.add_object("sphere", {{"center", glm::dvec3{1.8, 1, -0.5}}, {"radius", 1}}, "mirror");
  s.add_object("sphere", {{"center", glm::dvec3{0, 1.3, -3}}, {"radius", 0.8}}, "planet", tilt);
  s.add_object("ring", {{"center", glm::dvec3{0, 1.3, -3}}, {"inner_radius", 1}, {"outer_radius", 1.4}}, "copper",
               tilt);
  s.add_object("box", {{"center", glm::dvec3{-3, 0.6, 2.5}}, {"half_size", glm::dvec3{0.6, 0.6, 0.6}}}, "copper",
               Rotation{.axis = {0, 1, 0}, .degrees = 30});
  s.add_object("torus", {{"center", glm::dvec3{-4, 0.9, -2}}, {"major_radius", 0.6}, {"minor_radius", 0.2}}, "",
               Rotation{.quaternion = glm::dvec4{0.8, 0.6, 0, 0}});
  s.add_object("cylinder", {{"center", glm::dvec3{3, 0, 2.5}}, {"radius", 0.45}, {"height", 1.1}}, "copper");
  s.add_object("cone", {{"center", glm::dvec3{4, 1.6, -1.8}}, {"radius", 0.6}, {"height", 1.6}}, "",
               Rotation{.axis = {1, 0, 0}, .degrees = 180});
  s.add_object("quadric",
               {{"coefficients", {1, 0, 1, 0, 0, 0, 0, -0.2, 0, -0.3}},
                {"center", glm::dvec3{0, 0.5, 3}},
                {"clip_min", Value::Array{std::nullopt, 0.0, std::nullopt}},
                {"clip_max", Value::Array{std::nullopt, 1.5, std::nullopt}}},
               "mirror");
}

void expect_same_pixels(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) differing += std::memcmp(&a.rgb[i], &b.rgb[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u) << "of " << a.rgb.size() << " channel values";
}

TEST_P(ApiScene, BuiltInCodeRendersLikeTheSceneFile) {
  Engine engine;
  LiveScene scene(engine);
  build_in_code(scene);
  Renderer renderer(engine, GetParam());
  const Image from_api = renderer.render(scene);
  const Image from_file = render(load(kSceneJson, textures()));
  expect_same_pixels(from_api, from_file);
  // Not a blank image: the scene is in view.
  float brightest = 0;
  for (float v : from_api.rgb) brightest = std::max(brightest, v);
  EXPECT_GT(brightest, 0.5f);
}

PRISM_INSTANTIATE_BACKEND_TESTS(ApiScene);

// Saving and loading are the same whatever renders the result: the
// reference backend checks them (every backend's rendering of API scenes is
// checked above, and its updates in api_update_test.cpp).
class ApiFiles : public BackendTest {};

TEST_P(ApiFiles, SavedSceneLoadsAndRendersTheSame) {
  Engine engine;
  LiveScene scene(engine);
  build_in_code(scene);
  const fs::path file = fresh_temp_dir() / "saved.json";
  scene.save(file);
  LiveScene loaded = LiveScene::load(engine, file);
  Renderer renderer(engine, GetParam());
  expect_same_pixels(renderer.render(loaded), render(load(kSceneJson, textures())));
}

TEST_P(ApiFiles, LoadedSceneEditedRendersLikeTheEditedFile) {
  const fs::path dir = fresh_temp_dir();
  write_file(dir / "scene.json", kSceneJson);
  for (const auto& entry : fs::directory_iterator(textures())) fs::copy(entry.path(), dir / entry.path().filename());
  Engine engine;
  LiveScene scene = LiveScene::load(engine, dir / "scene.json");
  Renderer renderer(engine, GetParam());
  renderer.render(scene);
  const ObjectId mirror = scene.object_at(2);  // the mirror sphere
  scene.move_object(mirror, {1.5, 1.2, 0});
  scene.set_material("glass", {.ior = 1.33});
  const Image edited = renderer.render(scene);

  std::string text = kSceneJson;
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace(R"("center": [1.8, 1, -0.5])", R"("center": [1.5, 1.2, 0])");
  replace(R"("glass": { "ior": 1.5, "absorb": [0.2, 0.05, 0.02] })", R"("glass": { "ior": 1.33 })");
  expect_same_pixels(edited, render(load(text, textures())));
}

INSTANTIATE_TEST_SUITE_P(Reference, ApiFiles, testing::Values(std::string("reference")));

TEST(ApiRenderer, RenderIntoChecksTheBufferSize) {
  Engine engine;
  LiveScene scene(engine);
  scene.set_image({.width = 8, .height = 4, .spp = 1, .max_depth = 1});
  Renderer renderer(engine, "reference");
  std::vector<float> wrong(8 * 4 * 3 - 1);
  try {
    renderer.render_into(scene, wrong);
    FAIL() << "a short buffer was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "render_into(): the buffer holds 95 floats; a 8x4 image needs 96");
  }
  std::vector<float> right(8 * 4 * 3, -1.0f);
  scene.set_background({0.25, 0.5, 0.75});
  renderer.render_into(scene, right);
  EXPECT_EQ(right[0], 0.25f);
  EXPECT_EQ(right[1], 0.5f);
  EXPECT_EQ(right[95], 0.75f);
}

TEST(ApiRenderer, RenderToFileWritesThePicture) {
  Engine engine;
  LiveScene scene(engine);
  scene.set_image({.width = 8, .height = 4, .spp = 1, .max_depth = 1});
  scene.set_background({1, 1, 1});
  Renderer renderer(engine, "reference");
  const fs::path file = fresh_temp_dir() / "white.png";
  renderer.render_to_file(scene, file);
  EXPECT_TRUE(fs::is_regular_file(file));
  EXPECT_GT(fs::file_size(file), 0u);
  EXPECT_THROW(renderer.render_to_file(scene, file.parent_path() / "white.bmp"), InputError);
}

TEST(ApiRenderer, UnknownBackendIsAnInputError) {
  Engine engine;
  EXPECT_THROW(Renderer(engine, "no-such-backend"), InputError);
}

TEST(ApiEngine, FindsTheBuiltPluginsWithoutAnyPath) {
  Engine engine;
  const auto types = engine.primitive_types();
  for (const char* type : {"sphere", "plane", "box", "torus", "ring", "quadric", "cylinder", "cone"})
    EXPECT_NE(std::ranges::find(types, type), types.end()) << type;
  const auto backends = engine.backends();
  EXPECT_NE(std::ranges::find(backends, "reference"), backends.end());
}

}  // namespace
}  // namespace prism::test
