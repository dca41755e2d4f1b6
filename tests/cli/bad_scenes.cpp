#include "bad_scenes.hpp"

namespace prism::cli_test {

namespace {

// Shorthands: the valid scene with one member replaced.
std::string with_objects(const std::string& objects) {
  SceneText s;
  s.objects = objects;
  return s.text();
}
std::string with_lights(const std::string& lights) {
  SceneText s;
  s.lights = lights;
  return s.text();
}
std::string with_camera(const std::string& camera) {
  SceneText s;
  s.camera = camera;
  return s.text();
}
std::string with_image(const std::string& image) {
  SceneText s;
  s.image = image;
  return s.text();
}
std::string with_prism(const std::string& version) {
  SceneText s;
  s.prism = version;
  return s.text();
}
std::string with_extra(const std::string& extra) {
  SceneText s;
  s.extra = extra;
  return s.text();
}
// A material named `m` used by object 0 (the sphere).
std::string with_material(const std::string& material) {
  SceneText s;
  s.extra = R"("materials": {"m": )" + material + "}";
  s.objects = R"([{"type": "sphere", "radius": 1, "material": "m"}])";
  return s.text();
}

}  // namespace

std::string with_object(const std::string& object) { return with_objects("[" + object + "]"); }

const std::vector<BadScene>& bad_scenes() {
  static const std::vector<BadScene> cases = {
      // ---- not JSON: line and column ----
      // Line 3 is `  "camera": [1,,2]`; the second comma is column 16.
      {"syntax_error", "{\n  \"prism\": 1,\n  \"camera\": [1,,2]\n}\n", {"line 3", "column 16"}},
      {"truncated", "{\n  \"prism\": 1,\n", {"line 3|line 2", "column"}},
      {"empty_file", "", {"line 1", "column"}},
      {"trailing_garbage", SceneText{}.text() + "x\n", {"line 8", "column 1"}},
      {"comment", "// a scene\n" + SceneText{}.text(), {"line 1", "column 1"}},
      // ---- unknown keys: top level and nested, named by path ----
      {"unknown_key_top_level", with_extra(R"("objets": [])"), {"objets", "unknown key"}},
      {"unknown_key_typo_of_required", with_objects(R"([{"type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0]},
                                                        {"type": "sphere", "raduis": 1}])"),
       {"objects[1].raduis", "unknown key"}},
      {"unknown_key_in_object", with_object(R"({"type": "sphere", "radius": 1, "colour": [1, 0, 0]})"),
       {"objects[0].colour", "unknown key"}},
      {"unknown_key_in_camera",
       with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "fov": 60})"), {"camera.fov", "unknown key"}},
      {"unknown_key_in_image", with_image(R"({"width": 8, "height": 6, "samples": 4})"),
       {"image.samples", "unknown key"}},
      {"unknown_key_in_material", with_material(R"({"color": [1, 0, 0], "shine": 3})"),
       {"materials.m.shine", "unknown key"}},
      {"unknown_key_in_light", with_lights(R"([{"type": "point", "position": [0, 5, -5], "intesity": 2}])"),
       {"lights[0].intesity", "unknown key"}},
      {"unknown_key_in_rotation",
       with_object(R"({"type": "sphere", "radius": 1, "rotation": {"axis": [0, 1, 0], "degrees": 30, "angle": 1}})"),
       {"objects[0].rotation.angle", "unknown key"}},
      {"unknown_key_in_background", with_extra(R"("background": {"color": [0, 0, 0], "colour": [1, 1, 1]})"),
       {"background.colour", "unknown key"}},
      {"center_on_plane", with_object(R"({"type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0], "center": [0, 0, 0]})"),
       {"objects[0].center", "unknown key"}},
      {"radius_on_directional_light",
       with_lights(R"([{"type": "directional", "direction": [0, -1, 0], "radius": 0.5}])"),
       {"lights[0].radius", "unknown key"}},
      {"direction_on_point_light", with_lights(R"([{"type": "point", "position": [0, 5, -5], "direction": [0, -1, 0]}])"),
       {"lights[0].direction", "unknown key"}},
      // ---- duplicate keys ----
      {"duplicate_key_top_level", "{\"prism\": 1, \"prism\": 1, \"camera\": {\"position\": [0, 0, -5], \"look_at\": [0, 0, 0]}}",
       {"prism", "duplicate"}},
      {"duplicate_key_nested", with_objects(R"([{"type": "sphere", "radius": 1},
                                                {"type": "sphere", "radius": 1, "radius": 2}])"),
       {"objects[1].radius", "duplicate"}},
      {"duplicate_key_in_materials", with_extra(R"("materials": {"m": {}, "m": {"color": [1, 0, 0]}})"),
       {"materials.m", "duplicate"}},
      // The path of a duplicate deep inside, after arrays that hold arrays.
      {"duplicate_key_deep", with_objects(R"([{"type": "sphere", "radius": 1, "center": [0, 0, 0]},
                                              {"type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0]},
                                              {"type": "sphere", "radius": 1,
                                               "rotation": {"axis": [0, 1, 0], "degrees": 1, "degrees": 2}}])"),
       {"objects[2].rotation.degrees", "duplicate"}},
      // ---- missing required keys ----
      {"missing_prism", with_prism(""), {"prism", "missing"}},
      {"missing_camera", [] { SceneText s; s.camera = ""; return s.text(); }(), {"camera", "missing"}},
      {"missing_camera_position", with_camera(R"({"look_at": [0, 0, 0]})"), {"camera.position", "missing"}},
      {"missing_radius", with_object(R"({"type": "sphere"})"), {"objects[0].radius", "missing"}},
      {"missing_object_type", with_object(R"({"radius": 1})"), {"objects[0].type", "missing"}},
      {"missing_light_position", with_lights(R"([{"type": "point"}])"), {"lights[0].position", "missing"}},
      {"missing_plane_normal", with_object(R"({"type": "plane", "point": [0, -2, 0]})"),
       {"objects[0].normal", "missing"}},
      // ---- wrong types ----
      {"radius_is_a_string", with_object(R"({"type": "sphere", "radius": "1"})"),
       {"objects[0].radius", "must be a number", "string"}},
      {"camera_is_an_array", with_camera("[0, 0, -5]"), {"camera", "must be an object"}},
      {"type_is_a_number", with_object(R"({"type": 5, "radius": 1})"), {"objects[0].type", "must be a string"}},
      {"vector_entry_is_a_bool", with_material(R"({"color": [1, true, 0]})"),
       {"materials.m.color[1]", "must be a number"}},
      {"objects_is_an_object", with_objects(R"({"type": "sphere", "radius": 1})"), {"objects", "array"}},
      {"object_is_a_number", with_objects("[5]"), {"objects[0]", "must be an object"}},
      {"top_level_array", "[" + SceneText{}.text() + "]", {"top level", "must be an object"}},
      {"width_is_a_string", with_image(R"({"width": "8", "height": 6})"), {"image.width", "integer"}},
      // ---- wrong array lengths ----
      {"center_of_2", with_object(R"({"type": "sphere", "radius": 1, "center": [0, 0]})"),
       {"objects[0].center", "3 numbers", "array of 2"}},
      {"camera_position_of_4", with_camera(R"({"position": [0, 0, -5, 1], "look_at": [0, 0, 0]})"),
       {"camera.position", "3 numbers", "array of 4"}},
      {"quaternion_of_3",
       with_object(R"({"type": "sphere", "radius": 1, "rotation": {"quaternion": [1, 0, 0]}})"),
       {"objects[0].rotation.quaternion", "4 numbers"}},
      {"uv_scale_of_3", with_material(R"({"uv_scale": [1, 1, 1]})"), {"materials.m.uv_scale", "2 numbers"}},
      {"color_is_a_number", with_material(R"({"color": 1})"), {"materials.m.color", "3 numbers"}},
      // ---- NaN and Inf in any form ----
      {"nan_literal", with_object(R"({"type": "sphere", "radius": NaN})"), {"line 6|objects[0].radius", "column|NaN"}},
      {"infinity_literal", with_object(R"({"type": "sphere", "radius": Infinity})"),
       {"line 6|objects[0].radius", "column|Infinity"}},
      {"minus_infinity_literal", with_camera(R"({"position": [0, 0, -Infinity], "look_at": [0, 0, 0]})"),
       {"line 3|camera.position[2]"}},
      {"overflowing_number", with_object(R"({"type": "sphere", "radius": 1e999})"),
       {"objects[0].radius|line 6", "1e999|inf|finite"}},
      {"overflowing_negative_number", with_camera(R"({"position": [0, 0, -1e999], "look_at": [0, 0, 0]})"),
       {"camera.position[2]|line 3", "1e999|inf|finite"}},
      // ---- values out of range ----
      {"negative_radius",
       with_objects(R"([{"type": "sphere", "radius": 1}, {"type": "sphere", "radius": 1}, {"type": "sphere", "radius": 1},
                        {"type": "sphere", "radius": -1}])"),
       {"objects[3].radius: must be > 0", "got -1"}},
      {"zero_radius", with_object(R"({"type": "sphere", "radius": 0})"), {"objects[0].radius: must be > 0", "got 0"}},
      {"zero_light_direction", with_lights(R"([{"type": "directional", "direction": [0, 0, 0]}])"),
       {"lights[0].direction", "zero"}},
      {"zero_plane_normal", with_object(R"({"type": "plane", "point": [0, -2, 0], "normal": [0, 0, 0]})"),
       {"objects[0].normal", "zero"}},
      {"zero_plane_uv_scale",
       with_object(R"({"type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0], "uv_scale": 0})"),
       {"objects[0].uv_scale", "got 0"}},
      {"zero_rotation_axis",
       with_object(R"({"type": "sphere", "radius": 1, "rotation": {"axis": [0, 0, 0], "degrees": 30}})"),
       {"objects[0].rotation.axis", "zero"}},
      {"zero_quaternion",
       with_object(R"({"type": "sphere", "radius": 1, "rotation": {"quaternion": [0, 0, 0, 0]}})"),
       {"objects[0].rotation.quaternion", "zero"}},
      {"negative_light_intensity", with_lights(R"([{"type": "point", "position": [0, 5, -5], "intensity": -1}])"),
       {"lights[0].intensity", "got -1"}},
      {"negative_light_radius", with_lights(R"([{"type": "point", "position": [0, 5, -5], "radius": -0.5}])"),
       {"lights[0].radius", "got -0.5"}},
      {"negative_color", with_material(R"({"color": [0.5, -0.1, 0.5]})"), {"materials.m.color[1]", "got -0.1"}},
      {"reflect_above_1", with_material(R"({"reflect": 1.5})"), {"materials.m.reflect", "got 1.5"}},
      {"shininess_below_1", with_material(R"({"shininess": 0.5})"), {"materials.m.shininess", "got 0.5"}},
      {"negative_ambient", with_extra(R"("ambient": [0, 0, -1])"), {"ambient[2]", "got -1"}},
      {"shadow_ambient_above_1", with_extra(R"("shadow_ambient": [1.5, 0, 0])"), {"shadow_ambient[0]", "got 1.5"}},
      {"negative_background", with_extra(R"("background": {"color": [-1, 0, 0]})"),
       {"background.color[0]", "got -1"}},
      {"fov_180", with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y": 180})"),
       {"camera.fov_y", "got 180"}},
      {"fov_0", with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y": 0})"), {"camera.fov_y", "got 0"}},
      // ---- unknown names ----
      {"unknown_material", with_object(R"({"type": "sphere", "radius": 1, "material": "gold"})"),
       {"objects[0].material", "unknown material", "gold"}},
      // A NUL cut the message short ("unknown material 're"): control bytes are escaped.
      {"nul_in_material_name", with_object(R"({"type": "sphere", "radius": 1, "material": "re\u0000d"})"),
       {"objects[0].material", "unknown material 're\\x00d'"}},
      {"unknown_texture", with_material(R"({"texture": "wood"})"), {"materials.m.texture", "unknown texture", "wood"}},
      {"unknown_cubemap_texture",
       with_extra(R"("background": {"cubemap": ["a", "b", "c", "d", "e", "f"]})"),
       {"background.cubemap[0]", "unknown texture", "'a'"}},
      {"unknown_light_type", with_lights(R"([{"type": "spot", "position": [0, 5, -5]}])"),
       {"lights[0].type", "unknown light type", "spot"}},
      {"unknown_object_type", with_object(R"({"type": "capsule", "radius": 1})"),
       {"objects[0].type", "capsule", "sphere"}},
      // ---- format version: exactly the integer 1 ----
      {"version_2", with_prism("2"), {"prism", "version", "2"}},
      {"version_0", with_prism("0"), {"prism", "version", "0"}},
      {"version_1_0", with_prism("1.0"), {"prism", "integer"}},
      {"version_string", with_prism("\"1\""), {"prism", "string|integer"}},
      // ---- image settings: integers in range ----
      {"width_0", with_image(R"({"width": 0, "height": 6})"), {"image.width", "got 0"}},
      {"width_16385", with_image(R"({"width": 16385, "height": 6})"), {"image.width", "got 16385"}},
      {"height_16385", with_image(R"({"width": 8, "height": 16385})"), {"image.height", "got 16385"}},
      {"width_1_5", with_image(R"({"width": 1.5, "height": 6})"), {"image.width", "integer", "1.5"}},
      {"height_8_0", with_image(R"({"width": 8, "height": 8.0})"), {"image.height", "integer", "8.0"}},
      {"negative_height", with_image(R"({"width": 8, "height": -6})"), {"image.height", "got -6"}},
      {"huge_width", with_image(R"({"width": 18446744073709551616, "height": 6})"), {"image.width"}},
      {"spp_0", with_image(R"({"width": 8, "height": 6, "spp": 0})"), {"image.spp", "got 0"}},
      {"spp_4097", with_image(R"({"width": 8, "height": 6, "spp": 4097})"), {"image.spp", "got 4097"}},
      {"max_depth_65", with_image(R"({"width": 8, "height": 6, "max_depth": 65})"), {"image.max_depth", "got 65"}},
      {"max_depth_0", with_image(R"({"width": 8, "height": 6, "max_depth": 0})"), {"image.max_depth", "got 0"}},
      // ---- lengths and coordinates: magnitude <= 1e7 ----
      {"camera_position_too_far", with_camera(R"({"position": [0, 0, -2e7], "look_at": [0, 0, 0]})"),
       {"camera.position[2]", "-2e+07|-20000000"}},
      {"look_at_too_far", with_camera(R"({"position": [0, 0, -5], "look_at": [1e8, 0, 0]})"),
       {"camera.look_at[0]", "1e+08|100000000"}},
      {"center_too_far", with_object(R"({"type": "sphere", "radius": 1, "center": [10000001, 0, 0]})"),
       {"objects[0].center[0]", "10000001"}},
      {"radius_too_large", with_object(R"({"type": "sphere", "radius": 2e7})"),
       {"objects[0].radius", "2e+07|20000000"}},
      {"light_position_too_far", with_lights(R"([{"type": "point", "position": [0, -3e7, 0]}])"),
       {"lights[0].position[1]", "-3e+07|-30000000"}},
      {"light_radius_too_large", with_lights(R"([{"type": "point", "position": [0, 5, -5], "radius": 1.5e7}])"),
       {"lights[0].radius", "1.5e+07|15000000"}},
      {"plane_point_too_far", with_object(R"({"type": "plane", "point": [0, -2e7, 0], "normal": [0, 1, 0]})"),
       {"objects[0].point[1]", "-2e+07|-20000000"}},
      {"torus_major_radius_too_large", with_object(R"({"type": "torus", "major_radius": 2e7, "minor_radius": 1})"),
       {"objects[0].major_radius", "2e+07|20000000"}},
      // ---- materials ----
      {"ior_in_0_1", with_material(R"({"ior": 0.5})"), {"materials.m.ior", "0.5"}},
      {"negative_ior", with_material(R"({"ior": -1.5})"), {"materials.m.ior", "-1.5"}},
      // eta² overflowed into NaN pixels on every backend; the cap is 100.
      {"huge_ior", with_material(R"({"ior": 1e100})"), {"materials.m.ior", "[1, 100]", "1e+100"}},
      {"ior_just_over_cap", with_material(R"({"ior": 100.5})"), {"materials.m.ior", "100.5"}},
      {"absorb_on_opaque", with_material(R"({"absorb": [0.1, 0, 0]})"), {"materials.m.absorb", "opaque|ior"}},
      // ---- camera ----
      {"up_parallel_to_view", with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 0, 1]})"),
       {"camera.up", "parallel"}},
      {"up_antiparallel_to_view", with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 0, -3]})"),
       {"camera.up", "parallel"}},
      {"up_zero", with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 0, 0]})"),
       {"camera.up", "zero"}},
      {"look_at_is_position", with_camera(R"({"position": [1, 2, 3], "look_at": [1, 2, 3]})"),
       {"camera.look_at", "position"}},
      {"camera_rotation_and_look_at",
       with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "rotation": {"axis": [0, 1, 0], "degrees": 180}})"),
       {"camera.look_at|camera.rotation", "rotation"}},
      {"camera_rotation_and_up",
       with_camera(R"({"position": [0, 0, -5], "up": [0, 1, 0], "rotation": {"axis": [0, 1, 0], "degrees": 180}})"),
       {"camera.up|camera.rotation", "rotation"}},
      {"camera_without_look_at_or_rotation", with_camera(R"({"position": [0, 0, -5]})"),
       {"camera.look_at|camera.rotation", "missing|required"}},
      // ---- rotations ----
      {"rotation_axis_and_quaternion",
       with_object(R"({"type": "sphere", "radius": 1,
                       "rotation": {"axis": [0, 1, 0], "degrees": 30, "quaternion": [1, 0, 0, 0]}})"),
       {"objects[0].rotation", "quaternion", "axis"}},
      {"rotation_axis_without_degrees",
       with_object(R"({"type": "sphere", "radius": 1, "rotation": {"axis": [0, 1, 0]}})"),
       {"objects[0].rotation.degrees", "missing"}},
      // ---- background ----
      {"background_color_and_cubemap",
       with_extra(R"("background": {"color": [0, 0, 0], "cubemap": ["a", "b", "c", "d", "e", "f"]})"),
       {"background", "color", "cubemap"}},
      {"cubemap_of_5", with_extra(R"("background": {"cubemap": ["a", "b", "c", "d", "e"]})"),
       {"background.cubemap", "6"}},
      // ---- cross-field rules of the primitives ----
      {"torus_minor_equals_major", with_object(R"({"type": "torus", "major_radius": 1, "minor_radius": 1})"),
       {"objects[0]", "minor_radius"}},
      {"torus_minor_above_major", with_object(R"({"type": "torus", "major_radius": 1, "minor_radius": 2})"),
       {"objects[0]", "minor_radius"}},
      {"ring_inner_above_outer", with_object(R"({"type": "ring", "inner_radius": 2, "outer_radius": 1})"),
       {"objects[0]", "inner_radius|outer_radius"}},
      {"ring_inner_equals_outer", with_object(R"({"type": "ring", "inner_radius": 1, "outer_radius": 1})"),
       {"objects[0]", "inner_radius|outer_radius"}},
      {"ring_negative_inner", with_object(R"({"type": "ring", "inner_radius": -1, "outer_radius": 1})"),
       {"objects[0].inner_radius", "got -1"}},
      {"quadric_all_zero_a_to_i",
       with_object(R"({"type": "quadric", "coefficients": [0, 0, 0, 0, 0, 0, 0, 0, 0, 1]})"),
       {"objects[0]", "coefficients"}},
      {"quadric_of_9", with_object(R"({"type": "quadric", "coefficients": [1, 1, 1, 0, 0, 0, 0, 0, -1]})"),
       {"objects[0].coefficients", "10"}},
      {"quadric_clip_min_above_max",
       with_object(R"({"type": "quadric", "coefficients": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1],
                       "clip_min": [null, 0.5, null], "clip_max": [null, -0.5, null]})"),
       {"objects[0]", "clip_min|clip_max"}},
      // The 1e7 bound on clip entries is the core's (PRISM_FIELD_LENGTH), not the plugin's.
      {"quadric_clip_beyond_1e7",
       with_object(R"({"type": "quadric", "coefficients": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1],
                       "clip_min": [-2e7, null, null]})"),
       {"objects[0].clip_min[0]", "got -20000000"}},
      {"box_zero_half_size", with_object(R"({"type": "box", "half_size": [1, 0, 1]})"),
       {"objects[0].half_size[1]", "got 0"}},
      {"cylinder_negative_height", with_object(R"({"type": "cylinder", "radius": 1, "height": -1})"),
       {"objects[0].height", "got -1"}},
  };
  return cases;
}

}  // namespace prism::cli_test
