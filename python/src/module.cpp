// The `prism` Python module (prism._prism; prism/__init__.py re-exports it).
#include "bindings.hpp"

#include "prism/errors.hpp"
#include "prism/scene.hpp"

namespace prism::python {

namespace {

// Set once at import. Never destroyed: a static py::object would be released
// after the interpreter has finalized.
py::object& scene_error_type() {
  static auto* type = new py::object();
  return *type;
}

py::object& scene_warning_type() {
  static auto* type = new py::object();
  return *type;
}

}  // namespace

void warn_about_scene(const Scene& scene) {
  for (const std::string& warning : scene.warnings)
    if (PyErr_WarnEx(scene_warning_type().ptr(), warning.c_str(), 1) != 0) throw py::error_already_set();
}

void raise_scene_error(const std::string& message, const std::string& source) {
  std::string rest = message;
  const std::string prefix = source + ": ";
  if (!source.empty() && rest.rfind(prefix, 0) == 0) rest.erase(0, prefix.size());
  const size_t colon = rest.find(": ");
  std::string path = colon == std::string::npos ? "" : rest.substr(0, colon);
  if (path == "(top level)") path.clear();
  py::object error = scene_error_type()(message);
  error.attr("path") = path;
  error.attr("source") = source;
  PyErr_SetObject(scene_error_type().ptr(), error.ptr());
  throw py::error_already_set();
}

void SceneHandle::check_editable() const {
  if (renders_in_flight > 0)
    throw std::runtime_error("the scene is being rendered on another thread; edit it when the render has returned");
}

py::array_t<float> take_as_array(std::vector<float>&& values, const std::vector<py::ssize_t>& shape) {
  auto* owned = new std::vector<float>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>(shape, owned->data(), owner);
}

void bind_errors(py::module_& m) {
  scene_error_type() = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("prism.SceneError",
                                "A scene, or an edit of one, that the scene loader refuses.\n\n"
                                "str(error) is the loader's message. Attributes: `path`, the JSON path of\n"
                                "the offending value ('objects[0].raduis'), or the API call for an edit\n"
                                "('add_object(\"sphere\").radius'), '' when none; `source`, the scene file's\n"
                                "name, '<dict>' for a dict, '' for an edit.",
                                PyExc_ValueError, nullptr));
  m.attr("SceneError") = scene_error_type();
  scene_warning_type() = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("prism.SceneWarning",
                                "A scene that loads but looks wrong, issued by Engine.load_scene through\n"
                                "warnings.warn: no light and no ambient, colours above 1 that look like\n"
                                "0-255 values, objects entirely behind the camera (the warnings `prism render`\n"
                                "prints). str(warning) is \"SOURCE: PATH: what\", as the command line says it.",
                                PyExc_UserWarning, nullptr));
  m.attr("SceneWarning") = scene_warning_type();
  static py::exception<RuntimeError> render_error(m, "RenderError", PyExc_RuntimeError);
  render_error.doc() = "A failure at run time: a backend that cannot start here, a device lost, a file not written.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const RuntimeError& e) {
      PyErr_SetString(render_error.ptr(), e.what());
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace prism::python

PYBIND11_MODULE(_prism, m) {
  using namespace prism::python;
  m.doc() = "Prism, a ray tracer with interchangeable backends: scenes, renders into NumPy arrays, conformance metrics.";
  // Types are named prism.X (in signatures, help() and tracebacks), as the package re-exports them.
  const py::object module_name = m.attr("__name__");
  m.attr("__name__") = "prism";
  bind_errors(m);
  bind_engine(m);
  bind_scene(m);
  bind_renderer(m);
  bind_compare(m);
  m.attr("__name__") = module_name;
}
