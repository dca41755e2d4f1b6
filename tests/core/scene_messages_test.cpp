// What the loader says about a scene beyond accepting or refusing it: the
// key or name a misspelt one stands for, at every level of the file, and
// the warnings about a scene that loads but will not look as meant. Every
// message is given whole.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"

namespace prism {
namespace {

constexpr const char* kCamera = R"("camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]})";
constexpr const char* kLight = R"("lights": [{"type": "point", "position": [0, 5, 5]}])";

// `members` after "prism": 1; a camera and a light unless `members` has its own.
std::string scene_text(const std::string& members) {
  std::string text = R"({"prism": 1)";
  if (members.find(R"("camera")") == std::string::npos) text += std::string(", ") + kCamera;
  if (members.find(R"("lights")") == std::string::npos) text += std::string(", ") + kLight;
  return text + (members.empty() ? "" : ", " + members) + "}";
}

// The message loading the scene throws ("" when it loads).
std::string load_error(const std::string& members) {
  Registry registry;
  try {
    load_scene_from_string(scene_text(members), ".", registry, "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> warnings_of(const std::string& members) {
  Registry registry;
  return load_scene_from_string(scene_text(members), ".", registry, "t.json").warnings;
}

struct MessageCase {
  const char* name;
  const char* members;
  const char* message;
};

const MessageCase kMisspellings[] = {
    {"TopLevel", R"("materails": {})", "t.json: materails: unknown key (did you mean 'materials'?)"},
    {"TopLevelObjects", R"("objets": [])", "t.json: objets: unknown key (did you mean 'objects'?)"},
    {"Camera", R"("camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 40})",
     "t.json: camera.fov: unknown key (did you mean 'fov_y'?)"},
    {"CameraRequiredKey", R"("camera": {"positon": [0, 0, 5], "look_at": [0, 0, 0]})",
     "t.json: camera.positon: unknown key (did you mean 'position'?)"},
    {"Image", R"("image": {"widht": 100})", "t.json: image.widht: unknown key (did you mean 'width'?)"},
    {"Material", R"("materials": {"red": {"colr": [1, 0, 0]}})",
     "t.json: materials.red.colr: unknown key (did you mean 'color'?)"},
    {"Light", R"("lights": [{"type": "point", "position": [0, 5, 5], "intesity": 2}])",
     "t.json: lights[0].intesity: unknown key (did you mean 'intensity'?)"},
    {"Texture", R"("textures": {"wood": {"path": "wood.png", "srbg": false}})",
     "t.json: textures.wood.srbg: unknown key (did you mean 'srgb'?)"},
    {"ObjectRequiredField", R"("objects": [{"type": "sphere", "raduis": 1}])",
     "t.json: objects[0].raduis: unknown key (did you mean 'radius'?)"},
    {"ObjectOptionalField", R"("objects": [{"type": "sphere", "radius": 1, "centre": [0, 0, 0]}])",
     "t.json: objects[0].centre: unknown key (did you mean 'center'?)"},
    {"Background", R"("background": {"colour": [0, 0, 0]})",
     "t.json: background.colour: unknown key (did you mean 'color'?)"},
    // Nothing near: the keys there are, as before.
    {"NothingNear", R"("image": {"zzz": 1})",
     "t.json: image.zzz: unknown key (expected one of: width, height, spp, max_depth)"},
    // A key already given is no suggestion for another one.
    {"NotAKeyAlreadyThere", R"("image": {"width": 10, "widht": 100})",
     "t.json: image.widht: unknown key (expected one of: width, height, spp, max_depth)"},
    // One letter for a two-letter key is no typo of it.
    {"ShortKeysAreNotGuessed", R"("camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "x": [0, 1, 0]})",
     "t.json: camera.x: unknown key (expected one of: position, fov_y, rotation, look_at, up)"},
    // Unknown names list what the scene defines, or suggest the near one.
    {"MaterialListed",
     R"("materials": {"red": {}, "blue": {}}, "objects": [{"type": "sphere", "material": "gold"}])",
     "t.json: objects[0].material: unknown material 'gold' (materials: 'blue', 'red')"},
    {"MaterialGuessed", R"("materials": {"red": {}, "blue": {}}, "objects": [{"type": "sphere", "material": "rde"}])",
     "t.json: objects[0].material: unknown material 'rde' (did you mean 'red'?)"},
    {"NoMaterials", R"("objects": [{"type": "sphere", "material": "gold"}])",
     "t.json: objects[0].material: unknown material 'gold' (no materials are defined)"},
    {"NoTextures", R"("materials": {"m": {"texture": "wood"}})",
     "t.json: materials.m.texture: unknown texture 'wood' (no textures are defined)"},
};

class LoaderMessages : public testing::TestWithParam<MessageCase> {};

TEST_P(LoaderMessages, NamesWhatWasMeant) { EXPECT_EQ(load_error(GetParam().members), GetParam().message); }

INSTANTIATE_TEST_SUITE_P(Cases, LoaderMessages, testing::ValuesIn(kMisspellings),
                         [](const testing::TestParamInfo<MessageCase>& info) { return info.param.name; });

TEST(LoaderMessages, ALongListOfMaterialsIsCutAfterTen) {
  std::string materials = R"("materials": {)";
  for (char c = 'a'; c <= 'l'; ++c) materials += std::string(c == 'a' ? "" : ", ") + "\"" + c + c + c + "\": {}";
  EXPECT_EQ(load_error(materials + R"(}, "objects": [{"type": "sphere", "material": "zzzzzz"}])"),
            "t.json: objects[0].material: unknown material 'zzzzzz' (materials: 'aaa', 'bbb', 'ccc', 'ddd', 'eee', "
            "'fff', 'ggg', 'hhh', 'iii', 'jjj', ... (12 in all))");
}

TEST(SceneWarnings, NoneForAnOrdinaryScene) {
  EXPECT_EQ(warnings_of(R"("materials": {"red": {"color": [0.8, 0.1, 0.1]}},
                           "objects": [{"type": "sphere", "radius": 1, "material": "red"}])"),
            std::vector<std::string>{});
}

TEST(SceneWarnings, NoLightAndNoAmbient) {
  EXPECT_EQ(warnings_of(R"("lights": [], "objects": [{"type": "sphere", "radius": 1}])"),
            std::vector<std::string>{"t.json: lights: the scene has no lights and no ambient, so objects other than "
                                     "mirrors and glass render black"});
  // Ambient light alone lights it; a scene with no objects has nothing to light.
  EXPECT_EQ(warnings_of(R"("lights": [], "ambient": [0.1, 0.1, 0.1], "objects": [{"type": "sphere", "radius": 1}])"),
            std::vector<std::string>{});
  EXPECT_EQ(warnings_of(R"("lights": [])"), std::vector<std::string>{});
  // A mirror and a glass ball show their surroundings (a sky box) without light.
  EXPECT_EQ(warnings_of(R"("lights": [], "materials": {"mirror": {"reflect": 1}, "glass": {"ior": 1.5}},
                           "objects": [{"type": "sphere", "radius": 1, "material": "mirror"},
                                       {"type": "sphere", "radius": 1, "material": "glass"}])"),
            std::vector<std::string>{});
}

TEST(SceneWarnings, ColoursThatLookLike0To255) {
  EXPECT_EQ(warnings_of(R"("materials": {"red": {"color": [255, 0, 0]}, "dim": {"color": [1.5, 0.5, 0]}},
                           "background": {"color": [0, 0, 128]},
                           "lights": [{"type": "point", "position": [0, 5, 5], "color": [255, 255, 200]}])"),
            (std::vector<std::string>{
                "t.json: background.color: [0, 0, 128] looks like 0-255 values; colours run from 0 to 1 "
                "(divide by 255)",
                "t.json: materials.red.color: [255, 0, 0] looks like 0-255 values; colours run from 0 to 1 "
                "(divide by 255)",
                "t.json: lights[0].color: [255, 255, 200] looks like 0-255 values; colours run from 0 to 1 "
                "(divide by 255)"}));
}

// The camera at z = 5 looks down -z. A sphere of radius 1 at z = 8 spans
// z 7..9: all of it at least 2 behind the camera's plane. At z = 5.5 it
// spans 4.5..6.5 and reaches 0.5 in front.
TEST(SceneWarnings, AnObjectEntirelyBehindTheCamera) {
  EXPECT_EQ(warnings_of(R"("objects": [{"type": "sphere", "radius": 1, "center": [0, 0, 5.5]},
                                       {"type": "sphere", "radius": 1, "center": [0, 0, 8]}])"),
            std::vector<std::string>{
                "t.json: objects[1]: entirely behind the camera (it can show only in reflections)"});
}

TEST(SceneWarnings, ManyObjectsBehindTheCameraAreCounted) {
  std::string objects = R"("objects": [)";
  for (int i = 0; i < 7; ++i) objects += std::string(i ? ", " : "") + R"({"type": "sphere", "radius": 1, "center": [0, 0, 9]})";
  const std::vector<std::string> warnings = warnings_of(objects + "]");
  ASSERT_EQ(warnings.size(), 6u);
  EXPECT_EQ(warnings[0], "t.json: objects[0]: entirely behind the camera (it can show only in reflections)");
  EXPECT_EQ(warnings[4], "t.json: objects[4]: entirely behind the camera (it can show only in reflections)");
  EXPECT_EQ(warnings[5], "t.json: objects: 2 more objects entirely behind the camera");
}

TEST(SceneWarnings, WrittenOnePerLine) {
  Scene scene;
  scene.warnings = {"t.json: a", "t.json: b"};
  std::ostringstream out;
  write_warnings(scene, out);
  EXPECT_EQ(out.str(), "prism: warning: t.json: a\nprism: warning: t.json: b\n");
}

}  // namespace
}  // namespace prism
