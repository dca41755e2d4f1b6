// prism.Engine: the plugins, the backends that can run here, scenes and renderers.
#include <algorithm>

#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "prism/registry.hpp"

namespace prism::python {

namespace {

// One backend as `prism list` reports it.
struct BackendInfo {
  std::string name;
  bool available = false;
  std::string reason;  // what it runs on when available, why not otherwise
  std::string version;
  std::string path;
};

std::vector<BackendInfo> backends_of(Engine& engine) {
  std::vector<BackendInfo> infos;
  for (const PluginReport& report : engine.registry().scan_all()) {
    if (report.kind != "backend") continue;
    const bool loaded = report.error.empty();
    infos.push_back({report.name, loaded && report.usable, loaded ? report.detail : "failed to load: " + report.error,
                     report.version, report.path.string()});
  }
  return infos;
}

// A Python value of a scene dict as JSON; `path` names it in errors as the
// loader would ("objects[2].center").
nlohmann::ordered_json json_of(py::handle value, const std::string& path) {
  const auto fail = [&](const std::string& what) {
    raise_scene_error("<dict>: " + (path.empty() ? std::string("(top level)") : path) + ": " + what, "<dict>");
  };
  if (value.is_none()) return nullptr;
  if (PyBool_Check(value.ptr())) return value.cast<bool>();
  if (PyLong_Check(value.ptr())) {
    int overflow = 0;
    const long long whole = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow == 0) return whole;
    return PyLong_AsDouble(value.ptr());  // the loader reports it as out of range
  }
  if (PyFloat_Check(value.ptr())) {
    const double number = value.cast<double>();
    if (!std::isfinite(number)) fail("must be a finite number");
    return number;
  }
  if (PyUnicode_Check(value.ptr())) return value.cast<std::string>();
  if (PyDict_Check(value.ptr())) {
    nlohmann::ordered_json object = nlohmann::ordered_json::object();
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!PyUnicode_Check(key.ptr())) fail("keys must be strings, got " + py::repr(key).cast<std::string>());
      const std::string name = key.cast<std::string>();
      object[name] = json_of(item, path.empty() ? name : path + "." + name);
    }
    return object;
  }
  if (PyList_Check(value.ptr()) || PyTuple_Check(value.ptr())) {
    nlohmann::ordered_json array = nlohmann::ordered_json::array();
    size_t index = 0;
    for (const py::handle item : py::reinterpret_borrow<py::sequence>(value))
      array.push_back(json_of(item, path + "[" + std::to_string(index++) + "]"));
    return array;
  }
  if (py::hasattr(value, "tolist")) return json_of(value.attr("tolist")(), path);  // NumPy arrays and scalars
  fail("a " + py::type::of(value).attr("__name__").cast<std::string>() +
       " cannot be in a scene (dict, list, tuple, str, int, float, bool, None or a NumPy array)");
  return nullptr;
}

std::shared_ptr<SceneHandle> read_scene(const std::shared_ptr<Engine>& engine, py::handle source,
                                        const std::optional<std::filesystem::path>& base_dir) {
  if (PyDict_Check(source.ptr())) {
    const std::string text = json_of(source, "").dump();
    const std::filesystem::path folder = base_dir.value_or(std::filesystem::current_path());
    return scene_call("<dict>", [&] {
      return std::make_shared<SceneHandle>(SceneHandle{engine, LiveScene::load_json(*engine, text, folder, "<dict>")});
    });
  }
  const auto file = source.cast<std::filesystem::path>();
  return scene_call(file.string(),
                    [&] { return std::make_shared<SceneHandle>(SceneHandle{engine, LiveScene::load(*engine, file)}); });
}

std::shared_ptr<SceneHandle> load_scene(const std::shared_ptr<Engine>& engine, py::handle source,
                                        const std::optional<std::filesystem::path>& base_dir) {
  std::shared_ptr<SceneHandle> scene = read_scene(engine, source, base_dir);
  warn_about_scene(scene->live.scene());
  return scene;
}

}  // namespace

void bind_engine(py::module_& m) {
  py::class_<BackendInfo>(m, "BackendInfo", "A backend found in the plugin path, as `prism list` reports it.")
      .def_readonly("name", &BackendInfo::name, "The name renderer() and `prism -b` take.")
      .def_readonly("available", &BackendInfo::available, "Whether it can run on this machine.")
      .def_readonly("reason", &BackendInfo::reason,
                    "What it runs on (the device, the library) when available; why not otherwise.")
      .def_readonly("version", &BackendInfo::version)
      .def_readonly("path", &BackendInfo::path, "The plugin file.")
      .def("__repr__", [](const BackendInfo& b) {
        return "BackendInfo(name=" + py::repr(py::str(b.name)).cast<std::string>() +
               ", available=" + (b.available ? "True" : "False") +
               ", reason=" + py::repr(py::str(b.reason)).cast<std::string>() + ")";
      });

  py::class_<Engine, std::shared_ptr<Engine>>(m, "Engine", R"(The plugin registry: primitive types and backends.

Engine() searches PRISM_PLUGIN_PATH, then the plugins installed beside the
core library; Engine(plugin_path=[...]) searches only those folders. One
Engine serves any number of scenes and renderers.)")
      .def(py::init([](std::optional<std::vector<std::filesystem::path>> plugin_path) {
             return plugin_path ? std::make_shared<Engine>(*plugin_path) : std::make_shared<Engine>();
           }),
           py::arg("plugin_path") = py::none())
      .def("backends", &backends_of, R"(Every backend found, with whether it can run here and why (as `prism list`).)")
      .def("primitive_types", &Engine::primitive_types, "The primitive plugins found (sphere, plane, torus, ...).")
      .def("auto_backend", &Engine::auto_backend, R"(The backend "auto" picks: the fastest that can run here.)")
      .def("load_scene", &load_scene, py::arg("source"), py::arg("base_dir") = py::none(),
           R"doc(A scene from a scene file (a path) or from a dict with the scene format's keys.

The dict goes through the scene loader exactly as a file does: the same
checks and the same messages. Relative texture paths in a dict resolve
against `base_dir` (default: the current folder); in a file, against the
file's folder. Raises SceneError, whose `path` is the JSON path of what is
wrong: SceneError("<dict>: objects[0].raduis: unknown key (did you mean 'radius'?)").
A scene that loads but looks wrong (no light, 0-255 colours, objects behind
the camera) is returned, with one warnings.warn(message, SceneWarning) each.)doc")
      .def(
          "new_scene",
          [](const std::shared_ptr<Engine>& engine) {
            return std::make_shared<SceneHandle>(SceneHandle{engine, LiveScene(*engine)});
          },
          "An empty scene: the default camera, 640x360, 1 spp, depth 5, black background.");
}

}  // namespace prism::python
