// What the parts of the Python module share: conversions between glm vectors
// and Python sequences, NumPy arrays that own a C++ vector, prism.SceneError,
// and the handles that keep an Engine alive for as long as a scene or a
// renderer made from it lives.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prism/api.hpp"

namespace pybind11::detail {

// glm::dvec2 / dvec3 from any sequence of that many numbers (a tuple, a
// list, a NumPy array); to Python as a tuple.
template <class Vec>
bool load_glm_vector(handle source, Vec& value) {
  if (!source || PyUnicode_Check(source.ptr()) || !PySequence_Check(source.ptr())) return false;
  const auto items = reinterpret_borrow<sequence>(source);
  if (items.size() != size_t(Vec::length())) return false;
  for (int i = 0; i < Vec::length(); ++i) {
    const object item = items[size_t(i)];
    if (!PyNumber_Check(item.ptr())) return false;
    value[i] = PyFloat_AsDouble(item.ptr());
    if (PyErr_Occurred()) {
      PyErr_Clear();
      return false;
    }
  }
  return true;
}

template <class Vec>
handle cast_glm_vector(const Vec& v) {
  tuple out(size_t(Vec::length()));
  for (int i = 0; i < Vec::length(); ++i) out[size_t(i)] = float_(v[i]);
  return out.release();
}

template <>
struct type_caster<glm::dvec3> {
  PYBIND11_TYPE_CASTER(glm::dvec3, const_name("tuple[float, float, float]"));
  bool load(handle source, bool) { return load_glm_vector(source, value); }
  static handle cast(const glm::dvec3& v, return_value_policy, handle) { return cast_glm_vector(v); }
};
template <>
struct type_caster<glm::dvec2> {
  PYBIND11_TYPE_CASTER(glm::dvec2, const_name("tuple[float, float]"));
  bool load(handle source, bool) { return load_glm_vector(source, value); }
  static handle cast(const glm::dvec2& v, return_value_policy, handle) { return cast_glm_vector(v); }
};

}  // namespace pybind11::detail

namespace prism::python {

namespace py = pybind11;

// A LiveScene with the Engine it was made from.
struct SceneHandle {
  std::shared_ptr<Engine> engine;
  LiveScene live;
  int renders_in_flight = 0;  // read and written with the GIL held only

  // RuntimeError while a renderer renders this scene on another thread (the
  // library forbids edits during a render; Python users get a message, not a crash).
  void check_editable() const;
};

// Raises prism.SceneError for a loader or API message ("SOURCE: PATH: what"):
// its `path` attribute is PATH (a JSON path, or an API call such as
// "move_object(#3)"), `source` is SOURCE (a file name, "<dict>", or "").
[[noreturn]] void raise_scene_error(const std::string& message, const std::string& source);

// Issues each of the loaded scene's warnings (prism/scene_loader.hpp: no
// light, 0-255 colours, objects behind the camera) as warnings.warn(message,
// prism.SceneWarning), attributed to the caller's line. A filter that turns
// them into errors raises the warning (py::error_already_set).
void warn_about_scene(const Scene& scene);

// Runs `edit`, turning an InputError into prism.SceneError.
template <class Edit>
auto scene_call(const std::string& source, Edit&& edit) -> decltype(edit()) {
  try {
    return edit();
  } catch (const InputError& e) {
    raise_scene_error(e.what(), source);
  }
}

// A float32 NumPy array of `shape` that takes over `values` (no copy).
py::array_t<float> take_as_array(std::vector<float>&& values, const std::vector<py::ssize_t>& shape);

void bind_errors(py::module_& m);
void bind_engine(py::module_& m);
void bind_scene(py::module_& m);
void bind_renderer(py::module_& m);
void bind_compare(py::module_& m);

}  // namespace prism::python
