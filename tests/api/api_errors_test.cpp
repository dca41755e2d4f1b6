// Invalid values through the API raise the scene loader's errors: the same
// message, with the API call standing where the file has its JSON path. Each
// case gives both literally, and an edit that fails changes nothing.
#include <functional>

#include "prism/api.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace prism::test {
namespace {

// The message an edit of a fresh scene throws ("" when it does not throw).
std::string api_error(const std::function<void(LiveScene&)>& edit) {
  Engine engine;
  LiveScene scene(engine);
  scene.set_material("m", {});
  try {
    edit(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The message loading a scene file with `parts` (JSON members) throws. A
// camera and the material "m" are added unless `parts` has its own.
std::string file_error(const std::string& parts) {
  Registry registry;
  std::string text = R"({"prism": 1, )" + parts;
  if (parts.find(R"("camera")") == std::string::npos)
    text += R"(, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]})";
  if (parts.find(R"("materials")") == std::string::npos) text += R"(, "materials": {"m": {}})";
  text += "}";
  try {
    load_scene_from_string(text, ".", registry, "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct ErrorCase {
  const char* name;
  std::function<void(LiveScene&)> edit;
  const char* api_message;
  const char* file_parts;
  const char* file_message;
};

const ErrorCase kCases[] = {
    {"NegativeRadius", [](LiveScene& s) { s.add_object("sphere", {{"radius", -1}}); },
     "add_object(\"sphere\").radius: must be > 0, got -1",
     R"("objects": [{"type": "sphere", "radius": -1}])", "t.json: objects[0].radius: must be > 0, got -1"},
    {"GenericObjectField", [](LiveScene& s) { s.add_object("torus", {{"major_radius", 1}, {"minor_radius", 0}}); },
     "add_object(\"torus\").minor_radius: must be > 0, got 0",
     R"("objects": [{"type": "torus", "major_radius": 1, "minor_radius": 0}])",
     "t.json: objects[0].minor_radius: must be > 0, got 0"},
    {"MisspelledField", [](LiveScene& s) { s.add_object("sphere", {{"raduis", 1}}); },
     "add_object(\"sphere\").raduis: unknown key (did you mean 'radius'?)",
     R"("objects": [{"type": "sphere", "raduis": 1}])",
     "t.json: objects[0].raduis: unknown key (did you mean 'radius'?)"},
    {"UnknownMaterial", [](LiveScene& s) { s.add_object("sphere", {{"radius", 1}}, "gold"); },
     "add_object(\"sphere\").material: unknown material 'gold' (materials: 'm')",
     R"("objects": [{"type": "sphere", "material": "gold"}])",
     "t.json: objects[0].material: unknown material 'gold' (materials: 'm')"},
    {"PluginValidation",
     [](LiveScene& s) {
       s.add_object("quadric", {{"coefficients", {1, 1, 1, 0, 0, 0, 0, 0, 0, -1}},
                                {"clip_min", {0, 0, 0}}, {"clip_max", {1, -1, 1}}});
     },
     "add_object(\"quadric\").clip_max: entry 1 must be >= clip_min (0), got -1",
     R"("objects": [{"type": "quadric", "coefficients": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1],
                     "clip_min": [0, 0, 0], "clip_max": [1, -1, 1]}])",
     "t.json: objects[0].clip_max: entry 1 must be >= clip_min (0), got -1"},
    {"CoordinateOutOfRange", [](LiveScene& s) { s.add_object("sphere", {{"center", {2e7, 0, 0}}, {"radius", 1}}); },
     "add_object(\"sphere\").center[0]: must be in [-10000000, 10000000], got 20000000",
     R"("objects": [{"type": "sphere", "center": [2e7, 0, 0]}])",
     "t.json: objects[0].center[0]: must be in [-10000000, 10000000], got 20000000"},
    {"OpaqueIor", [](LiveScene& s) { s.set_material("glass", {.ior = 0.5}); },
     "set_material(\"glass\").ior: must be 0 (opaque) or in [1, 100], got 0.5",
     R"("materials": {"m": {}, "glass": {"ior": 0.5}})", "t.json: materials.glass.ior: must be 0 (opaque) or in [1, 100], got 0.5"},
    {"AbsorbOnOpaque", [](LiveScene& s) { s.set_material("m", {.absorb = {0.1, 0, 0}}); },
     "set_material(\"m\").absorb: must be [0, 0, 0] on an opaque material (ior 0)",
     R"("materials": {"m": {"absorb": [0.1, 0, 0]}})",
     "t.json: materials.m.absorb: must be [0, 0, 0] on an opaque material (ior 0)"},
    {"UnknownTexture", [](LiveScene& s) { s.set_material("m", {.texture = "wood"}); },
     "set_material(\"m\").texture: unknown texture 'wood' (no textures are defined)",
     R"("materials": {"m": {"texture": "wood"}})",
     "t.json: materials.m.texture: unknown texture 'wood' (no textures are defined)"},
    {"NegativeIntensity", [](LiveScene& s) { s.add_light(PointLight{.intensity = -1}); },
     "add_light().intensity: must be >= 0, got -1",
     R"("lights": [{"type": "point", "position": [0, 0, 0], "intensity": -1}])",
     "t.json: lights[0].intensity: must be >= 0, got -1"},
    {"ZeroDirection", [](LiveScene& s) { s.add_light(DirectionalLight{.direction = {0, 0, 0}}); },
     "add_light().direction: must be non-zero, got [0, 0, 0]",
     R"("lights": [{"type": "directional", "direction": [0, 0, 0]}])",
     "t.json: lights[0].direction: must be non-zero, got [0, 0, 0]"},
    {"CameraLooksAtItself", [](LiveScene& s) { s.set_camera({.position = {1, 2, 3}, .look_at = {1, 2, 3}}); },
     "set_camera().look_at: must differ from camera.position",
     R"("image": {}, "camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]})",
     "t.json: camera.look_at: must differ from camera.position"},
    {"ImageWidth", [](LiveScene& s) { s.set_image({.width = 0}); },
     "set_image().width: must be in [1, 16384], got 0",
     R"("image": {"width": 0})", "t.json: image.width: must be in [1, 16384], got 0"},
    {"Ambient", [](LiveScene& s) { s.set_ambient({-1, 0, 0}); },
     "set_ambient().ambient[0]: must be >= 0, got -1",
     R"("ambient": [-1, 0, 0])", "t.json: ambient[0]: must be >= 0, got -1"},
    {"CubemapOfUnknownTextures", [](LiveScene& s) { s.set_background_cubemap({"a", "b", "c", "d", "e", "f"}); },
     "set_background_cubemap().cubemap[0]: unknown texture 'a' (no textures are defined)",
     R"("background": {"cubemap": ["a", "b", "c", "d", "e", "f"]})",
     "t.json: background.cubemap[0]: unknown texture 'a' (no textures are defined)"},
};

class ApiErrors : public testing::TestWithParam<ErrorCase> {};

TEST_P(ApiErrors, SameMessageAsTheSceneFile) {
  const ErrorCase& c = GetParam();
  EXPECT_EQ(api_error(c.edit), c.api_message);
  EXPECT_EQ(file_error(c.file_parts), c.file_message);
}

INSTANTIATE_TEST_SUITE_P(Cases, ApiErrors, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<ErrorCase>& info) { return info.param.name; });

TEST(ApiErrorsMore, UnknownTypeNamesTheTypeAsTheLoaderDoes) {
  const std::string api = api_error([](LiveScene& s) { s.add_object("teapot", {}); });
  const std::string file = file_error(R"("objects": [{"type": "teapot"}])");
  const std::string api_path = "add_object(\"teapot\").type: ";
  const std::string file_path = "t.json: objects[0].type: ";
  ASSERT_EQ(api.rfind(api_path, 0), 0u) << api;
  ASSERT_EQ(file.rfind(file_path, 0), 0u) << file;
  EXPECT_EQ(api.substr(api_path.size()), file.substr(file_path.size()));
  EXPECT_NE(api.find("teapot"), std::string::npos);
}

TEST(ApiErrorsMore, TextureThatIsNotThereNamesTheFile) {
  const std::string missing = (fresh_temp_dir() / "missing.png").string();
  const std::string api = api_error([&](LiveScene& s) { s.add_texture("t", missing); });
  const std::string file = file_error(R"("textures": {"t": ")" + missing + R"("})");
  ASSERT_EQ(api.rfind("add_texture(\"t\"): ", 0), 0u) << api;
  ASSERT_EQ(file.rfind("t.json: textures.t: ", 0), 0u) << file;
  EXPECT_EQ(api.substr(std::string("add_texture(\"t\"): ").size()),
            file.substr(std::string("t.json: textures.t: ").size()));
  EXPECT_NE(api.find("missing.png"), std::string::npos);
}

TEST(ApiErrorsMore, ObjectTypeCannotChange) {
  EXPECT_EQ(api_error([](LiveScene& s) {
              s.update_object(s.add_object("sphere", {{"radius", 1}}), {{"type", "box"}});
            }),
            "update_object(#1).type: an object's type cannot change (remove it and add another)");
}

TEST(ApiErrorsMore, RemovedIdsAreRefused) {
  EXPECT_EQ(api_error([](LiveScene& s) {
              const ObjectId id = s.add_object("sphere", {{"radius", 1}});
              s.remove_object(id);
              s.move_object(id, {1, 0, 0});
            }),
            "move_object(#1): no object has this id (removed, or from another scene)");
  EXPECT_EQ(api_error([](LiveScene& s) {
              const LightId id = s.add_light(PointLight{});
              s.remove_light(id);
              s.update_light(id, PointLight{});
            }),
            "update_light(#1): no light has this id (removed, or from another scene)");
}

TEST(ApiErrorsMore, AFailedEditChangesNothing) {
  Engine engine;
  LiveScene scene(engine);
  scene.set_image({.width = 16, .height = 8, .spp = 1, .max_depth = 2});
  const ObjectId ball = scene.add_object("sphere", {{"radius", 1}});
  scene.add_light(PointLight{.position = {0, 4, 4}});
  Renderer renderer(engine, "reference");
  renderer.render(scene);
  const std::string before = scene.to_json();
  EXPECT_THROW(scene.move_object(ball, {0, 0, 1e9}), InputError);
  EXPECT_THROW(scene.update_object(ball, {{"radius", -2}}), InputError);
  EXPECT_THROW(scene.set_material("m", {.shininess = 0}), InputError);
  EXPECT_THROW(scene.add_light(PointLight{.radius = -1}), InputError);
  EXPECT_EQ(scene.to_json(), before);
  EXPECT_EQ(scene.object_count(), 1u);
  EXPECT_EQ(scene.scene().objects[0].center, glm::dvec3(0, 0, 0));
  renderer.render(scene);
  EXPECT_EQ(renderer.counters().updates, 0u) << "nothing changed, so nothing was sent to the backend";
}

}  // namespace
}  // namespace prism::test
