// prism.Scene: a LiveScene edited from Python, and the value types its calls
// take (Camera, Material, PointLight, DirectionalLight, Rotation, ImageSettings).
#include <cmath>

#include "bindings.hpp"

namespace prism::python {

namespace {

// A field's value for add_object / update_object: a number, a bool, a
// string, or a sequence of numbers (None where the type allows nulls).
Value value_of(py::handle item, const std::string& key) {
  if (PyBool_Check(item.ptr())) return item.cast<bool>();
  if (PyUnicode_Check(item.ptr())) return item.cast<std::string>();
  if (PyNumber_Check(item.ptr()) && !py::hasattr(item, "__len__")) return item.cast<double>();
  if (py::hasattr(item, "tolist")) return value_of(item.attr("tolist")(), key);  // NumPy
  if (PySequence_Check(item.ptr())) {
    Value::Array array;
    for (const py::handle e : py::reinterpret_borrow<py::sequence>(item))
      array.push_back(e.is_none() ? std::nullopt : std::optional<double>(e.cast<double>()));
    return array;
  }
  throw py::type_error(key + ": a " + py::type::of(item).attr("__name__").cast<std::string>() +
                       " cannot be a field's value (number, bool, str or a sequence of numbers)");
}

Params params_of(const py::kwargs& fields) {
  Params params;
  for (const auto& [key, item] : fields) params.emplace_back(key.cast<std::string>(), value_of(item, key.cast<std::string>()));
  return params;
}

// An edit: refused during a render, InputError raised as SceneError.
template <class Edit>
auto edit(SceneHandle& s, Edit&& change) {
  s.check_editable();
  return scene_call("", [&] { return change(s.live); });
}

void bind_values(py::module_& m) {
  py::class_<Rotation>(m, "Rotation", "`degrees` about `axis` (right-hand rule), or a quaternion (w, x, y, z).")
      .def(py::init([](glm::dvec3 axis, double degrees, std::optional<std::vector<double>> quaternion) {
             Rotation r{axis, degrees, std::nullopt};
             if (quaternion) {
               if (quaternion->size() != 4) throw py::value_error("quaternion: needs 4 numbers (w, x, y, z)");
               r.quaternion = glm::dvec4((*quaternion)[0], (*quaternion)[1], (*quaternion)[2], (*quaternion)[3]);
             }
             return r;
           }),
           py::arg("axis") = glm::dvec3(0, 1, 0), py::arg("degrees") = 0.0, py::arg("quaternion") = py::none())
      .def_readwrite("axis", &Rotation::axis)
      .def_readwrite("degrees", &Rotation::degrees);

  py::class_<CameraDesc>(m, "Camera", "A pinhole camera; fov_y is the vertical field of view in degrees.")
      .def(py::init([](glm::dvec3 position, glm::dvec3 look_at, glm::dvec3 up, double fov_y) {
             return CameraDesc{position, look_at, up, fov_y};
           }),
           py::arg("position") = CameraDesc{}.position, py::arg("look_at") = CameraDesc{}.look_at,
           py::arg("up") = CameraDesc{}.up, py::arg("fov_y") = CameraDesc{}.fov_y)
      .def_readwrite("position", &CameraDesc::position)
      .def_readwrite("look_at", &CameraDesc::look_at)
      .def_readwrite("up", &CameraDesc::up)
      .def_readwrite("fov_y", &CameraDesc::fov_y);

  const MaterialDesc m0;
  py::class_<MaterialDesc>(m, "Material", "A material; the defaults are the scene format's. texture: a texture's name.")
      .def(py::init([](glm::dvec3 color, std::string texture, glm::dvec2 uv_scale, glm::dvec2 uv_offset,
                       double diffuse, double specular, double shininess, double reflect, double ior,
                       glm::dvec3 absorb) {
             return MaterialDesc{color, texture, uv_scale, uv_offset, diffuse, specular, shininess, reflect, ior, absorb};
           }),
           py::arg("color") = m0.color, py::arg("texture") = m0.texture, py::arg("uv_scale") = m0.uv_scale,
           py::arg("uv_offset") = m0.uv_offset, py::arg("diffuse") = m0.diffuse, py::arg("specular") = m0.specular,
           py::arg("shininess") = m0.shininess, py::arg("reflect") = m0.reflect, py::arg("ior") = m0.ior,
           py::arg("absorb") = m0.absorb)
      .def_readwrite("color", &MaterialDesc::color)
      .def_readwrite("texture", &MaterialDesc::texture)
      .def_readwrite("uv_scale", &MaterialDesc::uv_scale)
      .def_readwrite("uv_offset", &MaterialDesc::uv_offset)
      .def_readwrite("diffuse", &MaterialDesc::diffuse)
      .def_readwrite("specular", &MaterialDesc::specular)
      .def_readwrite("shininess", &MaterialDesc::shininess)
      .def_readwrite("reflect", &MaterialDesc::reflect)
      .def_readwrite("ior", &MaterialDesc::ior, "0: opaque; >= 1: a dielectric")
      .def_readwrite("absorb", &MaterialDesc::absorb);

  const PointLight p0;
  py::class_<PointLight>(m, "PointLight", "A point light; radius > 0 makes it a visible sphere.")
      .def(py::init([](glm::dvec3 position, glm::dvec3 color, double intensity, double linear, double quadratic,
                       double radius) { return PointLight{position, color, intensity, linear, quadratic, radius}; }),
           py::arg("position") = p0.position, py::arg("color") = p0.color, py::arg("intensity") = p0.intensity,
           py::arg("linear") = p0.linear, py::arg("quadratic") = p0.quadratic, py::arg("radius") = p0.radius)
      .def_readwrite("position", &PointLight::position)
      .def_readwrite("color", &PointLight::color)
      .def_readwrite("intensity", &PointLight::intensity)
      .def_readwrite("linear", &PointLight::linear)
      .def_readwrite("quadratic", &PointLight::quadratic)
      .def_readwrite("radius", &PointLight::radius);

  const DirectionalLight d0;
  py::class_<DirectionalLight>(m, "DirectionalLight", "A light from a direction (any non-zero length).")
      .def(py::init([](glm::dvec3 direction, glm::dvec3 color, double intensity) {
             return DirectionalLight{direction, color, intensity};
           }),
           py::arg("direction") = d0.direction, py::arg("color") = d0.color, py::arg("intensity") = d0.intensity)
      .def_readwrite("direction", &DirectionalLight::direction)
      .def_readwrite("color", &DirectionalLight::color)
      .def_readwrite("intensity", &DirectionalLight::intensity);

  const ImageSettings i0;
  py::class_<ImageSettings>(m, "ImageSettings", "The image a scene asks for: size, samples per pixel, depth.")
      .def(py::init([](int width, int height, int spp, int max_depth) {
             return ImageSettings{width, height, spp, max_depth};
           }),
           py::arg("width") = i0.width, py::arg("height") = i0.height, py::arg("spp") = i0.spp,
           py::arg("max_depth") = i0.max_depth)
      .def_readwrite("width", &ImageSettings::width)
      .def_readwrite("height", &ImageSettings::height)
      .def_readwrite("spp", &ImageSettings::spp)
      .def_readwrite("max_depth", &ImageSettings::max_depth);
}

LightDesc light_of(py::handle light) {
  if (py::isinstance<PointLight>(light)) return light.cast<PointLight>();
  if (py::isinstance<DirectionalLight>(light)) return light.cast<DirectionalLight>();
  throw py::type_error("a light is a prism.PointLight or a prism.DirectionalLight");
}

void bind_edits(py::class_<SceneHandle, std::shared_ptr<SceneHandle>>& c) {
  using S = SceneHandle;
  c.def("set_camera", [](S& s, const CameraDesc& camera) { edit(s, [&](LiveScene& l) { l.set_camera(camera); }); },
        py::arg("camera"))
      .def("set_image", [](S& s, const ImageSettings& image) { edit(s, [&](LiveScene& l) { l.set_image(image); }); },
           py::arg("image"))
      .def("set_background", [](S& s, glm::dvec3 color) { edit(s, [&](LiveScene& l) { l.set_background(color); }); },
           py::arg("color"))
      .def("set_ambient", [](S& s, glm::dvec3 color) { edit(s, [&](LiveScene& l) { l.set_ambient(color); }); },
           py::arg("color"))
      .def("set_shadow_ambient",
           [](S& s, glm::dvec3 color) { edit(s, [&](LiveScene& l) { l.set_shadow_ambient(color); }); },
           py::arg("color"))
      .def("add_texture",
           [](S& s, const std::string& name, const std::filesystem::path& file, bool srgb) {
             edit(s, [&](LiveScene& l) { l.add_texture(name, file, srgb); });
           },
           py::arg("name"), py::arg("file"), py::arg("srgb") = true)
      .def("set_material",
           [](S& s, const std::string& name, const MaterialDesc& material) {
             edit(s, [&](LiveScene& l) { l.set_material(name, material); });
           },
           py::arg("name"), py::arg("material"), "Adds the material, or replaces the one of that name.")
      .def("add_object",
           [](S& s, const std::string& type, const std::string& material, std::optional<Rotation> rotation,
              const py::kwargs& fields) {
             const Params params = params_of(fields);
             return edit(s, [&](LiveScene& l) { return l.add_object(type, params, material, rotation).value; });
           },
           py::arg("type"), py::arg("material") = "", py::arg("rotation") = py::none(),
           R"(Adds an object of any primitive type; its fields are keyword arguments, as in a scene file:
add_object("sphere", center=(0, 1, 0), radius=1, material="red"). Returns its id.)")
      .def("update_object",
           [](S& s, uint64_t id, const py::kwargs& fields) {
             const Params params = params_of(fields);
             edit(s, [&](LiveScene& l) { l.update_object({id}, params); });
           },
           py::arg("id"), "Changes some fields of an object (the others keep their values).")
      .def("move_object",
           [](S& s, uint64_t id, glm::dvec3 center) { edit(s, [&](LiveScene& l) { l.move_object({id}, center); }); },
           py::arg("id"), py::arg("center"))
      .def("rotate_object",
           [](S& s, uint64_t id, std::optional<Rotation> rotation) {
             edit(s, [&](LiveScene& l) { l.rotate_object({id}, rotation); });
           },
           py::arg("id"), py::arg("rotation"), "None removes the rotation.")
      .def("set_object_material",
           [](S& s, uint64_t id, const std::string& material) {
             edit(s, [&](LiveScene& l) { l.set_object_material({id}, material); });
           },
           py::arg("id"), py::arg("material"))
      .def("remove_object", [](S& s, uint64_t id) { edit(s, [&](LiveScene& l) { l.remove_object({id}); }); },
           py::arg("id"))
      .def("add_light",
           [](S& s, py::handle light) {
             const LightDesc desc = light_of(light);
             return edit(s, [&](LiveScene& l) { return l.add_light(desc).value; });
           },
           py::arg("light"), "Adds a PointLight or DirectionalLight; returns its id.")
      .def("update_light",
           [](S& s, uint64_t id, py::handle light) {
             const LightDesc desc = light_of(light);
             edit(s, [&](LiveScene& l) { l.update_light({id}, desc); });
           },
           py::arg("id"), py::arg("light"), "Replaces the light `id` with `light` (its id stays).")
      .def("remove_light", [](S& s, uint64_t id) { edit(s, [&](LiveScene& l) { l.remove_light({id}); }); },
           py::arg("id"));
}

void bind_reads(py::class_<SceneHandle, std::shared_ptr<SceneHandle>>& c) {
  using S = SceneHandle;
  c.def_property_readonly("object_count", [](const S& s) { return s.live.object_count(); })
      .def_property_readonly("light_count", [](const S& s) { return s.live.scene().lights.size(); })
      .def_property_readonly("image", [](const S& s) { return s.live.scene().image; },
                             "The scene's ImageSettings (a copy: change them with set_image).")
      .def("object_index", [](const S& s, uint64_t id) { return s.live.object_index({id}); }, py::arg("id"),
           "The object's index in the scene, which is its value in the `id` AOV; -1 once removed.")
      .def("object_at", [](const S& s, size_t index) { return scene_call("", [&] { return s.live.object_at(index).value; }); },
           py::arg("index"), "The id of the object at `index` (e.g. of a loaded scene).")
      .def("light_at", [](const S& s, size_t index) { return scene_call("", [&] { return s.live.light_at(index).value; }); },
           py::arg("index"), "The id of the light at `index`.")
      .def("to_json", [](const S& s) { return s.live.to_json(); }, "The scene as a scene file's text.")
      .def("to_dict", [](const S& s) { return py::module_::import("json").attr("loads")(s.live.to_json()); },
           "The scene as a dict that load_scene takes back.")
      .def("save", [](const S& s, const std::filesystem::path& file) { s.live.save(file); }, py::arg("file"),
           "Writes the scene file atomically.");
}

}  // namespace

void bind_scene(py::module_& m) {
  bind_values(m);
  py::class_<SceneHandle, std::shared_ptr<SceneHandle>> c(m, "Scene", R"(A scene held in memory and edited live.

Made by Engine.load_scene (a file or a dict) or Engine.new_scene. Every edit
goes through the scene loader's checks: a refused edit raises SceneError and
leaves the scene as it was. Objects and lights have stable integer ids.
A renderer of this scene sends its backend only what changed since it last
rendered (see Renderer.counters).)");
  bind_edits(c);
  bind_reads(c);
}

}  // namespace prism::python
