// prism.Renderer: one backend rendering one scene into NumPy arrays, and
// tracing NumPy rays.
#include <cmath>

#include "bindings.hpp"
#include "interrupt.hpp"
#include "prism/ray_csv.hpp"

namespace prism::python {

namespace {

struct RendererHandle {
  std::shared_ptr<Engine> engine;
  std::shared_ptr<SceneHandle> scene;
  std::unique_ptr<Renderer> renderer;  // declared last: gone before the scene and the engine
  bool busy = false;                   // read and written with the GIL held only
};

// One render: its arrays take over the Image's buffers.
struct Frame {
  py::array_t<float> rgb;
  py::object id = py::none(), path = py::none();
  py::object depth = py::none(), normal = py::none(), albedo = py::none();
};

struct Hits {
  py::array_t<double> t;
  py::array_t<int32_t> id;
  py::array_t<double> normal;
};

// Marks the renderer and its scene busy for one call (with the GIL held).
class InFlight {
 public:
  explicit InFlight(RendererHandle& r) : r_(r) {
    if (r_.busy) throw std::runtime_error("this renderer is already rendering on another thread");
    r_.busy = true;
    ++r_.scene->renders_in_flight;
  }
  ~InFlight() {
    r_.busy = false;
    --r_.scene->renders_in_flight;
  }
  InFlight(const InFlight&) = delete;
  InFlight& operator=(const InFlight&) = delete;

 private:
  RendererHandle& r_;
};

RenderOptions options_of(std::optional<int> width, std::optional<int> height, std::optional<int> spp,
                         std::optional<int> max_depth, const std::vector<std::string>& aovs) {
  RenderOptions options{width, height, spp, max_depth};
  for (const std::string& aov : aovs) {
    if (aov == "id") options.aov_id = true;
    else if (aov == "path") options.aov_path = true;
    else if (aov == "depth") options.aov_depth = true;
    else if (aov == "normal") options.aov_normal = true;
    else if (aov == "albedo") options.aov_albedo = true;
    else throw py::value_error("aovs: unknown channel '" + aov + "' (expected id, path, depth, normal or albedo)");
  }
  return options;
}

Frame render(RendererHandle& r, std::optional<int> width, std::optional<int> height, std::optional<int> spp,
             std::optional<int> max_depth, const std::vector<std::string>& aovs) {
  const RenderOptions options = options_of(width, height, spp, max_depth, aovs);
  InFlight in_flight(r);
  Image image = interruptible([&] { return r.renderer->render(r.scene->live, options); });
  const py::ssize_t h = image.height, w = image.width;
  Frame frame{take_as_array(std::move(image.rgb), {h, w, 3})};
  if (options.aov_id) frame.id = take_as_array(std::move(image.id), {h, w});
  if (options.aov_path) frame.path = take_as_array(std::move(image.path), {h, w});
  if (options.aov_depth) frame.depth = take_as_array(std::move(image.depth), {h, w});
  if (options.aov_normal) frame.normal = take_as_array(std::move(image.normal), {h, w, 3});
  if (options.aov_albedo) frame.albedo = take_as_array(std::move(image.albedo), {h, w, 3});
  return frame;
}

using Rays = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<TraceQuery> queries_of(const Rays& origins, const Rays& directions, const Rays& tmin) {
  if (origins.ndim() != 2 || origins.shape(1) != 3) throw py::value_error("origins: expected an array of shape (N, 3)");
  const py::ssize_t n = origins.shape(0);
  if (directions.ndim() != 2 || directions.shape(0) != n || directions.shape(1) != 3)
    throw py::value_error("directions: expected an array of shape (N, 3), N as for origins");
  if (!(tmin.ndim() == 0 || (tmin.ndim() == 1 && tmin.shape(0) == n)))
    throw py::value_error("tmin: expected a number or an array of shape (N,)");
  const auto o = origins.unchecked<2>();
  const auto d = directions.unchecked<2>();
  const double* t = tmin.data();
  std::vector<TraceQuery> queries;
  queries.reserve(size_t(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    const std::string where = "rays[" + std::to_string(i) + "]";
    const double ti = tmin.ndim() == 0 ? t[0] : t[i];
    const glm::dvec3 origin(o(i, 0), o(i, 1), o(i, 2)), direction(d(i, 0), d(i, 1), d(i, 2));
    const auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!std::isfinite(ti) || !finite(origin) || !finite(direction))
      throw py::value_error(where + ": not a finite number");
    queries.push_back(make_trace_query(origin, direction, ti, where));
  }
  return queries;
}

Hits trace(RendererHandle& r, const Rays& origins, const Rays& directions, const Rays& tmin) {
  const std::vector<TraceQuery> queries = queries_of(origins, directions, tmin);
  InFlight in_flight(r);
  const std::vector<TraceResult> results = interruptible([&] { return r.renderer->trace(r.scene->live, queries); });
  const py::ssize_t n = py::ssize_t(results.size());
  Hits hits{py::array_t<double>(n), py::array_t<int32_t>(n), py::array_t<double>({n, py::ssize_t(3)})};
  auto t = hits.t.mutable_unchecked<1>();
  auto id = hits.id.mutable_unchecked<1>();
  auto normal = hits.normal.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    t(i) = results[size_t(i)].t;
    id(i) = results[size_t(i)].id;
    for (int c = 0; c < 3; ++c) normal(i, c) = results[size_t(i)].normal[c];
  }
  return hits;
}

py::dict stats_of(const BackendStats& s) {
  py::dict d;
  d["kernel_features"] = s.kernel_features;
  d["rays"] = s.rays;
  d["rays_by_kind"] = s.rays_by_kind;
  d["ms"] = s.ms;
  d["counters"] = s.counters;
  d["info"] = s.info;
  return d;
}

std::shared_ptr<RendererHandle> make_renderer(const std::shared_ptr<Engine>& engine,
                                              const std::shared_ptr<SceneHandle>& scene, const std::string& backend) {
  if (scene->engine != engine) throw py::value_error("the scene was made by another Engine");
  std::unique_ptr<Renderer> renderer;
  {
    py::gil_scoped_release release;  // a GPU backend takes a while to start
    renderer = std::make_unique<Renderer>(*engine, backend);
  }
  return std::make_shared<RendererHandle>(RendererHandle{engine, scene, std::move(renderer)});
}

void bind_results(py::module_& m) {
  py::class_<Frame>(m, "Frame", "One rendered image: NumPy arrays, row 0 at the top.")
      .def_readonly("rgb", &Frame::rgb, "float32, shape (height, width, 3): linear RGB.")
      .def_readonly("id", &Frame::id,
                    "float32, shape (height, width): the object seen in each pixel (its index in the scene; -1 "
                    "background, -2-k light k's sphere); None unless asked for.")
      .def_readonly("path", &Frame::path,
                    "float32, shape (height, width): each pixel's path signature (sample 0), which compare() "
                    "splits stable pixels from edges with; None unless asked for.")
      .def_readonly("depth", &Frame::depth,
                    "float32, shape (height, width): the t of sample 0's first hit; inf on a miss; None unless "
                    "asked for.")
      .def_readonly("normal", &Frame::normal,
                    "float32, shape (height, width, 3): the first hit's outward unit normal; 0 on a miss; None "
                    "unless asked for.")
      .def_readonly("albedo", &Frame::albedo,
                    "float32, shape (height, width, 3): the first hit's surface colour (material colour times "
                    "texture; a light sphere's colour); 0 on a miss; None unless asked for.");

  py::class_<Hits>(m, "Hits", "The closest hit of each ray, as `prism trace` reports it.")
      .def_readonly("t", &Hits::t, "float64, shape (N,): the distance along the unit direction; inf on a miss.")
      .def_readonly("id", &Hits::id, "int32, shape (N,): the object's index; -1 a miss, -2-k light k's sphere.")
      .def_readonly("normal", &Hits::normal, "float64, shape (N, 3): the outward unit normal; 0 on a miss.");

  py::class_<UpdateCounters>(m, "UpdateCounters", "What a renderer's backend did since the renderer was made.")
      .def_readonly("prepares", &UpdateCounters::prepares, "Full preparations (first render, another scene).")
      .def_readonly("updates", &UpdateCounters::updates, "Incremental updates after edits.")
      .def_readonly("objects_uploaded", &UpdateCounters::objects_uploaded, "Object records read or sent again.")
      .def_readonly("bvh_builds", &UpdateCounters::bvh_builds)
      .def_readonly("bvh_refits", &UpdateCounters::bvh_refits)
      .def_readonly("kernel_builds", &UpdateCounters::kernel_builds, "GPU kernels generated and built.")
      .def("__repr__", [](const UpdateCounters& c) {
        return "UpdateCounters(prepares=" + std::to_string(c.prepares) + ", updates=" + std::to_string(c.updates) +
               ", objects_uploaded=" + std::to_string(c.objects_uploaded) +
               ", bvh_builds=" + std::to_string(c.bvh_builds) + ", bvh_refits=" + std::to_string(c.bvh_refits) +
               ", kernel_builds=" + std::to_string(c.kernel_builds) + ")";
      });
}

}  // namespace

void bind_renderer(py::module_& m) {
  bind_results(m);
  py::class_<RendererHandle, std::shared_ptr<RendererHandle>>(m, "Renderer", R"(One backend rendering one scene.

Made by Engine.renderer(scene, backend). Each call first brings the backend
up to date with the scene's edits since the last call, sending only what
changed. The GIL is released while the backend works, and Ctrl-C stops it
between tiles with KeyboardInterrupt; the renderer stays usable.)")
      .def_property_readonly("backend", [](const RendererHandle& r) { return r.renderer->backend_name(); },
                             "The backend's name (\"auto\" resolved).")
      .def_property_readonly("scene", [](const RendererHandle& r) { return r.scene; })
      .def("render", &render, py::kw_only(), py::arg("width") = py::none(), py::arg("height") = py::none(),
           py::arg("spp") = py::none(), py::arg("max_depth") = py::none(),
           py::arg("aovs") = std::vector<std::string>{},
           R"(Renders the scene with its camera; returns a Frame of NumPy arrays.

width, height, spp, max_depth: override the scene's image settings for this
render (None: the scene's). aovs: any of "id", "path", "depth", "normal" and
"albedo", for the Frame's arrays of those names. The pixels are the ones `prism render` writes to an EXR, bit for
bit; the arrays take over the renderer's buffers without copying them.
Raises ValueError for an override out of range, KeyboardInterrupt on Ctrl-C,
RenderError when the backend fails.)")
      .def("trace", &trace, py::arg("origins"), py::arg("directions"), py::arg("tmin") = 0.0,
           R"(The closest hit of each ray with t > tmin, light spheres included (`prism trace`).

origins, directions: arrays of shape (N, 3) (directions of any non-zero
length, normalized here as `prism trace` does); tmin: a number or shape (N,).
Returns Hits (t, id, normal).)")
      .def("counters", [](const RendererHandle& r) { return r.renderer->counters(); },
           "The backend's update counters: prepares, updates, objects_uploaded, bvh_builds, bvh_refits, kernel_builds.")
      .def("stats", [](const RendererHandle& r) { return stats_of(r.renderer->stats()); },
           "The backend's full statistics (`prism render --stats`): rays, times, counters, info.");

  auto engine = py::reinterpret_borrow<py::class_<Engine, std::shared_ptr<Engine>>>(m.attr("Engine"));
  engine.def("renderer", &make_renderer, py::arg("scene"), py::arg("backend") = "auto",
             R"(A Renderer of `scene` on `backend`: a name from backends(), or "auto" (the fastest that runs here).

Raises ValueError for an unknown name, RenderError when the backend cannot run here.)");
}

}  // namespace prism::python
